// SPDX-License-Identifier: Apache-2.0
// Reconstruction error as vertex colours: the distance of each decoded vertex from the
// original, on the ramp MeshLab's filter uses (vcg's quality ramp): blue at 0, then cyan,
// green and yellow, red at the scale's top and beyond.

// An original sequence in Blender's point cache 2 format: a 32-byte header ("POINTCACHE2\0",
// version, points, start frame, sample rate, samples), then the frames' floats.
export function readPc2(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const magic = new TextDecoder().decode(bytes.subarray(0, 11));
  if (bytes.length < 32 || magic !== 'POINTCACHE2') throw new Error('the original is not a .pc2 file');
  const vertexCount = view.getInt32(16, true);
  const frameCount = view.getInt32(28, true);
  if (vertexCount <= 0 || frameCount <= 0 || 32 + 12 * vertexCount * frameCount !== bytes.length)
    throw new Error('the .pc2 file is truncated or its header is wrong');
  const frames = new Float32Array(3 * vertexCount * frameCount);
  new Uint8Array(frames.buffer).set(bytes.subarray(32));
  return { vertexCount, frameCount, frames };
}

function distances(positions, original, k) {
  const n = positions.length / 3;
  const base = 3 * n * k;
  const d = new Float32Array(n);
  for (let i = 0; i < n; ++i) {
    const dx = positions[3 * i] - original.frames[base + 3 * i];
    const dy = positions[3 * i + 1] - original.frames[base + 3 * i + 1];
    const dz = positions[3 * i + 2] - original.frames[base + 3 * i + 2];
    d[i] = Math.sqrt(dx * dx + dy * dy + dz * dz);
  }
  return d;
}

// The largest vertex error over every frame: the top of the scale, as the filter's default.
export async function largestError(frameOf, original) {
  let top = 0;
  for (let k = 0; k < original.frameCount; ++k) {
    for (const d of distances(await frameOf(k), original, k)) top = Math.max(top, d);
  }
  return top;
}

// RGB in [0, 1] of t in [0, 1]: blue, cyan, green, yellow, red at quarters.
export function ramp(t) {
  const x = Math.min(1, Math.max(0, t)) * 4;
  const stops = [[0, 0, 1], [0, 1, 1], [0, 1, 0], [1, 1, 0], [1, 0, 0]];
  const i = Math.min(3, Math.floor(x));
  const f = x - i;
  return stops[i].map((a, c) => a + (stops[i + 1][c] - a) * f);
}

export function errorColours(positions, original, k, scale) {
  const d = distances(positions, original, k);
  const colours = new Float32Array(3 * d.length);
  for (let i = 0; i < d.length; ++i) colours.set(ramp(scale > 0 ? d[i] / scale : 0), 3 * i);
  return colours;
}
