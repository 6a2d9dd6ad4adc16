// End-to-end test of a multi-level world in the browser viewer (issue 9): `throng serve
// scenarios/two_floors.gltf` (a hall and a gallery 3 m above it, joined by stairs and a ramp) in
// Debian's headless chromium. Checks: the world description carries the terrain; crowd frames bring
// agents at both floor heights (the gallery's guests start upstairs, the visitors downstairs) and,
// within 40 s, some agent between the floors (on the stairs or the ramp); the picture is not blank;
// a participant who joins stands on the terrain's walking surface, at a height from 0 to 3 m (the
// server's /api/status sees the participant). Run: THRONG_EXE=build/apps/throng/throng node --test
// web/viewer/e2e/levels.e2e.test.mjs. Fails, like the other e2e tests, when something it needs is missing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { repo, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer, sleep } from './harness.mjs';

/** Heights of the agents the viewer holds now. */
function heights(page) {
  return page.evaluate(() => {
    const s = globalThis.__throng.state;
    return Array.from(s.z.subarray(0, s.count));
  });
}

test('viewer shows a two-floor world with agents at their heights', { timeout: 90000 }, async () => {
  requirePrerequisites('levels e2e');
  const server = await startServer(path.join(repo, 'scenarios/two_floors.gltf'));
  const browser = await launchBrowser();
  const errors = [];
  try {
    const page = await openViewer(browser, server.url, errors);
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 0, null, { timeout: 30000 });
    const terrain = await page.evaluate(() => {
      const t = globalThis.__throng.description.scenario.terrain;
      return t ? { vertices: t.vertices.length, walkable: t.walkable.length } : null;
    });
    assert.ok(terrain && terrain.vertices > 0 && terrain.walkable > 0, `terrain in the world description: ${JSON.stringify(terrain)}`);

    // Both floors at once, then someone between them.
    let z = await heights(page);
    const deadline = Date.now() + 40000;
    let between = z.some((h) => h > 0.3 && h < 2.7);
    while (!between && Date.now() < deadline) {
      await sleep(500);
      z = await heights(page);
      between = z.some((h) => h > 0.3 && h < 2.7);
    }
    assert.ok(z.some((h) => h < 0.2), `an agent on the hall floor: ${z.map((h) => h.toFixed(2)).join(' ')}`);
    assert.ok(between, 'an agent on the stairs or the ramp within 40 s');
    const upstairs = await page.waitForFunction(() => {
      const s = globalThis.__throng.state;
      return Array.from(s.z.subarray(0, s.count)).some((h) => h > 2.8);
    }, null, { timeout: 40000 }).then(() => true, () => false);
    assert.ok(upstairs, 'an agent on the gallery (3 m)');

    // The plan view flattens the floors: those upstairs get a white rim, and the legend says so.
    await page.click('#cam-plan');
    await sleep(400);
    const plan = await page.evaluate(() => {
      const { crowd, state } = globalThis.__throng;
      const up = Array.from(state.z.subarray(0, state.count)).filter((h) => h > 1.2).length;
      return { marked: crowd.discs.upperCount, up, drawn: crowd.discs.count, legend: document.querySelector('#legend').textContent };
    });
    assert.ok(plan.drawn > 0 && plan.marked > 0, `upper-floor discs in the plan view: ${JSON.stringify(plan)}`);
    assert.ok(Math.abs(plan.marked - plan.up) <= 2, `those marked are those upstairs: ${JSON.stringify(plan)}`);
    assert.ok(plan.legend.includes('white rim = on an upper floor'), plan.legend);
    // Joining from here: the avatar stands on a floor even where the view's centre is over none.

    const { grey } = await page.evaluate(() => globalThis.__throng.pixels(8));
    const mean = grey.reduce((a, b) => a + b, 0) / grey.length;
    const spread = grey.reduce((a, b) => a + (b - mean) ** 2, 0) / grey.length;
    assert.ok(spread > 20, `the picture is not blank (grey variance ${spread.toFixed(1)})`);

    // A participant stands on a floor of the terrain and its Move carries that height.
    await page.fill('#join-name', 'e2e-levels');
    await page.click('#join-button');
    await page.waitForFunction(() => globalThis.__throng.joined !== null, null, { timeout: 15000 });
    const avatar = await page.evaluate(() => ({ ...globalThis.__throng.cameras.avatar }));
    assert.ok(avatar.onTerrain, `the avatar stands on the terrain: ${JSON.stringify(avatar)}`);
    assert.ok(avatar.z > -0.05 && avatar.z < 3.05, `on the building's walking surface (0 to 3 m): z = ${avatar.z}`);
    const status = await (await fetch(`${server.url}api/status`)).json();
    assert.equal(status.participants, 1, JSON.stringify(status));
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
  }
});
