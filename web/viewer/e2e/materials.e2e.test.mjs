// End-to-end test of glTF materials (issue 20, "glTF materials where the world has them") against a
// real `throng serve` in Debian's headless chromium. scenarios/tiled_hall.gltf (written by
// scripts/make_tiled_hall_gltf.py) has a checker-tiled floor texture, a red carpet and coloured
// obstacles: the viewer loads the file from /api/world/model and draws its meshes instead of the
// flat floor — checked by image statistics on the same frame drawn both ways (the crowd identical):
// the slate-blue and sand tiles and the red carpet cover several per cent of the picture only with
// the materials. scenarios/gallery.gltf has no materials: it stays flat (no model drawn). A
// recording of the hall (`throng run`, which stores the file's name) replays with the same
// materials; a recording of a scenario JSON stays flat and the HUD's debug panel says why.
// Run: THRONG_EXE=build/apps/throng/throng node --test web/viewer/e2e/materials.e2e.test.mjs
// (THRONG_E2E_SHOTS=DIR keeps screenshots). Fails, like the other e2e tests, when something it needs is missing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import os from 'node:os';
import { repo, exe, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer, sleep } from './harness.mjs';

const shotsDir = process.env.THRONG_E2E_SHOTS || '';
async function shot(page, name) {
  if (!shotsDir) return;
  fs.mkdirSync(shotsDir, { recursive: true });
  await page.screenshot({ path: path.join(shotsDir, name) });
}

/** Shares of the sampled pixels [0, 1] that look like each of the hall's materials, as lit. */
function shares(rgb) {
  const n = rgb.length;
  const count = (f) => rgb.filter(([r, g, b]) => f(r, g, b)).length / n;
  return {
    slate: count((r, g, b) => b > r + 25 && b > g + 8 && b < 230),
    sand: count((r, g, b) => r > 150 && r > g && g > b && r - b > 45),
    carpet: count((r, g, b) => r > 90 && r > 2 * g && r > 2 * b),
  };
}

/** The same frame drawn with the world's glTF meshes and flat: the hall's slate and sand tiles and
 * its red carpet cover several per cent of the picture more with the materials. */
async function assertMaterialsShow(page) {
  const [withModel, flat] = await page.evaluate(() => {
    const t = globalThis.__throng;
    // The world framed over the whole 640×360 canvas, panels or not (Fit keeps it clear of them,
    // which at this size draws it at half the size: framing.e2e checks that): the shares below are
    // of the picture the hall fills.
    const keep = t.cameras.panels;
    t.cameras.panels = () => [];
    t.cameras.fit();
    t.cameras.panels = keep;
    const a = t.pixels(4, true);
    t.showWorldModel(false);
    const b = t.pixels(4, true);
    t.showWorldModel(true);
    return [a, b];
  });
  const a = shares(withModel.rgb), b = shares(flat.rgb);
  const mean = withModel.grey.reduce((s, v) => s + v, 0) / withModel.grey.length;
  const sd = Math.sqrt(withModel.grey.reduce((s, v) => s + (v - mean) ** 2, 0) / withModel.grey.length);
  assert.ok(sd > 8, `not blank: grey sd ${sd.toFixed(1)}`);
  const pc = (x) => `${(x * 100).toFixed(1)} %`;
  const says = `with the materials: slate ${pc(a.slate)}, sand ${pc(a.sand)}, carpet ${pc(a.carpet)}; flat: slate ${pc(b.slate)}, sand ${pc(b.sand)}, carpet ${pc(b.carpet)}`;
  console.log(says);
  assert.ok(a.slate - b.slate > 0.03, `the floor's slate tiles show: ${says}`);
  assert.ok(a.sand - b.sand > 0.03, `the floor's sand tiles show: ${says}`);
  assert.ok(a.carpet - b.carpet > 0.01, `the red carpet shows: ${says}`);
}

async function openWorld(browser, file, errors) {
  const server = await startServer(path.join(repo, 'scenarios', file));
  const page = await openViewer(browser, server.url, errors);
  await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 0, null, { timeout: 30000 });
  return { server, page };
}

test('a glTF world with materials is drawn with its textures and colours', { timeout: 120000 }, async () => {
  requirePrerequisites('materials.e2e');
  const browser = await launchBrowser();
  const errors = [];
  let server = null;
  try {
    const hall = await openWorld(browser, 'tiled_hall.gltf', errors);
    server = hall.server;
    const { page } = hall;
    await page.waitForFunction(() => globalThis.__throng.worldModel !== null, null, { timeout: 20000 });
    const summary = await page.evaluate(() => globalThis.__throng.worldModel.userData.summary);
    assert.deepEqual(summary, { textured: 1, coloured: 4, plain: 0, any: true });
    await sleep(500);
    await shot(page, 'viewer_gltf_materials.png');
    await assertMaterialsShow(page);
    if (shotsDir) {
      await page.evaluate(() => globalThis.__throng.showWorldModel(false));
      await shot(page, 'viewer_gltf_flat.png');
      await page.evaluate(() => globalThis.__throng.showWorldModel(true));
    }
    const flatFloor = await page.evaluate(() => {
      const out = [];
      globalThis.__throng.worldRoot().traverse((o) => { if (o.userData.flat) out.push(o.visible); });
      return out;
    });
    assert.ok(flatFloor.length > 0 && flatFloor.every((v) => !v), `the flat floors and obstacles are hidden: ${flatFloor}`);
    await page.close();
    await stopServer(server);

    // A glTF world without materials keeps the flat floor.
    const gallery = await openWorld(browser, 'gallery.gltf', errors);
    server = gallery.server;
    await sleep(1500);
    const model = await gallery.page.evaluate(() => globalThis.__throng.worldModel);
    assert.equal(model, null, 'no model drawn for a world without materials');
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
  }
});

test('a recording of a glTF world replays with its materials; a recording of a scenario JSON says why it has none', { timeout: 150000 }, async () => {
  requirePrerequisites('materials.e2e');
  // Recorded elsewhere: the server finds the glTF file the recording names (throng_world_file) in
  // the bundled scenarios/, and it describes exactly the world recorded.
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-materials-e2e-'));
  const record = (scenario, out) => {
    const r = spawnSync(path.resolve(exe), ['run', path.join(repo, 'scenarios', scenario), '--duration', '4', '--out', path.join(dir, out), '--quiet'],
      { cwd: dir, encoding: 'utf8' });
    assert.equal(r.status, 0, r.stderr);
    return path.join(dir, out);
  };
  const hallRecording = record('tiled_hall.gltf', 'hall.sqlite');
  const museumRecording = record('museum.json', 'museum.sqlite');
  const browser = await launchBrowser();
  const errors = [];
  let server = null;
  try {
    server = await startServer(hallRecording);
    const page = await openViewer(browser, server.url, errors);
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 0, null, { timeout: 30000 });
    await page.waitForFunction(() => globalThis.__throng.worldModel !== null, null, { timeout: 20000 });
    // A served recording says it is one in its first ReplayStatus, sent once a second: waited for
    // (asserting at once lost the race in two of four runs on the 2-core machine).
    await page.waitForFunction(() => globalThis.__throng.source.kind === 'replay', null, { timeout: 10000 });
    assert.equal(await page.evaluate(() => globalThis.__throng.source.kind), 'replay');
    assert.deepEqual(await page.evaluate(() => globalThis.__throng.worldModel.userData.summary),
      { textured: 1, coloured: 4, plain: 0, any: true });
    await page.evaluate(() => globalThis.__throng.source.pause());
    await sleep(500);
    await shot(page, 'viewer_gltf_materials_replay.png');
    await assertMaterialsShow(page);
    assert.ok(!(await page.evaluate(() => globalThis.__throng.hud.modelMissing)), 'nothing said missing');
    await page.close();
    await stopServer(server);

    // A recording of a scenario JSON: flat, and the HUD's debug panel says why.
    server = await startServer(museumRecording);
    const museum = await openViewer(browser, server.url, errors);
    await museum.waitForFunction(() => globalThis.__throng && globalThis.__throng.hud.modelMissing, null, { timeout: 30000 });
    await museum.click('.hud-debug-toggle');
    await sleep(1200);
    const text = await museum.evaluate(() => globalThis.__throng.hud.text());
    assert.match(text, /materials +not drawn: the recording names no glTF world file/, text);
    assert.equal(await museum.evaluate(() => globalThis.__throng.worldModel), null);
    assert.deepEqual(errors.filter((e) => !e.includes('glTF materials are not drawn')), []);
  } finally {
    await browser.close();
    await stopServer(server);
    fs.rmSync(dir, { recursive: true, force: true });
  }
});
