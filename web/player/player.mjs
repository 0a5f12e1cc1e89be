// SPDX-License-Identifier: Apache-2.0
// The player: an .ams stream decoded in a Web Worker (WorkerStream) and drawn with three.js;
// frames play at the stream's rate while the rest of a file arrives. An original .pc2 colours
// each vertex by its error, blue (0) to red (the sequence's largest error), as MeshLab's
// "reconstruction error" filter does. window.animcPlayer is what the browser test reads.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { WorkerStream } from '../worker_stream.mjs';
import { errorColours, largestError, readPc2 } from './error_colours.mjs';

const $ = (id) => document.getElementById(id);
const state = { frame: 0, frameCount: 0, complete: false, error: '', bytes: 0 };
let stream = null;
let original = null;   // { vertexCount, frameCount, frames: Float32Array }
let errorScale = 0;
let playing = false;
let clockStart = 0, frameAtStart = 0;
let showing = null, wantedFrame = null;  // showFrame()'s decoding, and the frame it shows next
let shownPositions = null;
let loads = 0;  // files opened: a load that is not the latest stops

const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
$('view').appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x20242b);
scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.5);
sun.position.set(1, 2, 3);
scene.add(sun);
const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
const controls = new OrbitControls(camera, renderer.domElement);
const geometry = new THREE.BufferGeometry();
const material = new THREE.MeshStandardMaterial({ color: 0xc8ccd4, roughness: 0.6, side: THREE.DoubleSide });
const mesh = new THREE.Mesh(geometry, material);
scene.add(mesh);

function resize() {
  const { clientWidth: w, clientHeight: h } = $('view');
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(1, h);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();

function message(text, isError = false) {
  $('message').textContent = text;
  $('message').className = isError ? 'error' : '';
  if (isError) state.error = text;
}

function readout() {
  const bpvf = state.frameCount ? (8 * state.bytes) / (stream.vertexCount * state.frameCount) : 0;
  const size = state.bytes >= 1 << 20 ? `${(state.bytes / (1 << 20)).toFixed(2)} MiB` : `${(state.bytes / 1024).toFixed(1)} KiB`;
  $('readout').textContent = `frame ${state.frame + 1} / ${state.frameCount}${state.complete ? '' : ' (loading)'}` +
    ` · ${size} · ${bpvf.toFixed(3)} bpvf · ${stream.codec}`;
}

// Looks at the mesh across its thinnest side, its longest side up (a standing figure from the
// front, whichever axis its file calls up).
function frameCamera(positions) {
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.computeBoundingBox();
  geometry.computeBoundingSphere();
  const size = geometry.boundingBox.getSize(new THREE.Vector3()).toArray();
  const order = [0, 1, 2].sort((a, b) => size[a] - size[b]);
  const axis = (i) => new THREE.Vector3().setComponent(i, 1);
  const { center, radius } = geometry.boundingSphere;
  camera.up.copy(axis(order[2]));
  const view = axis(order[0]).add(axis(order[1]).multiplyScalar(0.35)).normalize();
  controls.target.copy(center);
  // The bounding sphere fits the vertical field of view with a tenth to spare.
  camera.position.copy(center).add(view.multiplyScalar((1.1 * radius) / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2))));
  camera.near = radius / 100;
  camera.far = radius * 100;
  camera.updateProjectionMatrix();
}

async function sha256(floats) {
  const digest = await crypto.subtle.digest('SHA-256', floats);
  return [...new Uint8Array(digest)].map((b) => b.toString(16).padStart(2, '0')).join('');
}

// Shows frame k: its positions, its normals and, with an original, its error colours.
async function show(k) {
  const from = stream;
  const positions = await from.frame(k);
  if (from !== stream) return;  // another file was opened meanwhile
  const first = !geometry.getAttribute('position');
  if (first) frameCamera(positions);
  else geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  if (original) geometry.setAttribute('color', new THREE.BufferAttribute(errorColours(positions, original, k, errorScale), 3));
  material.vertexColors = Boolean(original);
  material.needsUpdate = true;
  geometry.computeVertexNormals();
  state.frame = k;
  shownPositions = positions;
  $('scrub').value = String(k);
  readout();
}

// Asks for frame k. One frame decodes at a time and only the latest asked for is next, so a
// slow decoder drops frames instead of queueing them; the promise settles when the frame
// asked for last is shown.
function showFrame(k) {
  wantedFrame = k;
  showing ??= (async () => {
    try {
      while (wantedFrame !== null) {
        const next = wantedFrame;
        wantedFrame = null;
        await show(next);
      }
    } catch (error) {
      if (stream) message(error.message, true);
    } finally {
      showing = null;
    }
  })();
  return showing;
}

function tick() {
  if (playing && stream && state.frameCount > 0) {
    // performance.now(), not the animation frame's time stamp, which can precede clockStart.
    const k = frameAtStart + Math.floor(((performance.now() - clockStart) / 1000) * stream.frameRate);
    const wanted = $('loop').checked || !state.complete ? k % state.frameCount : Math.min(k, state.frameCount - 1);
    if (wanted !== state.frame && wanted !== wantedFrame) showFrame(wanted);
    if (!$('loop').checked && state.complete && k >= state.frameCount - 1) setPlaying(false);
  }
  controls.update();
  renderer.render(scene, camera);
  requestAnimationFrame(tick);
}
requestAnimationFrame(tick);

function setPlaying(on) {
  playing = on;
  clockStart = performance.now();
  frameAtStart = state.frame;
  $('play').textContent = on ? 'Pause' : 'Play';
}

// Takes the stream of `bytes`: the whole groups so far while `partial`, else the whole file.
// `current()` is false once another file is being opened: then this one's work is dropped.
async function take(bytes, partial, current) {
  if (!stream) {
    const opened = await WorkerStream.open(bytes, { partial });
    if (!opened || !current()) return opened?.close();
    stream = opened;
    geometry.setIndex(new THREE.BufferAttribute(stream.triangles(), 1));
    message('');
    $('play').disabled = $('scrub').disabled = false;
    state.frameCount = stream.frameCount;
    await showFrame(0);
    setPlaying(true);
  } else if (!(await stream.reopen(bytes, { partial })) || !current()) {
    return;
  }
  state.frameCount = stream.frameCount;
  state.complete = !partial;
  state.bytes = partial ? state.bytes : bytes.length;
  $('scrub').max = String(state.frameCount - 1);
  readout();
}

// Reads a response as it arrives, opening the whole groups so far each time a quarter more
// has come (each opening copies what has arrived).
async function loadResponse(response, current) {
  const total = Number(response.headers.get('content-length')) || 0;
  const chunks = [];
  let received = 0, opened = 0;
  for (const reader = response.body.getReader(); ;) {
    const { done, value } = await reader.read();
    if (!current()) return reader.cancel();
    if (done) break;
    chunks.push(value);
    received += value.length;
    state.bytes = Math.max(total, received);
    if (received >= 1.25 * opened + 16384 && (!total || received < total)) {
      opened = received;
      await take(concat(chunks, received), true, current);
    }
  }
  await take(concat(chunks, received), false, current);
}

function concat(chunks, size) {
  const out = new Uint8Array(size);
  let at = 0;
  for (const c of chunks) out.set(c, at), (at += c.length);
  return out;
}

// Forgets the stream shown, before another file is opened.
function forgetStream() {
  setPlaying(false);
  stream?.close();
  stream = null;
  shownPositions = null;
  geometry.deleteAttribute('position');
  geometry.deleteAttribute('color');
  geometry.setIndex(null);
  Object.assign(state, { frame: 0, frameCount: 0, complete: false, error: '', bytes: 0 });
  errorScale = 0;
}

async function open(source) {
  const load = ++loads;
  const current = () => load === loads;
  try {
    forgetStream();
    message('Loading…');
    if (typeof source === 'string') {
      const response = await fetch(source);
      if (!response.ok) throw new Error(`${source}: HTTP ${response.status}`);
      await loadResponse(response, current);
    } else {
      state.bytes = source.size;
      await take(new Uint8Array(await source.arrayBuffer()), false, current);
    }
    if (original && current()) await measureErrors();
  } catch (error) {
    if (current()) message(`Cannot play this file: ${error.message}`, true);
  }
}

async function openOriginal(bytes) {
  try {
    original = readPc2(bytes);
    if (stream && state.complete) await measureErrors();
  } catch (error) {
    original = null;
    message(`Cannot use the original: ${error.message}`, true);
  }
}

async function measureErrors() {
  if (original.vertexCount !== stream.vertexCount || original.frameCount !== stream.frameCount) {
    message(`The original has ${original.vertexCount} vertices × ${original.frameCount} frames; ` +
      `the stream ${stream.vertexCount} × ${stream.frameCount}: no error colours`, true);
    original = null;
    return;
  }
  errorScale = await largestError((k) => stream.frame(k), original);
  await showFrame(state.frame);
}

$('play').onclick = () => setPlaying(!playing);
$('scrub').oninput = () => {
  setPlaying(false);
  showFrame(Number($('scrub').value));
};
window.addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dragging'); });
window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
window.addEventListener('drop', async (e) => {
  e.preventDefault();
  document.body.classList.remove('dragging');
  for (const file of e.dataTransfer.files) {
    if (file.name.toLowerCase().endsWith('.pc2')) await openOriginal(new Uint8Array(await file.arrayBuffer()));
    else await open(file);
  }
});

// What the browser test reads and drives.
window.animcPlayer = {
  state,
  showFrame: (k) => { setPlaying(false); return showFrame(k); },
  // SHA-256 of the positions shown (crypto.subtle: pages served from localhost or https).
  shownHash: () => sha256(shownPositions),
  pause: () => setPlaying(false),
  errorScale: () => errorScale,
  async hashAllFrames() {
    const floats = 3 * stream.vertexCount;
    const all = new Float32Array(floats * stream.frameCount);
    for (let k = 0; k < stream.frameCount; ++k) all.set(await stream.frame(k), k * floats);
    return sha256(all);
  },
  // Pixels of the canvas that are not the background (the mesh drawn).
  meshPixels() {
    renderer.render(scene, camera);
    const c = document.createElement('canvas');
    c.width = renderer.domElement.width;
    c.height = renderer.domElement.height;
    const g = c.getContext('2d');
    g.drawImage(renderer.domElement, 0, 0);
    const p = g.getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < p.length; i += 4) n += Math.abs(p[i] - 0x20) + Math.abs(p[i + 1] - 0x24) + Math.abs(p[i + 2] - 0x2b) > 24;
    return n;
  },
};

async function openFromUrl(params) {
  if (params.get('original')) {
    try {
      const response = await fetch(params.get('original'));
      if (!response.ok) throw new Error(`${params.get('original')}: HTTP ${response.status}`);
      await openOriginal(new Uint8Array(await response.arrayBuffer()));
    } catch (error) {
      message(`Cannot use the original: ${error.message}`, true);
    }
  }
  if (params.get('src')) await open(params.get('src'));
}
openFromUrl(new URLSearchParams(location.search));
