// SPDX-License-Identifier: Apache-2.0
// The WebAssembly decoder against the native one: every golden file (all four codecs) decodes
// to the frames of `animc decode --format pc2`, bit for bit; damaged files throw Errors with
// their code; the limits refuse a file that announces more than they allow; a stream still
// arriving opens as its whole groups.
//   ANIMC=build/animc/animc node --test web/test/
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createHash } from 'node:crypto';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { AnimStream } from '../animcompress.mjs';
import { crc32 } from './crc32.mjs';

const goldenDir = fileURLToPath(new URL('../../tests/golden/', import.meta.url));
const goldens = readdirSync(goldenDir).filter((f) => f.endsWith('.ams')).sort();
const animc = process.env.ANIMC;

function sha256(bytes) {
  return createHash('sha256').update(bytes).digest('hex');
}

// The frames of the native decoder: a PC2 file's floats after its 32-byte header.
function nativeFrames(path) {
  const dir = mkdtempSync(join(tmpdir(), 'animc-web-'));
  try {
    execFileSync(animc, ['decode', path, '-o', join(dir, 'f.pc2'), '--format', 'pc2', '--threads', '1']);
    return readFileSync(join(dir, 'f.pc2')).subarray(32);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

async function allFrames(stream) {
  const floats = 3 * stream.vertexCount;
  const all = new Float32Array(floats * stream.frameCount);
  for (let k = 0; k < stream.frameCount; ++k) stream.frame(k, all.subarray(k * floats, (k + 1) * floats));
  return new Uint8Array(all.buffer);
}

test('every golden file decodes to the native frames, bit for bit', { skip: !animc && 'ANIMC (the animc binary) is not set' }, async () => {
  const codecs = new Set();
  for (const name of goldens) {
    const stream = await AnimStream.open(readFileSync(join(goldenDir, name)));
    codecs.add(stream.codec);
    assert.equal(sha256(await allFrames(stream)), sha256(nativeFrames(join(goldenDir, name))), name);
    stream.close();
  }
  assert.deepEqual([...codecs].sort(), ['affine-octree', 'auto', 'trajectory', 'trajectory2', 'wavelet']);
});

test('random access gives the frames of sequential decoding', async () => {
  const stream = await AnimStream.open(readFileSync(join(goldenDir, 'trajectory.v1.groups.1_2.ams')));
  const sequential = [];
  for (let k = 0; k < stream.frameCount; ++k) sequential.push(stream.frame(k));
  for (const k of [stream.frameCount - 1, 0, Math.floor(stream.frameCount / 2), 1]) assert.deepEqual(stream.frame(k), sequential[k]);
  assert.equal(stream.triangles().length, 3 * stream.triangleCount);
  assert.ok(stream.triangles().every((v) => v < stream.vertexCount));
  assert.throws(() => stream.frame(stream.frameCount), { code: 'invalid' });
  stream.close();
  assert.throws(() => stream.frame(0), { code: 'invalid' });
});

const sample = readFileSync(join(goldenDir, 'affine_octree_default.v1.groups.ams'));

test('a truncated file throws truncated', async () => {
  for (const size of [0, 10, 100, sample.length - 1]) {
    await assert.rejects(AnimStream.open(sample.subarray(0, size)), { code: 'truncated' }, `${size} bytes`);
  }
});

test('a corrupt file throws corrupt, when opened or when its damaged group is reached', async () => {
  const header = Buffer.from(sample);
  header[20] ^= 0x10;  // in HEAD: its CRC fails
  await assert.rejects(AnimStream.open(header), { code: 'corrupt' });
  const lastGroup = Buffer.from(sample);
  lastGroup[sample.length - 300] ^= 0x10;
  const stream = await AnimStream.open(lastGroup);
  assert.throws(() => stream.frame(stream.frameCount - 1), (e) => e.code === 'corrupt' && /CRC/.test(e.message));
  assert.equal(stream.frame(0).length, 3 * stream.vertexCount, 'the other groups still decode');
  const version = Buffer.from(sample);
  version[4] = 9;  // Format_Version
  await assert.rejects(AnimStream.open(version), { code: 'unsupported' });
});

// HEAD (at offset 8): tag, length, then Codec_Id, Codec_Params_Length (one-byte varint here),
// the params and Vertex_Count; its CRC follows the payload.
function withVertexCount(bytes, count) {
  const out = Buffer.from(bytes);
  const length = Number(out.readBigUInt64LE(12));
  const payload = 20;
  const paramsLength = out[payload + 1];
  assert.ok(paramsLength < 128);
  out.writeUInt32LE(count, payload + 2 + paramsLength);
  out.writeUInt32LE(crc32(out.subarray(payload, payload + length)), payload + length);
  return out;
}

test('the limits refuse what a file announces beyond them, before any work', async () => {
  await assert.rejects(AnimStream.open(withVertexCount(sample, 0x7fffffff)), { code: 'limit' });
  await assert.rejects(AnimStream.open(sample, { maxVertices: 10 }), { code: 'limit' });
  await assert.rejects(AnimStream.open(sample, { maxVertices: NaN }), { code: 'invalid' });
  const unlimited = await AnimStream.open(sample, { maxVertices: Infinity, maxVertexFrames: 2 ** 70 });
  assert.equal(unlimited.frame(0).length, 3 * unlimited.vertexCount, 'Infinity: no limit');
  unlimited.close();
  const trajectory = await AnimStream.open(readFileSync(join(goldenDir, 'trajectory.v1.target_kg.1_2.ams')),
    { maxMultiplyAdds: 1000 });
  assert.throws(() => trajectory.frame(0), { code: 'limit' });
});

test('a stream still arriving opens as the frames of its whole groups', async () => {
  const whole = await AnimStream.open(sample);
  assert.ok(whole.groupCount >= 3);
  assert.equal(await AnimStream.open(sample.subarray(0, 200), { partial: true }), null);
  let seen = 0;
  for (let size = 0; size <= sample.length; size += Math.ceil(sample.length / 40)) {
    const part = await AnimStream.open(sample.subarray(0, size), { partial: true });
    if (!part) continue;
    assert.ok(part.frameCount >= seen && part.frameCount < whole.frameCount);
    seen = part.frameCount;
    assert.deepEqual(part.frame(part.frameCount - 1), whole.frame(part.frameCount - 1));
    part.close();
  }
  assert.ok(seen > 0);
  const all = await AnimStream.open(sample, { partial: true });
  assert.equal(all.frameCount, whole.frameCount);
});

test('npm pack makes a package that imports as animcompress', async () => {
  const dir = mkdtempSync(join(tmpdir(), 'animc-pack-'));
  try {
    const webDir = fileURLToPath(new URL('..', import.meta.url));
    const tarball = execFileSync('npm', ['pack', '--silent', '--pack-destination', dir], { cwd: webDir, encoding: 'utf8' }).trim();
    const installed = join(dir, 'node_modules', 'animcompress');
    execFileSync('mkdir', ['-p', installed]);
    execFileSync('tar', ['-xzf', join(dir, tarball), '-C', installed, '--strip-components=1']);
    // A module beside node_modules imports the package by its name, through its "exports".
    writeFileSync(join(dir, 'probe.mjs'), "export { AnimStream } from 'animcompress';\nexport { WorkerStream } from 'animcompress/worker';\n");
    const { AnimStream: Packed, WorkerStream } = await import(join(dir, 'probe.mjs'));
    assert.equal(typeof WorkerStream.open, 'function');
    const stream = await Packed.open(sample);
    assert.equal(stream.frame(0).length, 3 * stream.vertexCount);
    const files = execFileSync('find', ['.', '-type', 'f'], { cwd: installed, encoding: 'utf8' }).split('\n').filter(Boolean).sort();
    assert.deepEqual(files, ['./README.md', './animcompress.mjs', './decode_worker.mjs', './dist/animc.wasm', './package.json',
      './worker_stream.mjs']);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
