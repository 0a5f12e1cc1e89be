// SPDX-License-Identifier: Apache-2.0
// Plays a .glb or .gltf of `animc decode` in three.js (GLTFLoader, AnimationMixer), as a web
// page would, and compares what it shows at every frame's time with the frames of a PC2 of the
// same decode: the morph weights one-hot at the frame, the morphed positions (computed on the
// CPU by three.js) equal to the frame. Prints one JSON object for tests/gltf/gltf_test.sh.
//   usage: NODE_PATH=<folder holding three> node play_three.mjs FILE FRAMES.pc2 RATE
import { createRequire } from 'node:module';
import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';

// three.js's FileLoader, which reads the .gltf's data: URI with fetch(), reports progress with
// the browser's ProgressEvent, which Node lacks.
globalThis.ProgressEvent ??= class extends Event {
  constructor(type, init = {}) {
    super(type);
    Object.assign(this, init);
  }
};

const require = createRequire(import.meta.url);
const threeDir = require.resolve('three').replace(/build[/\\][^/\\]+$/, '');
const THREE = await import(pathToFileURL(threeDir + 'build/three.module.js'));
const { GLTFLoader } = await import(pathToFileURL(threeDir + 'examples/jsm/loaders/GLTFLoader.js'));
const [file, pc2Path, rateText] = process.argv.slice(2);
const rate = Number(rateText);

function readPc2(path) {
  const bytes = readFileSync(path);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const points = view.getInt32(16, true), frames = view.getInt32(28, true);
  const data = new Float32Array(bytes.buffer.slice(bytes.byteOffset + 32, bytes.byteOffset + 32 + 12 * points * frames));
  return { points, frames, frame: (k) => data.subarray(3 * points * k, 3 * points * (k + 1)) };
}

const bytes = readFileSync(file);
const gltf = await new GLTFLoader().parseAsync(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength), '');
let mesh = null;
gltf.scene.traverse((o) => { if (o.isMesh) mesh = o; });
const mixer = new THREE.AnimationMixer(gltf.scene);
mixer.clipAction(gltf.animations[0]).play();
const frames = readPc2(pc2Path);
const position = new THREE.Vector3();
let worst = 0, wrongWeights = 0, scale = 0;
// Each frame at its own time, then halfway through it (the last frame must last 1 / rate too).
for (const offset of [0, 0.5]) {
  for (let k = 0; k < frames.frames; ++k) {
    mixer.setTime((k + offset) / rate);
    const weights = mesh.morphTargetInfluences;
    if (weights[k] !== 1 || weights.reduce((a, b) => a + b, 0) !== 1) ++wrongWeights;
    const expected = frames.frame(k);
    for (let v = 0; v < frames.points; ++v) {
      mesh.getVertexPosition(v, position);
      for (let axis = 0; axis < 3; ++axis) {
        worst = Math.max(worst, Math.abs(position.getComponent(axis) - expected[3 * v + axis]));
        scale = Math.max(scale, Math.abs(expected[3 * v + axis]));
      }
    }
  }
}
console.log(JSON.stringify({
  targets: mesh.morphTargetInfluences.length,
  duration: gltf.animations[0].duration,
  frames_checked: 2 * frames.frames,
  wrong_weights: wrongWeights,
  worst_error: worst,
  largest_coordinate: scale,
}));
