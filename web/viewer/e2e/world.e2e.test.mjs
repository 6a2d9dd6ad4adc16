// End-to-end test of readable worlds (issue 20) in Debian's headless chromium against a real
// `throng serve`: the museum and the mall get walls along their walkable area's boundary (and the
// mall's shops keep their doors open: fewer wall segments than polygon edges), the two-floor world
// gets stair risers and railings; each of them changes the picture (rendered with and without
// them); the museum's density map (key M) holds the classic density of the frames and is drawn,
// its speed map (key G) the mean speeds of walkers, and is drawn.
// THRONG_E2E_SHOTS=DIR keeps the screenshots docs/viewer.md shows (1280×720). Run:
// THRONG_EXE=build/apps/throng/throng node --test web/viewer/e2e/world.e2e.test.mjs. Fails, like
// the other e2e tests, when something it needs is missing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { repo, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer } from './harness.mjs';

const shotsDir = process.env.THRONG_E2E_SHOTS || '';
async function shot(page, name) {
  if (!shotsDir) return;
  fs.mkdirSync(shotsDir, { recursive: true });
  await page.screenshot({ path: path.join(shotsDir, name) });
}

/** Share of sampled pixels (every 4th px) that change when the world part `name` is hidden. */
function changedByPart(page, name) {
  return page.evaluate((name) => {
    const t = globalThis.__throng;
    const part = t.worldPart(name);
    // Every second pixel: the plan view's walls are lines a pixel or two wide, which a coarser grid
    // catches or misses by where they fall (every 4th pixel saw 0.16 % of the museum's, every 2nd 0.59 %).
    const on = t.pixels(2).grey;
    part.visible = false;
    const off = t.pixels(2).grey;
    part.visible = true;
    let changed = 0;
    for (let i = 0; i < on.length; ++i) if (Math.abs(on[i] - off[i]) > 6) ++changed;
    return changed / on.length;
  }, name);
}

/** The density map (key M): its cells hold PedPy's classic density of the frames it saw (summed
 * over the grid times the cell area: the mean number of agents in the world, within 15 %), it is
 * drawn (the picture changes with it hidden), the legend and the checkbox follow, M hides it. */
async function checkHeatmap(page) {
  await page.keyboard.press('p');
  await page.keyboard.press('m');
  await page.waitForFunction(() => globalThis.__throng.heatmap.grid.frames.length >= 10, null, { timeout: 15000 });
  const r = await page.evaluate(() => {
    const t = globalThis.__throng, g = t.heatmap.grid;
    let total = 0;
    for (let j = 0; j < g.ny; ++j) for (let i = 0; i < g.nx; ++i) total += g.density(i, j) * g.cell * g.cell;
    const frames = g.frames.length;
    const counted = g.frames.reduce((n, f) => n + f.counts.reduce((a, b) => a + b, 0), 0) / frames;
    const on = t.pixels(4).grey;
    t.heatmap.mesh.visible = false;
    const off = t.pixels(4).grey;
    t.heatmap.mesh.visible = true;
    let changed = 0;
    for (let i = 0; i < on.length; ++i) if (Math.abs(on[i] - off[i]) > 6) ++changed;
    return { total, counted, agents: t.state.count, changed: changed / on.length, checked: document.querySelector('#heatmap-toggle').checked,
             legend: document.querySelector('#legend').textContent };
  });
  assert.ok(r.agents > 0 && Math.abs(r.total - r.counted) < 1e-6 && Math.abs(r.total - r.agents) <= 0.15 * r.agents + 1,
    `density map: ${JSON.stringify({ total: r.total, counted: r.counted, agents: r.agents })}`);
  assert.ok(r.changed > 0.001, `the density map shows (${(r.changed * 100).toFixed(2)} % of pixels)`);
  assert.ok(r.checked && r.legend.includes('density map'), 'the Density checkbox and the legend follow the key');
  await shot(page, 'viewer_density_map.png');
  await page.keyboard.press('m');
  assert.equal(await page.evaluate(() => globalThis.__throng.heatmap.enabled), false);
}

/** The density map's Voronoi definition (the menu beside Density): each frame's Voronoi shares
 * sum to the agents whose cell covers walkable ground (within 15 % of those on screen), spread over
 * more cells than the classic counts, the legend says "density map (Voronoi)"; back to classic. */
async function checkVoronoiMap(page) {
  await page.selectOption('#heatmap-method', 'voronoi');
  await page.keyboard.press('m');
  await page.waitForFunction(() => globalThis.__throng.heatmap.grid.frames.length >= 10, null, { timeout: 20000 });
  const r = await page.evaluate(() => {
    const t = globalThis.__throng, g = t.heatmap.grid;
    let total = 0, cells = 0;
    for (let j = 0; j < g.ny; ++j) for (let i = 0; i < g.nx; ++i) {
      const d = g.density(i, j);
      total += d * g.cell * g.cell;
      if (d > 0) ++cells;
    }
    // The classic counts of the latest frame, for comparison: cells with someone in them.
    const occupied = new Set();
    for (let k = 0; k < t.state.count; ++k) occupied.add(`${Math.floor((t.state.x[k] - g.minX) / g.cell)},${Math.floor((t.state.y[k] - g.minY) / g.cell)}`);
    return { total, cells, occupied: occupied.size, agents: t.state.count, voronoi: g.definition,
             legend: document.querySelector('#legend').textContent };
  });
  assert.equal(r.voronoi, 'voronoi');
  assert.ok(r.agents > 0 && r.total <= r.agents + 1e-6 && r.total >= 0.85 * r.agents - 1, `Voronoi map: ${JSON.stringify(r)}`);
  assert.ok(r.cells > r.occupied, `Voronoi cells spread over more grid cells (${r.cells}) than agents occupy (${r.occupied})`);
  assert.ok(r.legend.includes('density map (Voronoi)'), r.legend);
  await shot(page, 'viewer_density_voronoi.png');
  await page.keyboard.press('m');
  await page.selectOption('#heatmap-method', 'classic');
  assert.equal(await page.evaluate(() => globalThis.__throng.heatmap.grid.definition), 'classic');
}

/** The speed map (key G): its cells hold mean speeds of walkers (every sampled cell 0–3 m/s, their
 * sample-weighted mean 0.2–2 m/s: the museum's visitors walk and stop), it is drawn (the picture
 * changes with it hidden), the legend and the checkbox follow, G hides it. */
async function checkSpeedmap(page) {
  // From 14 m above the crowd's middle: the whole museum's few walking cells are a handful of pixels.
  await page.evaluate(() => {
    const { state, cameras } = globalThis.__throng;
    let cx = 0, cy = 0;
    for (let i = 0; i < state.count; ++i) { cx += state.x[i]; cy += state.y[i]; }
    if (state.count > 0) cameras.planAt(cx / state.count, cy / state.count, 14);
  });
  await page.keyboard.press('g');
  await page.waitForFunction(() => globalThis.__throng.speedmap.grid.frames.length >= 10, null, { timeout: 15000 });
  const r = await page.evaluate(() => {
    const t = globalThis.__throng, g = t.speedmap.grid;
    let cells = 0, samples = 0, weighted = 0, lo = Infinity, hi = -Infinity;
    for (let j = 0; j < g.ny; ++j) {
      for (let i = 0; i < g.nx; ++i) {
        const v = g.speed(i, j);
        if (v === null) continue;
        const n = g.sum[j * g.nx + i];
        ++cells; samples += n; weighted += v * n; lo = Math.min(lo, v); hi = Math.max(hi, v);
      }
    }
    const on = t.pixels(4).grey;
    t.speedmap.mesh.visible = false;
    const off = t.pixels(4).grey;
    t.speedmap.mesh.visible = true;
    let changed = 0;
    for (let i = 0; i < on.length; ++i) if (Math.abs(on[i] - off[i]) > 6) ++changed;
    return { cells, mean: weighted / samples, lo, hi, changed: changed / on.length,
             checked: document.querySelector('#speedmap-toggle').checked, legend: document.querySelector('#legend').textContent };
  });
  assert.ok(r.cells > 3 && r.lo >= 0 && r.hi <= 3 && r.mean > 0.2 && r.mean < 2, `speed map: ${JSON.stringify(r)}`);
  assert.ok(r.changed > 0.001, `the speed map shows (${(r.changed * 100).toFixed(2)} % of pixels)`);
  assert.ok(r.checked && r.legend.includes('speed map') && r.legend.includes('m/s'), `the Speed checkbox and the legend follow the key: ${r.checked} ${r.legend}`);
  await shot(page, 'viewer_speed_map.png');
  await page.keyboard.press('g');
  assert.equal(await page.evaluate(() => globalThis.__throng.speedmap.enabled), false);
}

/** The speed map's Voronoi definition (the maps' menu after Density and Speed): every cell someone's Voronoi cell
 * covers has a speed (0–3 m/s), so more cells than agents occupy; the legend says
 * "speed map (Voronoi)"; back to classic. */
async function checkVoronoiSpeedmap(page) {
  await page.selectOption('#heatmap-method', 'voronoi');
  await page.keyboard.press('g');
  await page.waitForFunction(() => globalThis.__throng.speedmap.grid.frames.length >= 10, null, { timeout: 20000 });
  const r = await page.evaluate(() => {
    const t = globalThis.__throng, g = t.speedmap.grid;
    let cells = 0, lo = Infinity, hi = -Infinity;
    for (let j = 0; j < g.ny; ++j) for (let i = 0; i < g.nx; ++i) {
      const v = g.speed(i, j);
      if (v === null) continue;
      ++cells; lo = Math.min(lo, v); hi = Math.max(hi, v);
    }
    const occupied = new Set();
    for (let k = 0; k < t.state.count; ++k) occupied.add(`${Math.floor((t.state.x[k] - g.minX) / g.cell)},${Math.floor((t.state.y[k] - g.minY) / g.cell)}`);
    return { cells, lo, hi, occupied: occupied.size, definition: g.definition, legend: document.querySelector('#legend').textContent };
  });
  assert.equal(r.definition, 'voronoi');
  assert.ok(r.lo >= 0 && r.hi <= 3, `Voronoi speeds: ${JSON.stringify(r)}`);
  assert.ok(r.cells > r.occupied, `Voronoi cells give speeds to more grid cells (${r.cells}) than agents occupy (${r.occupied})`);
  assert.ok(r.legend.includes('speed map (Voronoi)'), r.legend);
  await shot(page, 'viewer_speed_voronoi.png');
  await page.keyboard.press('g');
  await page.selectOption('#heatmap-method', 'classic');
  assert.equal(await page.evaluate(() => globalThis.__throng.speedmap.grid.definition), 'classic');
}

/** Opens `input` served by throng at 1280×720 (`query`: extra URL options); {server, browser, page, errors}. */
async function open(input, query = '') {
  const server = await startServer(path.join(repo, input));
  const browser = await launchBrowser();
  const errors = [];
  const page = await openViewer(browser, server.url + query, errors);
  await page.setViewportSize({ width: 1280, height: 720 });
  await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 0, null, { timeout: 30000 });
  await page.waitForTimeout(800);  // a few frames, the clips loaded
  return { server, browser, page, errors };
}

async function close(s) {
  if (s.browser) await s.browser.close();
  await stopServer(s.server);
}

for (const [input, name, minSegments] of [['scenarios/museum.json', 'museum', 8], ['scenarios/mall.json', 'mall', 200]]) {
  test(`${name}: walls along the walkable boundary, drawn in plan and orbit views`, { timeout: 90000 }, async () => {
    requirePrerequisites('world e2e');
    const s = await open(input, '?camera=plan');
    try {
      const parts = await s.page.evaluate(() => globalThis.__throng.worldParts());
      assert.ok(parts['boundary-walls'] >= minSegments, `boundary walls: ${JSON.stringify(parts)}`);
      if (name === 'mall') {
        // 99 walkable polygons with ~600 edges; where a shop's polygon overlaps the corridor's at its
        // door the edge is split and the door left open, so the walls are not simply every edge.
        const edges = await s.page.evaluate(() => globalThis.__throng.description.scenario.walkable.reduce((n, p) => n + p.length, 0));
        assert.notEqual(parts['boundary-walls'], edges, 'every polygon edge walled: doors closed');
      }
      const plan = await changedByPart(s.page, 'boundary-walls');
      assert.ok(plan > 0.004, `the walls show in plan view (${(plan * 100).toFixed(2)} % of pixels)`);
      if (name === 'museum') {
        // Its eight paintings hang on the walls their visitors face, seen from above as strips.
        assert.equal(parts.exhibits, 8, `paintings: ${JSON.stringify(parts)}`);
        assert.match(await s.page.evaluate(() => document.querySelector('#legend').textContent), /painting: what visitors/);
        const seen = await changedByPart(s.page, 'exhibits');
        assert.ok(seen > 0.0005, `the paintings show in plan view (${(seen * 100).toFixed(3)} % of pixels)`);
      }
      await shot(s.page, `viewer_walls_${name}_plan.png`);
      await s.page.keyboard.press('o');
      await s.page.waitForTimeout(500);
      const orbit = await changedByPart(s.page, 'boundary-walls');
      assert.ok(orbit > 0.01, `the walls show in the orbit view (${(orbit * 100).toFixed(2)} % of pixels)`);
      if (name === 'museum') {
        const seen = await changedByPart(s.page, 'exhibits');
        assert.ok(seen > 0.001, `the paintings show in the orbit view (${(seen * 100).toFixed(3)} % of pixels)`);
      }
      await shot(s.page, `viewer_walls_${name}_orbit.png`);
      if (name === 'museum') {
        // The scenario's description, for someone new to the world, under the HUD's name.
        const about = await s.page.evaluate(() => document.querySelector('#hud .hud-about').textContent);
        assert.ok(about.startsWith('A museum of three rooms'), `HUD description: ${about}`);
      }
      if (name === 'museum') await checkHeatmap(s.page);
      if (name === 'museum') await checkVoronoiMap(s.page);
      if (name === 'museum') await checkSpeedmap(s.page);
      if (name === 'museum') await checkVoronoiSpeedmap(s.page);
      assert.deepEqual(s.errors, []);
    } finally {
      await close(s);
    }
  });
}

test('two floors: risers on the stairs and railings along the gallery', { timeout: 90000 }, async () => {
  requirePrerequisites('world e2e');
  const s = await open('scenarios/two_floors.gltf', '?camera=orbit');
  try {
    const parts = await s.page.evaluate(() => globalThis.__throng.worldParts());
    assert.ok(parts['stair-risers'] >= 5, `stair risers: ${JSON.stringify(parts)}`);
    assert.ok(parts['terrain-railings'] >= 4, `railings: ${JSON.stringify(parts)}`);
    const risers = await changedByPart(s.page, 'stair-risers');
    const railings = await changedByPart(s.page, 'terrain-railings');
    assert.ok(risers > 0.001, `the risers show (${(risers * 100).toFixed(2)} % of pixels)`);
    assert.ok(railings > 0.01, `the railings show (${(railings * 100).toFixed(2)} % of pixels)`);
    await shot(s.page, 'viewer_walls_two_floors.png');
    // A glTF world says what it is too (its scene's extras carry the description).
    const about = await s.page.evaluate(() => document.querySelector('#hud .hud-about').textContent);
    assert.ok(about.startsWith('A two-storey hall'), `HUD description: ${about}`);
    assert.deepEqual(s.errors, []);
  } finally {
    await close(s);
  }
});
