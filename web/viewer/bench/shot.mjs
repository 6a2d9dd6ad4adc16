// Screenshot of a live world or a recording for the docs: starts `throng serve WORLD` (a scenario,
// a world file or FILE.sqlite), opens the viewer in headless
// Chromium (SwiftShader), waits, frames the camera and writes the canvas as a PNG (with --page:
// the whole page, HUD, legend and panels included, as docs/viewer.md's "Screenshots" are).
//   THRONG_EXE=build/apps/throng/throng node viewer/bench/shot.mjs WORLD OUT.png
//       [--wait 20] [--look x,y,distance,height] [--width 1280 --height 720]
//       [--query 'colour=state&camera=orbit'] [--page]
// (run from web/ after `npm run build`; WORLD and OUT relative to the current directory)
import fs from 'node:fs';
import path from 'node:path';
import { startServer, stopServer, launchBrowser, sleep, missing } from '../e2e/harness.mjs';

const argv = process.argv.slice(2);
const opt = (name, fallback) => {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 ? argv[i + 1] : fallback;
};
const flags = new Set(['--page']);  // options without a value
const positional = argv.filter((a, i) => !a.startsWith('--') && !(i > 0 && argv[i - 1].startsWith('--') && !flags.has(argv[i - 1])));
if (positional.length !== 2) {
  console.error('usage: node viewer/bench/shot.mjs WORLD OUT.png [--wait S] [--look x,y,distance,height] [--width W --height H] [--query Q] [--page]');
  process.exit(2);
}
const why = missing();
if (why) { console.error(`cannot take the screenshot: ${why}`); process.exit(1); }
const [world, out] = positional.map((p) => path.resolve(p));
const wait = Number(opt('wait', 20));
const look = opt('look', '');
const width = Number(opt('width', 1280)), height = Number(opt('height', 720));
const query = opt('query', '');
const wholePage = argv.includes('--page');

const server = await startServer(world);
const browser = await launchBrowser();
try {
  const page = await browser.newPage({ viewport: { width, height } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  // shot=1 hides the panels and draws at full resolution; a page screenshot keeps them, as a person sees it.
  await page.goto(`${server.url}?${[wholePage ? '' : 'shot=1', query].filter(Boolean).join('&')}`);
  // A recording (throng serve FILE.sqlite) may open paused: play it.
  await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.source && globalThis.__throngStats, null, { timeout: 30000 });
  const replay = await page.evaluate(() => globalThis.__throng.source.kind === 'replay');
  if (replay) {
    await page.waitForFunction(() => !!globalThis.__throng.source.replay, null, { timeout: 15000 });
    if (!(await page.evaluate(() => globalThis.__throng.source.replay.playing))) await page.click('#tl-play');
  }
  await page.waitForFunction(() => globalThis.__throngStats.agents > 0, null, { timeout: 30000 });
  if (look) {
    const [x, y, d, h] = look.split(',').map(Number);
    await page.evaluate(([x, y, d, h]) => globalThis.__throng.cameras.lookAt(x, y, d, h), [x, y, d, h]);
  }
  await sleep(wait * 1000);
  if (wholePage) {
    await page.screenshot({ path: out });
  } else {
    const url = await page.evaluate(() => globalThis.__throng.renderer.domElement.toDataURL('image/png'));
    fs.writeFileSync(out, Buffer.from(url.split(',')[1], 'base64'));
  }
  const s = await page.evaluate(() => globalThis.__throngStats);
  console.log(`${out}: ${s.agents} agents, fps ${s.fps.toFixed(1)}${errors.length ? `, page errors: ${errors.join('; ')}` : ''}`);
} finally {
  await browser.close();
  await stopServer(server);
}
