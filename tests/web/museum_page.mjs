// Drives a built museum for tests/test_museum_web.c: validates museum.glb
// with the Khronos glTF validator, serves the folder with `celadon museum
// --serve 0`, opens index.html in headless Chromium (Debian's, through
// playwright-core), takes two screenshots from the entrance, with and
// without the vessels, then in the same page picks each vessel, opens and
// closes a label, walks by touch (a tap, a drag, the virtual stick) and by
// emulated WebXR thumbsticks, these in a window of INPUT_W x INPUT_H
// (WIDTH x HEIGHT is the screenshots'). Prints one JSON object on stdout;
// the C test judges it.
//
//   node tests/web/museum_page.mjs CELADON_BIN MUSEUM_DIR OUT_DIR WIDTH HEIGHT [server|load]
//
// With "server" it validates and probes the server only, without the browser;
// with "load" it only times the page: firstFramesMs from the request to
// three rendered frames (the room, before its probes), loadMs to ready (the
// probes in place and drawn; docs/BENCHMARKS.md).
// Run from the repository root: the npm packages come from web/node_modules.
import { spawn } from 'node:child_process';
import { createRequire } from 'node:module';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';

const require = createRequire(path.resolve('web/package.json'));
const [bin, dir, out, width, height, mode] = process.argv.slice(2);
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const TIMEOUT_MS = mode === 'shots' || mode === 'load' ? 600000 : 120000;  // the benchmarks' big museums wait longer
// The input checks' window: in one much smaller the label panel, opened by
// the tap, covers the stick and the drag.
const INPUT_W = 640, INPUT_H = 360;

async function validate(file) {
  const validator = require('gltf-validator');
  const report = await validator.validateBytes(new Uint8Array(readFileSync(file)));
  return {
    errors: report.issues.numErrors,
    warnings: report.issues.numWarnings,
    messages: report.issues.messages.filter((m) => m.severity === 0).slice(0, 5).map((m) => `${m.code} ${m.pointer}`),
  };
}

// Starts the server and resolves with its URL (the line it prints).
function serve() {
  return new Promise((resolve, reject) => {
    const child = spawn(bin, ['museum', '--serve', '0', '-o', dir], { stdio: ['ignore', 'pipe', 'inherit'] });
    let text = '';
    child.stdout.on('data', (chunk) => {
      text += chunk;
      const m = text.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) resolve({ child, url: m[0] });
    });
    child.on('exit', (code) => reject(new Error(`the server exited (${code}) before listening`)));
  });
}

function stop(child) {
  return new Promise((resolve) => {
    child.removeAllListeners('exit');
    child.on('exit', (code, signal) => resolve(code === null ? signal : code));
    child.kill('SIGTERM');
  });
}

const frames = (page, n) => page.evaluate((k) => new Promise((resolve) => {
  const step = () => (k-- > 0 ? requestAnimationFrame(step) : resolve());
  step();
}), n);
const pose = (page) => page.evaluate(() => window.museum.pose());
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// A label opened by a pick closes with the panel's button (and its
// floating plate with it), and again with a pick of nothing.
async function labelCloses(page, at) {
  const state = () => page.evaluate(() => ({
    title: window.museum.label(), floating: window.museum.floatingLabel(),
    shown: getComputedStyle(document.getElementById('label')).display !== 'none',
    text: document.getElementById('label').textContent,
  }));
  await page.evaluate(([x, y]) => window.museum.pickAt(x, y), [at.x, at.y]);
  const open = await state();
  // A real click where the button is (playwright's click() waits for
  // stable frames, which software WebGL under load may not give in time).
  const box = await page.locator('#label .close').boundingBox();
  await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
  const closed = await state();
  await page.evaluate(([x, y]) => window.museum.pickAt(x, y), [at.x, at.y]);
  await page.evaluate(([x, y]) => window.museum.pickAt(x, y), [8, INPUT_H - 8]);
  const nothing = await state();
  return { open, closed, nothing };
}

// A finger, through Chromium's own touch input (CDP): points are [x, y].
async function finger(cdp, points, holdMs) {
  const at = ([x, y]) => [{ x, y, id: 1 }];
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: at(points[0]) });
  for (const p of points.slice(1)) await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: at(p) });
  if (holdMs) await sleep(holdMs);
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
}

// On a touch screen: a tap on a vessel opens its label, a drag turns the
// head, the virtual stick walks where the eyes look.
async function touchWalk(page, context, positions) {
  const cdp = await context.newCDPSession(page);
  const w = INPUT_W, h = INPUT_H;
  await finger(cdp, [[positions[1].x, positions[1].y]], 0);
  await frames(page, 1);
  const tapped = await page.evaluate(() => window.museum.lastTap);
  const p0 = await pose(page);
  const drag = [];
  for (let k = 0; k <= 10; k++) drag.push([0.7 * w + 10 * k, 0.5 * h]);
  await finger(cdp, drag, 0);
  const p1 = await pose(page);
  const r = await page.evaluate(() => {
    const b = document.getElementById('stick').getBoundingClientRect();  // shown since the first touch
    return { x: b.left + b.width / 2, y: b.top + b.height / 2 };
  });
  const stick = [[r.x, r.y], [r.x, r.y - 30], [r.x, r.y - 60]];  // the stick's centre, then full ahead
  const t0 = Date.now();
  await finger(cdp, stick, 400);
  const seconds = (Date.now() - t0) / 1000;
  await frames(page, 1);
  const p2 = await pose(page);
  return { tapped, before: p0, turned: p1, walked: p2, seconds };
}

// WebXR thumbsticks, emulated as the session's input sources: the left one
// walks where the head looks, the right one turns in snaps.
async function thumbsticks(page) {
  const emulate = (sources) => page.evaluate((s) => window.museum.emulateXr(s), sources);
  const left = (y) => [{ handedness: 'left', gamepad: { axes: [0, 0, 0, y] } }];
  const right = (x) => [{ handedness: 'right', gamepad: { axes: [0, 0, x, 0] } }];
  const p0 = await pose(page);
  const t0 = Date.now();
  await emulate(left(-1));
  await sleep(400);
  await emulate(left(0));
  const seconds = (Date.now() - t0) / 1000;
  await frames(page, 1);
  const walked = await pose(page);
  await emulate(right(1));
  await frames(page, 3);
  const snapped = await pose(page);
  await frames(page, 3);
  const held = await pose(page);
  await emulate(right(0));
  await frames(page, 1);
  await emulate(right(1));
  await frames(page, 2);
  const again = await pose(page);
  await emulate(null);
  return { before: p0, walked, seconds, snapped, held, again };
}

// The docs' screenshots (docs/museum.md): the entrance camera's view (the
// path tracer's), the entrance, the first case close up, and its label open.
async function shots(page) {
  // The glb's entrance camera, as museum.xml's sensor sees the room.
  await page.evaluate(() => window.museum.overlays(false));
  await frames(page, 2);
  await page.screenshot({ path: path.join(out, 'museum-camera.png'), timeout: 0 });
  const at = await page.evaluate(() => window.museum.casePosition(0));
  const entrance = await page.evaluate(() => window.museum.pose());
  await page.evaluate((p) => window.museum.lookFrom(p.x, 1.6, p.z, 0, 1.1, 0), entrance);
  await frames(page, 2);
  await page.screenshot({ path: path.join(out, 'museum-entrance.png'), timeout: 0 });
  await page.evaluate((c) => window.museum.lookFrom(c.x + 0.35, 1.35, c.z + c.w / 2 + 0.7, c.x, c.y, c.z), at);
  await frames(page, 2);
  await page.screenshot({ path: path.join(out, 'museum-case.png'), timeout: 0 });
  await page.evaluate((c) => window.museum.lookFrom(c.x, c.label + 0.15, c.z + c.w / 2 + 0.45, c.x, c.label, c.z + c.w / 2), at);
  await frames(page, 2);
  await page.screenshot({ path: path.join(out, 'museum-label.png'), timeout: 0 });
  return at;
}

async function browse(url) {
  const { chromium } = require('playwright-core');
  const profile = mkdtempSync(path.join(tmpdir(), 'celadon-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    viewport: { width: Number(width), height: Number(height) },
    args: ['--no-sandbox', '--disable-gpu', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync',
      '--disable-quic'],
  });
  const consoleErrors = [];
  try {
    const page = await context.newPage();
    page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
    page.on('pageerror', (e) => consoleErrors.push(e.message));
    const t0 = Date.now();
    await page.goto(url);
    // The first frames (the room, before the probes; a page without them:
    // when ready), then ready (every probe in place).
    await page.waitForFunction(() => window.museum && (window.museum.firstFrames || window.museum.ready ||
      window.museum.error), null, { timeout: TIMEOUT_MS, polling: 100 });
    const firstFramesMs = Date.now() - t0;
    await page.waitForFunction(() => window.museum && (window.museum.ready || window.museum.error),
      null, { timeout: TIMEOUT_MS });
    const loadMs = Date.now() - t0;
    // The page's own clock (ms from its navigation): museum.glb parsed, the first frames, the probes in place.
    const pageMs = await page.evaluate(() => ({ glb: window.museum.glbMs, firstFrames: window.museum.firstFramesMs,
      probes: window.museum.probesMs }));
    if (mode === 'load') return { firstFramesMs, loadMs, pageMs, consoleErrors };
    if (mode === 'shots') return { loadMs, shots: await shots(page), consoleErrors };
    const status = await page.evaluate(() => { const m = window.museum; return { error: m.error, title: m.title, vessels: m.vessels, trianglesFullDetail: m.trianglesFullDetail }; });
    const positions = await page.evaluate(() => window.museum.vesselScreenPositions());
    const heights = await page.evaluate(() => window.museum.vesselHeights());
    const frame = () => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await page.evaluate(() => window.museum.overlays(false));
    await frame();
    const figures = await page.evaluate(() => ({ triangles: window.museum.triangles, drawCalls: window.museum.drawCalls }));
    await page.screenshot({ path: path.join(out, 'page.png') });
    await page.evaluate(() => window.museum.setVesselsVisible(false));
    await frame();
    await page.screenshot({ path: path.join(out, 'page-without-vessels.png') });
    await page.evaluate(() => { window.museum.setVesselsVisible(true); window.museum.overlays(true); });
    const picked = [];
    for (const p of positions) picked.push(await page.evaluate(([x, y]) => window.museum.pickAt(x, y), [p.x, p.y]));
    const bytes = await page.evaluate(() => ({ loaded: window.museum.bytesLoaded, total: window.museum.bytesTotal }));
    const phaseMs = { load: loadMs, shots: Date.now() - t0 - loadMs };
    // The input checks need frames, not pixels: software WebGL draws an
    // eighth of the width and height from here on, 64 times faster.
    await page.setViewportSize({ width: INPUT_W, height: INPUT_H });
    await page.evaluate(() => window.museum.setPixelRatio(0.125));
    await frames(page, 2);  // the page's resize handler has run
    const at = await page.evaluate(() => window.museum.vesselScreenPositions());
    let t = Date.now();
    const label = await labelCloses(page, at[0]);
    phaseMs.label = Date.now() - t, t = Date.now();
    const touch = await touchWalk(page, context, at);
    phaseMs.touch = Date.now() - t, t = Date.now();
    const xr = await thumbsticks(page);
    phaseMs.xr = Date.now() - t;
    return { ...status, ...figures, loadMs, phaseMs, positions, heights, picked, bytes, label, touch, xr, consoleErrors };
  } finally {
    await context.close();
    rmSync(profile, { recursive: true, force: true });
  }
}

// What the server answers: the page and the glb with their types; paths
// that climb out of the folder (escaped, so the client does not resolve the
// "..") or name hidden files are not found.
async function probe(url) {
  const answers = {};
  for (const p of ['', 'museum.glb', '..%2f..%2fetc%2fpasswd', 'vessels%2f..%2f..%2fmuseum.json', '.hidden', 'no-such-file']) {
    const r = await fetch(url + p);
    answers[p || '/'] = { status: r.status, type: r.headers.get('content-type') };
    await r.arrayBuffer();
  }
  return answers;
}

const result = { validator: await validate(path.join(dir, 'museum.glb')) };
const server = await serve();
try {
  result.server = await probe(server.url);
  if (mode !== 'server') result.page = await browse(server.url);
} catch (e) {
  result.failure = String(e.message || e);
}
result.serverExit = await stop(server.child);
process.stdout.write(JSON.stringify(result) + '\n');
