// SPDX-License-Identifier: Apache-2.0
// animcompress for JavaScript: .ams streams decoded by the library's own decoder compiled to
// WebAssembly (dist/animc.wasm, src/animc_web.cpp), in Node ≥ 18 and in browsers.
//
//   import { AnimStream } from 'animcompress';
//   const a = await AnimStream.open(bytes);          // ArrayBuffer or Uint8Array
//   a.vertexCount; a.frameCount; a.frameRate;
//   a.triangles();                                   // Uint32Array, 3 per triangle
//   a.frame(k);                                      // Float32Array, x y z per vertex
//   a.close();
//
// Each open stream has its own WebAssembly instance (its own memory), so a stream that fails
// cannot disturb another; closed streams leave small instances for the next ones to reuse. Errors are Errors with .code: 'truncated', 'corrupt', 'unsupported',
// 'limit' (DecoderLimits) or 'invalid' (a bad argument).

const CODE_NAMES = { 2: 'invalid', 3: 'io', 4: 'bad-input', 5: 'truncated', 6: 'corrupt', 7: 'unsupported', 8: 'limit' };

// DecoderLimits (include/animc/animc.h) in the order animc_open() reads them.
export const LIMIT_NAMES = ['maxVertices', 'maxTriangles', 'maxFrames', 'maxFrameBytes', 'maxVertexFrames',
  'maxOutputBytes', 'maxMultiplyAdds'];

let compiled = null;
// Instances of closed streams, for the next open(): instantiating costs more than decoding a
// small file. Only a few, with little memory each (a WebAssembly memory never shrinks).
const idleInstances = [];
const MAX_IDLE_INSTANCES = 2;
const MAX_IDLE_MEMORY = 64 << 20;

function animError(code, message) {
  const error = new Error(message);
  error.code = code;
  return error;
}

async function wasmBytes(source) {
  if (source instanceof ArrayBuffer || ArrayBuffer.isView(source)) return source;
  const url = source ? new URL(source, import.meta.url) : new URL('./dist/animc.wasm', import.meta.url);
  if (url.protocol === 'file:') {  // Node: fetch() refuses file URLs
    const { readFile } = await import('node:fs/promises');
    return readFile(url);
  }
  const response = await fetch(url);
  if (!response.ok) throw animError('io', `animcompress: cannot load ${url}: HTTP ${response.status}`);
  return response.arrayBuffer();
}

// Where the .wasm comes from when not beside this file (a bundler's asset URL, or its bytes).
// Call before the first open().
export function setWasmSource(source) {
  compiled = wasmBytes(source).then((bytes) => WebAssembly.compile(bytes));
}

// How the decoder ends when it cannot go on: this build has no C++ exceptions, so where the
// library would throw (std::bad_alloc: out of memory) it calls exit(), which arrives here.
class DecoderAbort extends Error {}

// The decoder imports nothing it needs from its host: the standalone build asks for a few
// WASI calls (exit, the environment), answered here as unavailable, and exit as an abort.
function importsFor(module) {
  const imports = {};
  for (const { module: name, name: field } of WebAssembly.Module.imports(module)) {
    imports[name] ??= {};
    imports[name][field] = field === 'proc_exit'
      ? (status) => { throw new DecoderAbort(`exit(${status})`); }
      : () => 52;  // ENOSYS
  }
  return imports;
}

async function instantiate() {
  if (idleInstances.length) return idleInstances.pop();
  if (!compiled) setWasmSource();
  const module = await compiled;
  const instance = await WebAssembly.instantiate(module, importsFor(module));
  instance.exports._initialize?.();
  return instance.exports;
}

function asBytes(bytes) {
  if (bytes instanceof Uint8Array) return bytes;
  if (bytes instanceof ArrayBuffer) return new Uint8Array(bytes);
  if (ArrayBuffer.isView(bytes)) return new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  throw animError('invalid', 'animcompress: open() takes an ArrayBuffer or a Uint8Array');
}

function readString(wasm, pointer) {
  const memory = new Uint8Array(wasm.memory.buffer);
  let end = pointer;
  while (memory[end] !== 0) ++end;
  return new TextDecoder().decode(memory.subarray(pointer, end));
}

function lastError(wasm) {
  const code = wasm.animc_error_code();
  return animError(CODE_NAMES[code] ?? 'corrupt', `animcompress: ${readString(wasm, wasm.animc_error_message() >>> 0)}`);
}

// Runs a call into the decoder: an abort or a trap becomes a 'limit' Error (running out of
// memory is what ends the decoder early) and leaves the instance unusable, never reused.
function guarded(stream, call) {
  if (!stream.wasm) throw animError('invalid', 'animcompress: the stream is closed');
  try {
    return call(stream.wasm);
  } catch (error) {
    if (!(error instanceof WebAssembly.RuntimeError || error instanceof DecoderAbort)) throw error;
    stream.wasm = null;
    throw animError('limit', `animcompress: the decoder stopped, out of WebAssembly memory (${error.message})`);
  }
}

// Memory for `bytes` in the decoder, or a 'limit' Error. Addresses past 2 GiB come back from
// WebAssembly as negative numbers: >>> 0 makes them unsigned.
function allocate(wasm, bytes) {
  const pointer = wasm.animc_alloc(Math.max(1, bytes)) >>> 0;
  if (!pointer) throw animError('limit', `animcompress: no WebAssembly memory for ${bytes} bytes`);
  return pointer;
}

function limitValues(options) {
  return LIMIT_NAMES.map((name) => {
    const value = options[name] ?? 0;
    if (typeof value !== 'number' || !(value >= 0))
      throw animError('invalid', `animcompress: ${name} must be a number ≥ 0 (0: the default; Infinity: none)`);
    return value;
  });
}

export class AnimStream {
  // bytes: a whole .ams stream. options: DecoderLimits by LIMIT_NAMES (numbers), and
  // `partial: true` when bytes are the start of a stream still arriving: the stream opened is
  // then the frames of its whole groups, and the promise gives null while there is none yet.
  static async open(bytes, options = {}) {
    const data = asBytes(bytes);
    const limitsGiven = limitValues(options);
    const stream = new AnimStream(await instantiate());
    const handle = guarded(stream, (wasm) => {
      const limits = allocate(wasm, 8 * LIMIT_NAMES.length);
      try {
        const pointer = allocate(wasm, data.length);  // animc_open() owns it
        new Uint8Array(wasm.memory.buffer, pointer, data.length).set(data);
        new Float64Array(wasm.memory.buffer, limits, LIMIT_NAMES.length).set(limitsGiven);
        return wasm.animc_open(pointer, data.length, options.partial ? 1 : 0, limits) >>> 0;
      } finally {
        wasm.animc_free(limits);
      }
    });
    if (!handle) {
      const error = options.partial && stream.wasm.animc_error_code() === 0 ? null : lastError(stream.wasm);
      stream.close();
      if (error) throw error;
      return null;
    }
    stream.handle = handle;
    const w = stream.wasm;
    stream.vertexCount = w.animc_vertex_count(handle);
    stream.triangleCount = w.animc_triangle_count(handle);
    stream.frameCount = w.animc_frame_count(handle);
    stream.frameRate = w.animc_frame_rate(handle);
    stream.groupCount = w.animc_group_count(handle);
    stream.byteLength = w.animc_stream_bytes(handle);
    stream.codec = readString(w, w.animc_codec(handle) >>> 0);
    return stream;
  }

  constructor(wasm) {
    this.wasm = wasm;
    this.handle = 0;
    this.framePointer = 0;
  }

  // The vertex indices, 3 per triangle.
  triangles() {
    return guarded(this, (w) =>
      new Uint32Array(w.memory.buffer, w.animc_triangles(this.handle) >>> 0, 3 * this.triangleCount).slice());
  }

  // Frame k (0 ≤ k < frameCount), in any order: x, y, z per vertex. Into `out` (a Float32Array
  // of 3 × vertexCount) when given, else a new array. The frame after the last one decoded
  // costs one frame; any other costs reading the frames from the start of its group (decoding
  // them, but for trajectory groups, where only frame k is computed).
  frame(k, out) {
    if (!Number.isInteger(k) || k < 0 || k >= this.frameCount)
      throw animError('invalid', `animcompress: frame ${k} is outside 0..${this.frameCount - 1}`);
    const floats = 3 * this.vertexCount;
    if (out && out.length !== floats) throw animError('invalid', `animcompress: out must hold ${floats} floats`);
    return guarded(this, (w) => {
      if (!this.framePointer) this.framePointer = allocate(w, 4 * floats);
      if (w.animc_frame(this.handle, k, this.framePointer) !== 0) throw lastError(w);
      const decoded = new Float32Array(w.memory.buffer, this.framePointer, floats);
      if (!out) return decoded.slice();
      out.set(decoded);
      return out;
    });
  }

  // Frees the decoder's memory; the stream cannot be used afterwards.
  close() {
    const w = this.wasm;
    if (w && this.handle) {
      w.animc_close(this.handle);
      if (this.framePointer) w.animc_free(this.framePointer);
    }
    if (w && idleInstances.length < MAX_IDLE_INSTANCES && w.memory.buffer.byteLength <= MAX_IDLE_MEMORY)
      idleInstances.push(w);
    this.wasm = null;
    this.handle = 0;
  }
}
