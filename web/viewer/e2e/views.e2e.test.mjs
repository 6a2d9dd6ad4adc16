// End-to-end test of the viewer's cameras and picking (issue 20) against a real `throng serve
// scenarios/museum.json` in Debian's headless chromium: the 48 m museum opens in plan view
// (orthographic, top-down) with the whole walkable area on screen; clicking agents selects them in
// the zoomed-out plan, a close plan, a low oblique and a steep oblique orbit view (each click must
// select the agent under the pointer: the pick used to test only the side of a cylinder and missed
// every top-down click); F fits the world again after zooming; T follows the selected agent; C
// cycles plan → orbit → walk. Run: THRONG_EXE=build/apps/throng/throng node --test
// web/viewer/e2e/views.e2e.test.mjs (THRONG_E2E_SHOTS=DIR keeps screenshots). Fails, like the other
// e2e tests, when something it needs is missing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { repo, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer, sleep } from './harness.mjs';

const shotsDir = process.env.THRONG_E2E_SHOTS || '';
export async function shot(page, name) {
  if (!shotsDir) return;
  fs.mkdirSync(shotsDir, { recursive: true });
  await page.screenshot({ path: path.join(shotsDir, name) });
}

/** Up to `n` agents drawn on the bare canvas (no panel over them), at least `gap` px from any other
 * agent on screen: [{id, x, y}] (screen px, the body's middle). */
export function clickable(page, n, gap = 5) {
  return page.evaluate(([n, gap]) => {
    const { state, toScreen } = globalThis.__throng;
    const pts = [];
    for (let i = 0; i < state.count; ++i) {
      const p = toScreen(state.x[i], state.y[i], state.z[i] + 0.9);
      if (p) pts.push({ id: state.ids[i], x: p.x, y: p.y });
    }
    const out = [];
    for (const p of pts) {
      if (p.x < 8 || p.y < 8 || p.x > innerWidth - 8 || p.y > innerHeight - 8) continue;
      if (document.elementFromPoint(p.x, p.y) !== document.querySelector('#app canvas')) continue;
      if (pts.some((q) => q !== p && Math.hypot(q.x - p.x, q.y - p.y) < gap)) continue;
      out.push(p);
      if (out.length >= n) break;
    }
    return out;
  }, [n, gap]);
}

/** Clicks each agent where it is drawn now; returns [{want, got}] (got: the selected id, or null). */
export async function clickAgents(page, n) {
  const results = [];
  for (let k = 0; k < n; ++k) {
    await page.evaluate(() => { document.querySelector('#agent-close').click(); });
    const [t] = await clickable(page, 1 + k).then((a) => a.slice(k));
    if (!t) break;
    await page.mouse.click(t.x, t.y);
    const got = await page.waitForFunction(() => {
      const p = document.querySelector('#agent-panel');
      return !p.classList.contains('hidden') && document.querySelector('#agent-id').textContent;
    }, null, { timeout: 1500 }).then((h) => h.jsonValue(), () => null);
    results.push({ want: `#${t.id}`, got });
  }
  return results;
}

/** Screen rectangle covered by the world's walkable bounds in the current camera. */
function worldOnScreen(page) {
  return page.evaluate(() => {
    const { cameras, toScreen } = globalThis.__throng;
    const b = cameras.bounds;
    const c = [[b.minX, b.minY], [b.maxX, b.minY], [b.minX, b.maxY], [b.maxX, b.maxY]].map(([x, y]) => toScreen(x, y, 0));
    return { left: Math.min(...c.map((p) => p.x)), right: Math.max(...c.map((p) => p.x)),
      top: Math.min(...c.map((p) => p.y)), bottom: Math.max(...c.map((p) => p.y)), w: innerWidth, h: innerHeight };
  });
}

function assertFits(r, what) {
  assert.ok(r.left >= -1 && r.top >= -1 && r.right <= r.w + 1 && r.bottom <= r.h + 1, `${what}: the world is on screen ${JSON.stringify(r)}`);
  assert.ok(r.right - r.left > 0.6 * r.w || r.bottom - r.top > 0.6 * r.h, `${what}: the world fills the view ${JSON.stringify(r)}`);
}

function assertAllSelected(results, what, atLeast) {
  assert.ok(results.length >= atLeast, `${what}: ${results.length} agents to click (want ${atLeast})`);
  const wrong = results.filter((r) => r.got !== r.want);
  assert.deepEqual(wrong, [], `${what}: every click selects the agent under it (${results.length - wrong.length} of ${results.length})`);
}

test('plan view, fit, follow and picking from every angle', { timeout: 120000 }, async () => {
  requirePrerequisites('views e2e');
  const server = await startServer(path.join(repo, 'scenarios/museum.json'));
  const browser = await launchBrowser();
  const errors = [];
  try {
    const page = await openViewer(browser, server.url, errors);
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 12, null, { timeout: 45000 });
    const first = await page.evaluate(() => ({ mode: globalThis.__throng.cameras.mode, ortho: globalThis.__throng.camera.isOrthographicCamera }));
    assert.deepEqual(first, { mode: 'plan', ortho: true }, 'the 48 m museum opens in plan view');
    assert.ok(await page.evaluate(() => document.querySelector('#cam-plan').classList.contains('active')), 'the Plan button is lit');
    assertFits(await worldOnScreen(page), 'plan view at start');
    await shot(page, 'views_plan.png');

    // Zoomed-out plan: each body a few pixels wide.
    assertAllSelected(await clickAgents(page, 5), 'zoomed-out plan', 3);

    // Close plan around the crowd's centre.
    await page.evaluate(() => {
      const { state, cameras } = globalThis.__throng;
      let cx = 0, cy = 0;
      for (let i = 0; i < state.count; ++i) { cx += state.x[i]; cy += state.y[i]; }
      cameras.planAt(cx / state.count, cy / state.count, 14);
    });
    await sleep(300);
    assertAllSelected(await clickAgents(page, 4), 'close plan', 2);

    // F fits the world again.
    await page.mouse.click(5, 355);
    await page.keyboard.press('KeyF');
    await sleep(200);
    assertFits(await worldOnScreen(page), 'plan view after F');

    // Low and steep oblique orbit views.
    for (const [distance, height, what] of [[9, 4, 'low oblique'], [6, 12, 'steep oblique']]) {
      await page.evaluate(([d, h]) => {
        const { state, cameras } = globalThis.__throng;
        let cx = 0, cy = 0;
        for (let i = 0; i < state.count; ++i) { cx += state.x[i]; cy += state.y[i]; }
        cameras.lookAt(cx / state.count, cy / state.count, d, h);
      }, [distance, height]);
      await sleep(300);
      assert.equal(await page.evaluate(() => globalThis.__throng.camera.isPerspectiveCamera), true, `${what}: perspective camera`);
      assertAllSelected(await clickAgents(page, 3), what, 1);
      await shot(page, `views_${what.replace(' ', '_')}.png`);
    }

    // T follows the selected agent: after it walks, the orbit target is still on it.
    const [t] = await clickable(page, 1);
    await page.mouse.click(t.x, t.y);
    await page.waitForFunction(() => !document.querySelector('#agent-panel').classList.contains('hidden'), null, { timeout: 2000 });
    await page.keyboard.press('KeyT');
    await sleep(2500);
    const follow = await page.evaluate((id) => {
      const { state, cameras } = globalThis.__throng;
      const i = state.index.get(id);
      const tg = cameras.orbit.target;
      return { following: !!cameras.following, off: i === undefined ? null : Math.hypot(tg.x - state.x[i], -tg.z - state.y[i]),
        status: document.querySelector('#camera-status').textContent };
    }, t.id);
    assert.ok(follow.following && follow.off !== null && follow.off < 0.6, `the camera follows agent ${t.id}: ${JSON.stringify(follow)}`);
    await page.keyboard.press('KeyT');
    assert.equal(await page.evaluate(() => !!globalThis.__throng.cameras.following), false, 'T again stops following');

    // C cycles the cameras.
    const modes = [];
    for (let k = 0; k < 3; ++k) { await page.keyboard.press('KeyC'); modes.push(await page.evaluate(() => globalThis.__throng.cameras.mode)); }
    assert.deepEqual(modes, ['walk', 'plan', 'orbit'], 'C: orbit → walk → plan → orbit');
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
  }
});
