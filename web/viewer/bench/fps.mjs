#!/usr/bin/env node
// Frames per second against crowd size: serves web/dist (build it first: npm run build), opens
// `?demo&agents=N&lod=on|off` in headless Chromium (Debian's `chromium`, software renderer
// SwiftShader unless --gpu) through playwright-core, lets it warm up, then counts rendered frames
// over a window (window.__throngStats.frames). Prints a Markdown table. With --screenshots, writes
// docs/img/viewer_{near,middle,far,dots}.png (one per level of detail) instead.
//   node viewer/bench/fps.mjs [--agents 100,1000,10000] [--seconds 6] [--gpu] [--screenshots]
//                             [--chromium /usr/bin/chromium] [--width 1280 --height 720]
//                             [--overlays [trails,heatmap,speedmap]] [--only-on]
// --overlays: with the trails, the density map and the speed map on (?trails=1&heatmap=1&speedmap=1),
// or those listed; --only-on: the adaptive display on only (no "off" column).
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const here = path.dirname(fileURLToPath(import.meta.url));
const webRoot = path.resolve(here, '../..');
const dist = path.join(webRoot, 'dist');
const repo = path.resolve(webRoot, '..');

function arg(name, def) {
  const i = process.argv.indexOf(`--${name}`);
  if (i < 0) return def;
  const v = process.argv[i + 1];
  return v === undefined || v.startsWith('--') ? true : v;
}
const counts = String(arg('agents', '100,1000,10000')).split(',').map(Number);
const seconds = Number(arg('seconds', 6));
const width = Number(arg('width', 1280)), height = Number(arg('height', 720));
const gpu = arg('gpu', false) === true;
const screenshots = arg('screenshots', false) === true;
const overlayArg = arg('overlays', false);
const overlays = (overlayArg === true ? ['trails', 'heatmap', 'speedmap'] : overlayArg ? String(overlayArg).split(',') : [])
  .map((o) => `&${o}=1`).join('');
const onlyOn = arg('only-on', false) === true;
const exe = arg('chromium', '/usr/bin/chromium');

const types = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.bvh': 'text/plain' };
function serve() {
  if (!fs.existsSync(path.join(dist, 'index.html'))) throw new Error(`${dist}/index.html missing: run npm run build in web/`);
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://x');
    const file = path.join(dist, path.normalize(decodeURIComponent(url.pathname)).replace(/^([/\\])+/, '') || 'index.html');
    if (!file.startsWith(dist) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
      const index = path.join(dist, 'index.html');
      if (url.pathname === '/' || url.pathname === '') { res.writeHead(200, { 'content-type': 'text/html' }); fs.createReadStream(index).pipe(res); return; }
      res.writeHead(404); res.end(); return;
    }
    res.writeHead(200, { 'content-type': types[path.extname(file)] || 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function open(browser, base, query) {
  const page = await browser.newPage({ viewport: { width, height } });
  page.on('pageerror', (e) => console.error(`page error: ${e.message}`));
  page.on('console', (m) => { if (m.type() === 'error') console.error(`console: ${m.text()}`); });
  await page.goto(`${base}/?${query}`);
  await page.waitForFunction(() => globalThis.__throngStats && globalThis.__throngStats.frames > 2, null, { timeout: 120000 });
  return page;
}

async function measure(browser, base, n, lod) {
  const page = await open(browser, base, `demo&agents=${n}&lod=${lod}&aa=0&camera=orbit${overlays}`);  // the 3D view the table measures
  await sleep(3000);  // warm-up: the LOD budget settles
  const a = await page.evaluate(() => ({ f: globalThis.__throngStats.frames, t: performance.now() }));
  await sleep(seconds * 1000);
  const b = await page.evaluate(() => ({ f: globalThis.__throngStats.frames, t: performance.now(), s: globalThis.__throngStats }));
  await page.close();
  return { fps: ((b.f - a.f) * 1000) / (b.t - a.t), stats: b.s };
}

async function shots(browser, base) {
  const out = path.join(repo, 'docs/img');
  fs.mkdirSync(out, { recursive: true });
  // Close-up: skinned bodies fill the view. Middle: instanced bodies. Far: billboards only.
  const views = [
    { name: 'near', agents: 300, look: [0.5, 8, 2.2] },
    { name: 'middle', agents: 2000, look: [0.35, 30, 12] },
    { name: 'far', agents: 10000, look: [0.5, 140, 55] },
    { name: 'dots', agents: 10000, look: [0.0, 260, 160] },
  ];
  for (const v of views) {
    const page = await open(browser, base, `demo&agents=${v.agents}&lod=on&shot=1`);
    await page.evaluate(([fx, dist, h]) => {
      const { cameras, state } = globalThis.__throng;
      // Look at the agent nearest to a point fx of the way from the centre to the edge.
      let cx = 0, cy = 0;
      for (let i = 0; i < state.count; ++i) { cx += state.x[i]; cy += state.y[i]; }
      cx /= state.count; cy /= state.count;
      let best = 0, bd = Infinity;
      const tx = cx + fx * 20, ty = cy;
      for (let i = 0; i < state.count; ++i) {
        const d = Math.hypot(state.x[i] - tx, state.y[i] - ty);
        if (d < bd) { bd = d; best = i; }
      }
      cameras.lookAt(state.x[best], state.y[best], dist, h);
    }, v.look);
    await sleep(2500);
    const s = await page.evaluate(() => globalThis.__throngStats);
    const file = path.join(out, `viewer_${v.name}.png`);
    // The canvas itself (preserveDrawingBuffer in shot mode): no wait for a compositor frame.
    const url = await page.evaluate(() => globalThis.__throng.renderer.domElement.toDataURL('image/png'));
    fs.writeFileSync(file, Buffer.from(url.split(',')[1], 'base64'));
    console.log(`${file}: near ${s.lod.near}, middle ${s.lod.middle}, far ${s.lod.far}, dots ${s.lod.dot}, fps ${s.fps.toFixed(1)}`);
    await page.close();
  }
}

const server = await serve();
const base = `http://127.0.0.1:${server.address().port}`;
const args = ['--no-sandbox', '--ignore-gpu-blocklist', '--disable-gpu-vsync', '--disable-frame-rate-limit'];
if (!gpu) args.push('--use-angle=swiftshader', '--use-gl=angle', '--enable-unsafe-swiftshader');
const browser = await chromium.launch({ executablePath: exe, headless: true, args });
try {
  if (screenshots) {
    await shots(browser, base);
  } else {
    const renderer = gpu ? 'GPU' : 'SwiftShader (software)';
    console.log(`| agents | adaptive display on: fps | near / middle / far / dots | render scale | adaptive display off: fps |`);
    console.log(`|---:|---:|---|---:|---:|`);
    for (const n of counts) {
      const on = await measure(browser, base, n, 'on');
      const off = onlyOn ? { fps: NaN } : await measure(browser, base, n, 'off');
      const l = on.stats.lod;
      console.log(`| ${n} | ${on.fps.toFixed(1)} | ${l.near} / ${l.middle} / ${l.far} / ${l.dot ?? 0} | ${(l.renderScale ?? 1).toFixed(2)} | ${off.fps.toFixed(1)} |`);
    }
    console.log(`\n${renderer}, ${width}×${height}, headless Chromium ${browser.version()}, ${seconds} s per run`);
  }
} finally {
  await browser.close();
  server.close();
}
