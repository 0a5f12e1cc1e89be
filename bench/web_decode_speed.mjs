// SPDX-License-Identifier: Apache-2.0
// The WebAssembly decoder's speed on one file, as `animc bench IN.ams` times the native one
// from memory: open the stream, then every frame in order, R times; prints JSON with the
// median seconds and millions of vertices a second. bench_web.py runs it.
//   usage: node bench/web_decode_speed.mjs IN.ams [RUNS]
import { readFileSync } from 'node:fs';
import { AnimStream } from '../web/animcompress.mjs';

const [path, runsArgument] = process.argv.slice(2);
const runs = Number(runsArgument ?? 5);
const bytes = readFileSync(path);
const seconds = [];
let vertices = 0, frames = 0;
for (let r = 0; r < runs; ++r) {
  const t0 = performance.now();
  const stream = await AnimStream.open(bytes);
  const out = new Float32Array(3 * stream.vertexCount);
  for (let k = 0; k < stream.frameCount; ++k) stream.frame(k, out);
  seconds.push((performance.now() - t0) / 1000);
  vertices = stream.vertexCount;
  frames = stream.frameCount;
  stream.close();
}
seconds.sort((a, b) => a - b);
const median = seconds[Math.floor(seconds.length / 2)];
console.log(JSON.stringify({ decode_seconds_median: median, decode_mvps: (vertices * frames) / median / 1e6 }));
