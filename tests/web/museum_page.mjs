// Drives a built museum for tests/test_museum_web.c: validates museum.glb
// with the Khronos glTF validator, serves the folder with `celadon museum
// --serve 0`, opens index.html in headless Chromium (Debian's, through
// playwright-core) and takes two screenshots from the entrance, with and
// without the vessels. Prints one JSON object on stdout; the C test judges it.
//
//   node tests/web/museum_page.mjs CELADON_BIN MUSEUM_DIR OUT_DIR WIDTH HEIGHT [server]
//
// With "server" it validates and probes the server only, without the browser.
// Run from the repository root: the npm packages come from web/node_modules.
import { spawn } from 'node:child_process';
import { createRequire } from 'node:module';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';

const require = createRequire(path.resolve('web/package.json'));
const [bin, dir, out, width, height, mode] = process.argv.slice(2);
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const TIMEOUT_MS = 120000;

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
    await page.waitForFunction(() => window.museum && (window.museum.ready || window.museum.error),
      null, { timeout: TIMEOUT_MS });
    const loadMs = Date.now() - t0;
    const status = await page.evaluate(() => { const m = window.museum; return { error: m.error, title: m.title, vessels: m.vessels, trianglesFullDetail: m.trianglesFullDetail }; });
    const positions = await page.evaluate(() => window.museum.vesselScreenPositions());
    const frame = () => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await frame();
    const figures = await page.evaluate(() => ({ triangles: window.museum.triangles, drawCalls: window.museum.drawCalls }));
    await page.screenshot({ path: path.join(out, 'page.png') });
    await page.evaluate(() => window.museum.setVesselsVisible(false));
    await frame();
    await page.screenshot({ path: path.join(out, 'page-without-vessels.png') });
    await page.evaluate(() => window.museum.setVesselsVisible(true));
    const picked = [];
    for (const p of positions) picked.push(await page.evaluate(([x, y]) => window.museum.pickAt(x, y), [p.x, p.y]));
    return { ...status, ...figures, loadMs, positions, picked, consoleErrors };
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
