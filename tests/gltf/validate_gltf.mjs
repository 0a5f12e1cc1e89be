// SPDX-License-Identifier: Apache-2.0
// Validates a .glb or .gltf with the Khronos glTF validator and prints one JSON object: the
// counts of errors and warnings, the first messages, and what the asset holds (meshes, morph
// targets, animations), for tests/gltf/gltf_test.sh.
//   usage: NODE_PATH=<folder holding gltf-validator> node validate_gltf.mjs FILE
import { createRequire } from 'node:module';
import { readFileSync } from 'node:fs';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');
const path = process.argv[2];
const bytes = new Uint8Array(readFileSync(path));
const report = await validator.validateBytes(bytes, { maxIssues: 20, externalResourceFunction: () => Promise.reject(new Error('no external resources')) });
const asset = JSON.parse(path.endsWith('.glb') ? jsonChunk(bytes) : new TextDecoder().decode(bytes));
console.log(JSON.stringify({
  errors: report.issues.numErrors,
  warnings: report.issues.numWarnings,
  messages: report.issues.messages.map((m) => `${m.code}: ${m.message} (${m.pointer ?? ''})`),
  meshes: asset.meshes.length,
  targets: asset.meshes[0].primitives[0].targets.length,
  animations: asset.animations.length,
  interpolation: asset.animations[0].samplers[0].interpolation,
  duration: asset.accessors[asset.animations[0].samplers[0].input].max[0],
}));

function jsonChunk(glb) {
  const view = new DataView(glb.buffer, glb.byteOffset, glb.byteLength);
  return new TextDecoder().decode(glb.subarray(20, 20 + view.getUint32(12, true)));
}
