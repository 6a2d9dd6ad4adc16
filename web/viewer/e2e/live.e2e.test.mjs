// End-to-end test of going back from a recording to the live scenario without a restart (issue
// 20): `throng serve scenarios/museum.json --recordings DIR`, DIR holding a bottleneck recording,
// two viewers. While the museum runs live, /api/recordings names it as the live scenario, nothing
// is playing, the Live button is hidden and POST /api/recordings/live is refused (already live).
// The first viewer opens the recording: both reload into the bottleneck's replay and the Live
// button appears. Live: both reload into the live museum — crowd frames arriving, no timeline, the
// HUD's clock "of 5:00" of the scenario (not the recording's 0:08), /api/status counting both as
// clients, /api/recordings playing nothing — and the button hides again.
// Run: THRONG_EXE=build/apps/throng/throng node --test web/viewer/e2e/live.e2e.test.mjs
// Fails (never skips) without THRONG_EXE, web/node_modules, web/dist or chromium, saying which.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { exe, repo, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer, sleep } from './harness.mjs';

/** Resolves once the page shows the world `name` (after a reload too) with crowd frames arriving. */
async function waitForWorld(page, name, timeout = 30000) {
  await page.waitForFunction((n) => {
    const t = globalThis.__throng;
    return !!t && t.hud && t.hud.world && t.hud.world.name === n && (globalThis.__throngStats?.crowdFrames || 0) > 3;
  }, name, { timeout });
}

const liveHidden = (page) => page.$eval('#rec-live', (b) => b.classList.contains('hidden'));

test('Live goes back from a recording to the live scenario for every viewer', { timeout: 150000 }, async () => {
  requirePrerequisites('live e2e');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-live-e2e-'));
  const r = spawnSync(exe, ['run', path.join(repo, 'scenarios/bottleneck.json'), '--duration', '8', '--out', path.join(dir, 'bottleneck.sqlite'), '--quiet'],
    { encoding: 'utf8', timeout: 60000 });
  assert.equal(r.status, 0, `throng run bottleneck: ${r.stderr}`);
  const server = await startServer(path.join(repo, 'scenarios/museum.json'), 0, ['--recordings', dir]);
  let browser;
  const errors = [];
  try {
    browser = await launchBrowser();
    const page = await openViewer(browser, server.url, errors);
    const other = await openViewer(browser, server.url, errors);
    await waitForWorld(page, 'museum');
    await waitForWorld(other, 'museum');
    await page.waitForSelector('#recordings-row:not(.hidden)', { timeout: 10000 });

    // Live already: the listing names the live scenario, nothing plays, no Live button, a request refused.
    let listing = await (await fetch(`${server.url}api/recordings`)).json();
    assert.equal(listing.live, 'museum.json');
    assert.equal(listing.playing, null);
    assert.ok(await liveHidden(page), 'no Live button while the live scenario runs');
    const already = await fetch(`${server.url}api/recordings/live`, { method: 'POST' });
    assert.equal(already.status, 409);
    assert.match((await already.json()).error, /museum\.json is already playing/);

    // Open the recording: both pages reload into the bottleneck's replay; Live appears.
    await page.selectOption('#rec-list', 'bottleneck.sqlite');
    await Promise.all([page.waitForEvent('load', { timeout: 30000 }), other.waitForEvent('load', { timeout: 30000 }),
      page.click('#rec-open')]);
    await waitForWorld(page, 'bottleneck');
    await waitForWorld(other, 'bottleneck');
    await page.waitForFunction(() => /\/ 0:08/.test(document.querySelector('#tl-time').textContent), null, { timeout: 10000 });
    await page.waitForSelector('#rec-live:not(.hidden)', { timeout: 10000 });
    listing = await (await fetch(`${server.url}api/recordings`)).json();
    assert.equal(listing.playing, 'bottleneck.sqlite');

    // Live: both pages reload into the live museum.
    await Promise.all([page.waitForEvent('load', { timeout: 30000 }), other.waitForEvent('load', { timeout: 30000 }),
      page.click('#rec-live')]);
    await waitForWorld(page, 'museum');
    await waitForWorld(other, 'museum');
    for (const p of [page, other]) {
      await p.waitForFunction(() => /time +\d+:\d\d of 5:00/.test(globalThis.__throng.hud.text()), null, { timeout: 10000 })
        .catch(() => {});  // the assertion below says what the HUD shows instead
      const seen = await p.evaluate(() => ({ replay: !!globalThis.__throng.source.world.replay,
        timeline: !document.querySelector('#timeline').classList.contains('hidden'), hud: globalThis.__throng.hud.text() }));
      assert.equal(seen.replay, false, 'the world description is the live one');
      assert.equal(seen.timeline, false, 'no replay timeline');
      assert.match(seen.hud, /time +\d+:\d\d of 5:00/, `the live scenario's clock: ${seen.hud}`);
      const f0 = await p.evaluate(() => globalThis.__throngStats.crowdFrames);
      await sleep(1000);
      assert.ok(await p.evaluate(() => globalThis.__throngStats.crowdFrames) > f0, 'crowd frames keep arriving');
    }
    listing = await (await fetch(`${server.url}api/recordings`)).json();
    assert.equal(listing.playing, null);
    assert.equal(listing.live, 'museum.json');
    const status = await (await fetch(`${server.url}api/status`)).json();
    assert.equal(status.clients, 2, JSON.stringify(status));
    await page.waitForSelector('#recordings-row:not(.hidden)', { timeout: 10000 });
    assert.ok(await liveHidden(page), 'the Live button hides again');
    assert.deepEqual(errors, []);
  } finally {
    if (browser) await browser.close();
    await stopServer(server);
    fs.rmSync(dir, { recursive: true, force: true });
  }
});
