// SPDX-License-Identifier: Apache-2.0
// The Web Worker behind WorkerStream (worker_stream.mjs): one AnimStream, decoded off the
// page's thread. Messages: {id, op: 'open', bytes, options} → the stream's figures and
// triangles (null: no whole group yet, or a later open already answered); {id, op: 'frame',
// k} → the frame, transferred; {id, op: 'close'}. A failure answers {id, error: {message,
// code}}.
import { AnimStream } from './animcompress.mjs';

let stream = null;
// Opens may finish out of order (the first one compiles the decoder): one started before the
// stream shown was opened is dropped, so an older, shorter start of a file never replaces it.
let opensStarted = 0, openShown = 0;

function figures(s) {
  const { vertexCount, triangleCount, frameCount, frameRate, groupCount, byteLength, codec } = s;
  return { vertexCount, triangleCount, frameCount, frameRate, groupCount, byteLength, codec, triangles: s.triangles() };
}

async function answer({ op, bytes, options, k }) {
  if (op === 'open') {
    const ticket = ++opensStarted;
    const opened = await AnimStream.open(bytes, options);
    if (!opened) return [null];
    if (ticket < openShown) {
      opened.close();
      return [null];
    }
    openShown = ticket;
    stream?.close();
    stream = opened;
    const f = figures(stream);
    return [f, [f.triangles.buffer]];
  }
  if (op === 'frame') {
    const frame = stream.frame(k);
    return [frame, [frame.buffer]];
  }
  stream?.close();
  stream = null;
  return [null];
}

self.onmessage = async ({ data }) => {
  try {
    const [result, transfer] = await answer(data);
    self.postMessage({ id: data.id, result }, transfer ?? []);
  } catch (error) {
    self.postMessage({ id: data.id, error: { message: error.message, code: error.code } });
  }
};
