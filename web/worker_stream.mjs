// SPDX-License-Identifier: Apache-2.0
// An AnimStream decoded in a Web Worker (decode_worker.mjs), so that a page keeps drawing
// while frames decode. The same figures as AnimStream; frame(k) gives a promise.
//
//   import { WorkerStream } from 'animcompress/worker';
//   const s = await WorkerStream.open(bytes);        // or open(bytes, { partial: true }) again
//   const xyz = await s.frame(k);                    // as more of a stream arrives
const worker_url = new URL('./decode_worker.mjs', import.meta.url);

export class WorkerStream {
  constructor(worker) {
    this.worker = worker;
    this.pending = new Map();
    this.nextId = 0;
    worker.onmessage = ({ data }) => {
      const { resolve, reject } = this.pending.get(data.id);
      this.pending.delete(data.id);
      if (!data.error) return resolve(data.result);
      const error = new Error(data.error.message);
      error.code = data.error.code;
      reject(error);
    };
  }

  // A new worker holding the stream of `bytes` (AnimStream.open's options).
  static async open(bytes, options = {}) {
    const stream = new WorkerStream(new Worker(worker_url, { type: 'module' }));
    try {
      return (await stream.reopen(bytes, options)) ? stream : null;
    } catch (error) {
      stream.close();
      throw error;
    }
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
    this.worker.terminate();
    for (const { reject } of this.pending.values()) reject(new Error('animcompress: the stream is closed'));
    this.pending.clear();
  }

  call(message) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ id, ...message });
    });
  }
}
