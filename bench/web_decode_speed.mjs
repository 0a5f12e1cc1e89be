// SPDX-License-Identifier: Apache-2.0
// The WebAssembly decoder's speed on one file, as `animc bench IN.ams` times the native one
// from memory: open the stream, then every frame in order, R times after a second of the same
// untimed (V8 first runs WebAssembly from its baseline compiler, and swaps in optimised code
// for hot functions as it runs: steady speed is what a player sees after its first second);
// prints JSON with the
// median seconds and millions of vertices a second, and the SHA-256 of the frames' floats (an
// untimed pass), which bench_web.py compares with the native decoder's.
//   usage: node bench/web_decode_speed.mjs IN.ams [RUNS]
import { createHash } from 'node:crypto';
import { readFileSync } from 'node:fs';
import { AnimStream } from '../web/animcompress.mjs';

const [path, runsArgument] = process.argv.slice(2);
const runs = Number(runsArgument ?? 5);
const bytes = readFileSync(path);
let vertices = 0, frames = 0;

async function decodeAll() {
  const t0 = performance.now();
  const stream = await AnimStream.open(bytes);
  const out = new Float32Array(3 * stream.vertexCount);
  for (let k = 0; k < stream.frameCount; ++k) stream.frame(k, out);
  vertices = stream.vertexCount;
  frames = stream.frameCount;
  stream.close();
  return (performance.now() - t0) / 1000;
}

for (const warmUpEnd = performance.now() + 1000; performance.now() < warmUpEnd;) await decodeAll();
const seconds = [];
for (let r = 0; r < runs; ++r) seconds.push(await decodeAll());
const hash = createHash('sha256');
const stream = await AnimStream.open(bytes);
for (let k = 0; k < stream.frameCount; ++k) hash.update(stream.frame(k));
seconds.sort((a, b) => a - b);
const median = seconds[Math.floor(seconds.length / 2)];
console.log(JSON.stringify({ decode_seconds_median: median, decode_mvps: (vertices * frames) / median / 1e6,
  frames_sha256: hash.digest('hex') }));
