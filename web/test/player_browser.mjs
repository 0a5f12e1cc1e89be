// SPDX-License-Identifier: Apache-2.0
// The player in a real browser: Debian's Chromium, headless, driven by puppeteer-core, against
// a static server on 127.0.0.1 that this script starts and stops. It checks that the frames the
// page decodes are those of `animc decode --format pc2`, bit for bit (hashes); that the canvas
// shows the mesh; that scrubbing to frame k shows frame k; that the first group plays while
// the rest of the file is held back by the server; and that a corrupt file shows a message.
//   ANIMC=build/animc/animc node web/test/player_browser.mjs [--screenshot OUT.png]
// Not under `node --test test/`: it needs Chromium and the node_modules of web/package.json.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { createReadStream, existsSync, mkdtempSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { extname, join, normalize } from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';

const webRoot = fileURLToPath(new URL('..', import.meta.url));
const dataDir = fileURLToPath(new URL('../../tests/data/sydney_md2/', import.meta.url));
const animc = process.env.ANIMC;
const chromium = process.env.CHROMIUM ?? '/usr/bin/chromium';
const screenshotIndex = process.argv.indexOf('--screenshot');
const screenshotPath = screenshotIndex > 0 ? process.argv[screenshotIndex + 1] : null;
const types = { '.html': 'text/html', '.mjs': 'text/javascript', '.js': 'text/javascript', '.wasm': 'application/wasm' };

function sha256(bytes) {
  return createHash('sha256').update(bytes).digest('hex');
}

// The test's files: the sequence encoded in 5 groups, the native decoder's frames, a copy with
// a damaged header. The max error of 0.5 % makes a file whose first half, which /held/ sends,
// is more than the 16 KiB the player waits for before it opens a stream still arriving.
function makeFiles(dir) {
  const original = join(dir, 'original.pc2');
  writeFileSync(original, execFileSync('xz', ['-dc', join(dataDir, 'sydney_md2.pc2.xz')], { maxBuffer: 1 << 28 }));
  const ams = join(dir, 'sydney.ams');
  execFileSync(animc, ['encode', original, '--mesh', join(dataDir, 'sydney_md2.ply'), '-o', ams, '--iframe-interval', '40',
    '--max-error', '0.005']);
  execFileSync(animc, ['decode', ams, '-o', join(dir, 'decoded.pc2'), '--format', 'pc2']);
  const corrupt = Buffer.from(readFileSync(ams));
  corrupt[30] ^= 0x55;
  writeFileSync(join(dir, 'corrupt.ams'), corrupt);
  const frames = readFileSync(join(dir, 'decoded.pc2')).subarray(32);
  return { frames, vertexCount: 342 };
}

// Serves web/ and, under /files/, the test's files; /held/NAME sends the first group's
// bytes and holds the rest until release() is called.
function serve(filesDir) {
  let release;
  const released = new Promise((resolve) => (release = resolve));
  const server = createServer(async (request, response) => {
    const path = decodeURIComponent(new URL(request.url, 'http://x').pathname);
    if (path.startsWith('/held/')) {
      const bytes = readFileSync(join(filesDir, path.slice(6)));
      response.writeHead(200, { 'content-type': 'application/octet-stream', 'content-length': bytes.length });
      response.write(bytes.subarray(0, Math.floor(bytes.length / 2)));
      await released;
      return response.end(bytes.subarray(Math.floor(bytes.length / 2)));
    }
    const file = path.startsWith('/files/') ? join(filesDir, path.slice(7)) : join(webRoot, normalize(path));
    if (!existsSync(file) || !statSync(file).isFile()) return response.writeHead(404).end();
    response.writeHead(200, { 'content-type': types[extname(file)] ?? 'application/octet-stream' });
    createReadStream(file).pipe(response);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve({ server, release })));
}

async function waitFor(page, condition, what) {
  try {
    await page.waitForFunction(condition, { timeout: 60000, polling: 50 });
  } catch {
    const state = await page.evaluate(() => JSON.stringify(window.animcPlayer?.state));
    throw new Error(`the player never ${what} (state: ${state})`);
  }
}

async function main() {
  if (!animc) throw new Error('ANIMC (the animc binary) is not set');
  const dir = mkdtempSync(join(tmpdir(), 'animc-player-'));
  const { frames, vertexCount } = makeFiles(dir);
  const frameBytes = 12 * vertexCount;
  const { server, release } = await serve(dir);
  const base = `http://127.0.0.1:${server.address().port}/player/index.html`;
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=960,640'],
  });
  try {
    // Any error a page does not handle fails the test.
    const pageErrors = [];
    const newPage = async () => {
      const p = await browser.newPage();
      p.on('pageerror', (e) => pageErrors.push(e.message));
      return p;
    };
    const page = await newPage();
    await page.setViewport({ width: 960, height: 640 });

    // The frames decoded in the page are the native decoder's.
    await page.goto(`${base}?src=/files/sydney.ams&original=/files/original.pc2`);
    await waitFor(page, () => window.animcPlayer?.state.complete && window.animcPlayer.errorScale() > 0, 'loaded the file');
    assert.equal(await page.evaluate(() => window.animcPlayer.hashAllFrames()), sha256(frames), 'frames differ from animc decode');
    console.log('ok: every frame equals animc decode --format pc2');

    // Scrubbing to frame k shows frame k; the canvas shows the mesh.
    for (const k of [150, 7, 197]) {
      await page.evaluate((k) => window.animcPlayer.showFrame(k), k);
      assert.equal(await page.evaluate(() => window.animcPlayer.state.frame), k);
      assert.equal(await page.evaluate(() => window.animcPlayer.shownHash()),
        sha256(frames.subarray(k * frameBytes, (k + 1) * frameBytes)), `frame ${k}`);
    }
    const pixels = await page.evaluate(() => window.animcPlayer.meshPixels());
    assert.ok(pixels > 2000, `only ${pixels} pixels of mesh on the canvas`);
    console.log(`ok: scrubbing shows the frame asked for; the mesh covers ${pixels} pixels`);
    if (screenshotPath) {
      await page.evaluate(() => window.animcPlayer.showFrame(60));
      await page.screenshot({ path: screenshotPath });
      console.log(`screenshot: ${screenshotPath}`);
    }

    // The first group plays while the rest of the file is held back.
    const held = await newPage();
    await held.goto(`${base}?src=/held/sydney.ams`);
    await waitFor(held, () => window.animcPlayer?.state.frameCount > 0, 'played before the whole file arrived');
    const early = await held.evaluate(() => window.animcPlayer.state);
    assert.ok(!early.complete && early.frameCount < 198, JSON.stringify(early));
    release();
    await waitFor(held, () => window.animcPlayer.state.complete, 'took the rest of the file');
    assert.equal(await held.evaluate(() => window.animcPlayer.state.frameCount), 198);
    console.log(`ok: ${early.frameCount} frames played before the second half of the file arrived`);

    // A corrupt file shows a message.
    const bad = await newPage();
    await bad.goto(`${base}?src=/files/corrupt.ams`);
    await waitFor(bad, () => window.animcPlayer?.state.error, 'showed an error');
    const text = await bad.evaluate(() => document.getElementById('message').textContent);
    assert.match(text, /corrupt|CRC/i);
    console.log(`ok: a corrupt file shows "${text}"`);
    assert.deepEqual(pageErrors, [], 'errors the pages did not handle');
  } finally {
    await browser.close();
    server.close();
    rmSync(dir, { recursive: true, force: true });
  }
}

main().catch((error) => {
  console.error(`player_browser: ${error.message}`);
  process.exit(1);
});
