// End-to-end test of fit-to-world in the part of the screen the panels leave free (issue 20): the
// four worlds of docs/viewer.md's screenshots — the museum and the mall live (plan view), the
// bottleneck replayed from a recording and the two-floor world (orbit) — opened at the screenshots'
// 1280×720. In each, the world's bounding box projected into the camera (its corners at the lowest
// and highest floor) lies on screen, overlaps none of the panels (HUD, controls, legend,
// measurements, replay timeline: their DOM rectangles) and still fills the view (over half its
// width or height); the same after zooming in and pressing F, and, in the museum, in the orbit
// camera too. The panels change after the world is shown (joining makes the controls taller): the
// cameras are framed again clear of them.
// Before, the fit used the whole canvas and the controls covered the museum's north-east corner.
// Run: THRONG_EXE=build/apps/throng/throng node --test web/viewer/e2e/framing.e2e.test.mjs
// Fails (never skips) without THRONG_EXE, web/node_modules, web/dist or chromium, saying which.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { exe, repo, requirePrerequisites, startServer, stopServer, launchBrowser, sleep } from './harness.mjs';

const kPanels = ['hud', 'controls', 'legend', 'measure', 'timeline'];

/** The world's projected box and the panels' rectangles, in screen px. */
function framing(page) {
  return page.evaluate((ids) => {
    const { cameras, toScreen } = globalThis.__throng;
    const b = cameras.bounds;
    const pts = [];
    for (const x of [b.minX, b.maxX]) for (const y of [b.minY, b.maxY]) for (const z of [b.minZ ?? 0, b.maxZ ?? 0]) pts.push(toScreen(x, y, z));
    const world = pts.some((p) => !p) ? null : { left: Math.min(...pts.map((p) => p.x)), right: Math.max(...pts.map((p) => p.x)),
      top: Math.min(...pts.map((p) => p.y)), bottom: Math.max(...pts.map((p) => p.y)) };
    const panels = ids.map((id) => {
      const r = document.getElementById(id).getBoundingClientRect();
      return { id, left: r.left, top: r.top, right: r.right, bottom: r.bottom, shown: r.width > 0 && r.height > 0 };
    }).filter((p) => p.shown);
    return { world, panels, w: innerWidth, h: innerHeight, mode: cameras.mode };
  }, kPanels);
}

function assertClear(f, what) {
  const r = f.world;
  assert.ok(r, `${what}: the world's box is in front of the camera`);
  const box = JSON.stringify({ left: Math.round(r.left), top: Math.round(r.top), right: Math.round(r.right), bottom: Math.round(r.bottom) });
  assert.ok(r.left >= -1 && r.top >= -1 && r.right <= f.w + 1 && r.bottom <= f.h + 1, `${what}: the world ${box} is on screen (${f.w}×${f.h})`);
  for (const p of f.panels) {
    const hit = r.left < p.right && p.left < r.right && r.top < p.bottom && p.top < r.bottom;
    assert.ok(!hit, `${what}: the world ${box} lies under the ${p.id} panel ${JSON.stringify(p)}`);
  }
  assert.ok(r.right - r.left > 0.5 * f.w || r.bottom - r.top > 0.5 * f.h, `${what}: the world ${box} fills the view`);
}

async function open(browser, url, errors, name) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  page.on('pageerror', (e) => errors.push(`${name}: page error: ${e.message}`));
  await page.goto(url);
  await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.cameras && globalThis.__throng.state.count > 0, null, { timeout: 45000 });
  return page;
}

/** Checks the first view, then zooms in (the wheel over the middle), presses F and checks again. */
async function checkFits(page, what, mode) {
  await sleep(1500);  // the panels settle (group list, recordings row, timeline); the view is framed again
  const f = await framing(page);
  assert.equal(f.mode, mode, `${what} opens in the ${mode} view`);
  assertClear(f, `${what}, first view`);
  await page.mouse.move(640, 400);
  for (let k = 0; k < 5; ++k) { await page.mouse.wheel(0, -300); await sleep(60); }
  await sleep(300);
  const zoomed = await framing(page);
  assert.ok(zoomed.world && (zoomed.world.right - zoomed.world.left) > (f.world.right - f.world.left) * 1.2, `${what}: the wheel zoomed in`);
  await page.keyboard.press('KeyF');
  await sleep(300);
  assertClear(await framing(page), `${what}, after F`);
}

test('fit frames every world in the part of the screen the panels leave free', { timeout: 240000 }, async () => {
  requirePrerequisites('framing e2e');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-framing-e2e-'));
  const recording = path.join(dir, 'bottleneck.sqlite');
  const r = spawnSync(exe, ['run', path.join(repo, 'scenarios/bottleneck.json'), '--duration', '10', '--out', recording, '--quiet'],
    { encoding: 'utf8', timeout: 60000 });
  assert.equal(r.status, 0, `throng run bottleneck: ${r.stderr}`);
  const browser = await launchBrowser();
  const errors = [];
  try {
    for (const [world, what, mode] of [
      ['scenarios/museum.json', 'museum', 'plan'], ['scenarios/mall.json', 'mall', 'plan'],
      [recording, 'bottleneck recording', 'orbit'], ['scenarios/two_floors.gltf', 'two-floor world', 'orbit']]) {
      const server = await startServer(path.isAbsolute(world) ? world : path.join(repo, world));
      try {
        const page = await open(browser, server.url, errors, what);
        if (world === recording) {
          await page.waitForSelector('#timeline:not(.hidden)', { timeout: 15000 });
        }
        await checkFits(page, what, mode);
        if (what === 'museum') {
          // Joining makes the controls taller (the join status, the gesture buttons) and switches to
          // the walk camera; the plan and orbit cameras, as F left them, are framed again clear of them.
          const before = await framing(page);
          await page.fill('#join-name', 'e2e-frame');
          await page.click('#join-button');
          await page.waitForFunction(() => !!globalThis.__throng.joined, null, { timeout: 15000 });
          await sleep(800);
          const after = await framing(page);
          const grew = (f) => f.panels.find((p) => p.id === 'controls').bottom;
          assert.ok(grew(after) > grew(before) + 20, `the controls grew (${grew(before)} → ${grew(after)} px)`);
          await page.keyboard.press('KeyP');
          await sleep(300);
          assertClear(await framing(page), 'museum, plan view once joined');
          // The walk camera moved the perspective camera the orbit view shares: O, then F.
          await page.keyboard.press('KeyO');
          await page.keyboard.press('KeyF');
          await sleep(300);
          assertClear(await framing(page), 'museum, orbit view once joined, after F');
        }
        await page.close();
      } finally {
        await stopServer(server);
      }
    }
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    fs.rmSync(dir, { recursive: true, force: true });
  }
});
