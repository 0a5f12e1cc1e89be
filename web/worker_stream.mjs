// SPDX-License-Identifier: Apache-2.0
// An AnimStream decoded in a Web Worker (decode_worker.mjs), so that a page keeps drawing
// while frames decode. The same figures as AnimStream; frame(k) gives a promise.
//
//   import { WorkerStream } from 'animcompress/worker';
//   const s = await WorkerStream.open(bytes);        // or open(bytes, { partial: true }) again
//   const xyz = await s.frame(k);                    // as more of a stream arrives
const worker_url = new URL('./decode_worker.mjs', import.meta.url);

function workerError(message, code) {
  const error = new Error(message);
  error.code = code;
  return error;
}

export class WorkerStream {
  constructor(worker) {
    this.worker = worker;
    this.pending = new Map();
    this.nextId = 0;
    worker.onmessage = ({ data }) => {
      const call = this.pending.get(data.id);
      if (!call) return;
      this.pending.delete(data.id);
      if (!data.error) return call.resolve(data.result);
      call.reject(workerError(data.error.message, data.error.code));
    };
    // The worker could not load (its script or the .wasm) or failed outside a call.
    worker.onerror = (event) => {
      event.preventDefault?.();
      this.fail(workerError(`animcompress: the decoding worker failed: ${event.message ?? 'no message'}`, 'io'));
    };
  }

  // A new worker holding the stream of `bytes` (AnimStream.open's options).
  static async open(bytes, options = {}) {
    const stream = new WorkerStream(new Worker(worker_url, { type: 'module' }));
    try {
      if (await stream.reopen(bytes, options)) return stream;
    } catch (error) {
      stream.close();
      throw error;
    }
    stream.close();
    return null;
  }

  // Replaces the stream with that of `bytes` (more of a stream still arriving); false, with
  // the old stream kept, while `partial` bytes hold no whole group.
  async reopen(bytes, options = {}) {
    const figures = await this.call({ op: 'open', bytes, options });
    if (!figures) return false;
    const { triangles, ...rest } = figures;
    Object.assign(this, rest);
    this.indices = triangles;
    return true;
  }

  triangles() {
    return this.indices;
  }

  frame(k) {
    return this.call({ op: 'frame', k });
  }

  close() {
    this.fail(workerError('animcompress: the stream is closed', 'invalid'));
  }

  // Ends the worker: every call waiting, and any made later, fails with `error`.
  fail(error) {
    this.worker?.terminate();
    this.worker = null;
    this.failure = error;
    for (const { reject } of this.pending.values()) reject(error);
    this.pending.clear();
  }

  call(message) {
    if (!this.worker) return Promise.reject(this.failure);
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ id, ...message });
    });
  }
}
