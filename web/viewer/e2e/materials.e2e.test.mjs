// End-to-end test of glTF materials (issue 20, "glTF materials where the world has them") against a
// real `throng serve` in Debian's headless chromium. scenarios/tiled_hall.gltf (written by
// scripts/make_tiled_hall_gltf.py) has a checker-tiled floor texture, a red carpet and coloured
// obstacles: the viewer loads the file from /api/world/model and draws its meshes instead of the
// flat floor — checked by image statistics on the same frame drawn both ways (the crowd identical):
// the slate-blue and sand tiles and the red carpet cover several per cent of the picture only with
// the materials. scenarios/gallery.gltf has no materials: it stays flat (no model drawn).
// Run: THRONG_EXE=build/apps/throng/throng node --test web/viewer/e2e/materials.e2e.test.mjs
// (THRONG_E2E_SHOTS=DIR keeps screenshots). Fails, like the other e2e tests, when something it needs is missing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { repo, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer, sleep } from './harness.mjs';

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
    const [withModel, flat] = await page.evaluate(() => {
      const t = globalThis.__throng;
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
