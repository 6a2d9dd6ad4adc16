// End-to-end test of the trails of a large crowd (issue 20: 30 fps at 10,000 agents with trails on
// the software renderer): the viewer's demo crowd of 10,000 agents (`?demo&agents=10000&trails=1`,
// the page served by a real `throng serve`) in Debian's headless chromium draws its trails into the
// raster on the floor (src/crowd/trail_map.js), not as lines: tens of thousands of segments drawn
// into it, none as lines, and the same frame read back with and without the map differs over more
// than 2 % of the picture. Run: THRONG_EXE=build/apps/throng/throng node --test
// web/viewer/e2e/trails.e2e.test.mjs (THRONG_E2E_SHOTS=DIR keeps a screenshot).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { repo, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer, sleep } from './harness.mjs';

const shotsDir = process.env.THRONG_E2E_SHOTS || '';

test('10,000 agents leave their trails in the floor raster', { timeout: 120000 }, async () => {
  requirePrerequisites('trails.e2e');
  const server = await startServer(path.join(repo, 'scenarios/museum.json'));
  const browser = await launchBrowser();
  const errors = [];
  try {
    const page = await openViewer(browser, `${server.url}?demo&agents=10000&trails=1&camera=orbit`, errors);
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.trails.mode === 'map'
      && globalThis.__throng.trails.mapSegments > 20000, null, { timeout: 60000 });
    await page.evaluate(() => { const { cameras, state } = globalThis.__throng; cameras.lookAt(state.x[0], state.y[0], 25, 18); });
    await sleep(1500);
    if (shotsDir) { fs.mkdirSync(shotsDir, { recursive: true }); await page.screenshot({ path: path.join(shotsDir, 'viewer_trails_10k.png') }); }
    const r = await page.evaluate(() => {
      const t = globalThis.__throng;
      const on = t.pixels(4).grey;
      t.trails.map.visible = false;
      const off = t.pixels(4).grey;
      t.trails.map.visible = true;
      let changed = 0;
      for (let i = 0; i < on.length; ++i) if (Math.abs(on[i] - off[i]) > 12) changed++;
      return { changed: changed / on.length, lines: t.trails.segments, drawn: t.trails.mapSegments, enabled: t.trails.enabled };
    });
    assert.ok(r.enabled && r.lines === 0, `trails on, no lines: ${JSON.stringify(r)}`);
    assert.ok(r.changed > 0.02, `the trails show over ${(r.changed * 100).toFixed(1)} % of the picture`);
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
  }
});
