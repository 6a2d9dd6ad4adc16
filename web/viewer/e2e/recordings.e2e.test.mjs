// End-to-end test of recordings from the page (issue 20): `throng serve DIR/museum.sqlite
// --recordings DIR` with a museum recording in DIR, two viewers. The first lists DIR (the row
// appears with museum.sqlite marked as playing, its scenario and duration), uploads a file that is no recording (one
// message naming what was wrong; nothing added to DIR), uploads a bottleneck recording (stored,
// listed and picked), and opens it: the server plays it for every viewer — both pages reload by
// themselves into the bottleneck (HUD, world description, the timeline's 0:08) and crowd frames of
// its agents arrive; GET /api/recordings says it is playing. Run:
// THRONG_EXE=build/apps/throng/throng node --test web/viewer/e2e/recordings.e2e.test.mjs
// Fails (never skips) without THRONG_EXE, web/node_modules, web/dist or chromium, saying which.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { exe, repo, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer } from './harness.mjs';

function record(scenario, seconds, out) {
  const r = spawnSync(exe, ['run', path.join(repo, 'scenarios', scenario), '--duration', String(seconds), '--out', out, '--quiet'],
    { encoding: 'utf8', timeout: 60000 });
  assert.equal(r.status, 0, `throng run ${scenario}: ${r.stderr}`);
}

/** Resolves once the page shows the world `name` (after a reload too) with crowd frames arriving. */
async function waitForWorld(page, name, timeout = 30000) {
  await page.waitForFunction((n) => {
    const t = globalThis.__throng;
    return !!t && t.hud && t.hud.world && t.hud.world.name === n && (globalThis.__throngStats?.crowdFrames || 0) > 3;
  }, name, { timeout });
}

test('viewer lists, uploads and opens recordings (throng serve --recordings)', { timeout: 120000 }, async () => {
  requirePrerequisites('recordings e2e');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-recordings-e2e-'));
  const elsewhere = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-recordings-src-'));
  record('museum.json', 10, path.join(dir, 'museum.sqlite'));
  const bottleneck = path.join(elsewhere, 'my bottleneck.sqlite');
  record('bottleneck.json', 8, bottleneck);
  const notRecording = path.join(elsewhere, 'notes.sqlite');
  fs.copyFileSync(path.join(repo, 'scenarios/museum.json'), notRecording);

  const server = await startServer(path.join(dir, 'museum.sqlite'), 0, ['--recordings', dir]);
  let browser;
  const errors = [];
  try {
    browser = await launchBrowser();
    const page = await openViewer(browser, server.url, errors);
    const other = await openViewer(browser, server.url, errors);
    await waitForWorld(page, 'museum');
    await waitForWorld(other, 'museum');

    // The list: DIR's one recording, with its scenario and duration.
    await page.waitForSelector('#recordings-row:not(.hidden)', { timeout: 10000 });
    const options = await page.$$eval('#rec-list option', (os) => os.map((o) => o.textContent));
    assert.equal(options.length, 1, options.join(' | '));
    assert.match(options[0], /^▶ museum\.sqlite — museum, 0:10, \d+ agents/, 'the recording served is marked as playing');

    // A file that is no recording: one message saying what was wrong, nothing stored.
    await page.setInputFiles('#rec-upload', notRecording);
    await page.waitForFunction(() => document.querySelector('#rec-status').classList.contains('error'), null, { timeout: 15000 });
    const refused = await page.textContent('#rec-status');
    assert.match(refused, /notes\.sqlite: not a SQLite file/);
    assert.deepEqual(fs.readdirSync(dir), ['museum.sqlite']);

    // The bottleneck recording: stored under a safe name, listed and picked.
    await page.setInputFiles('#rec-upload', bottleneck);
    await page.waitForFunction(() => /stored as/.test(document.querySelector('#rec-status').textContent), null, { timeout: 30000 });
    assert.deepEqual(fs.readdirSync(dir).sort(), ['museum.sqlite', 'my_bottleneck.sqlite']);
    assert.equal(fs.readFileSync(path.join(dir, 'my_bottleneck.sqlite')).compare(fs.readFileSync(bottleneck)), 0);
    assert.equal(await page.inputValue('#rec-list'), 'my_bottleneck.sqlite');
    const listed = await page.$$eval('#rec-list option', (os) => os.map((o) => o.textContent));
    assert.ok(listed.some((t) => /my_bottleneck\.sqlite — bottleneck, 0:08/.test(t)), listed.join(' | '));

    // Open: the server plays it for everyone; both pages reload into the bottleneck.
    await Promise.all([page.waitForEvent('load', { timeout: 30000 }), other.waitForEvent('load', { timeout: 30000 }),
      page.click('#rec-open')]);
    await waitForWorld(page, 'bottleneck');
    await waitForWorld(other, 'bottleneck');
    for (const p of [page, other]) {
      await p.waitForFunction(() => /\/ 0:08/.test(document.querySelector('#tl-time').textContent), null, { timeout: 10000 });
      const world = await p.evaluate(() => globalThis.__throng.source.world);
      assert.equal(world.replay.duration, 8);
    }
    const answer = await (await fetch(`${server.url}api/recordings`)).json();
    assert.equal(answer.playing, 'my_bottleneck.sqlite');
    // Started with a recording, the server has no live scenario to go back to: no Live button, and
    // POST /api/recordings/live is refused (live.e2e.test.mjs has one).
    assert.equal(answer.live, null);
    assert.ok(await page.$eval('#rec-live', (b) => b.classList.contains('hidden')), 'no Live button');
    const noLive = await fetch(`${server.url}api/recordings/live`, { method: 'POST' });
    assert.equal(noLive.status, 409);
    assert.match((await noLive.json()).error, /started with a recording: there is no live scenario/);
    // The page's list marks it as playing.
    await page.waitForSelector('#recordings-row:not(.hidden)', { timeout: 10000 });
    const marked = await page.$$eval('#rec-list option', (os) => os.map((o) => o.textContent));
    assert.ok(marked.some((t) => t.startsWith('▶ my_bottleneck.sqlite')), marked.join(' | '));
    // The browser logs the refused upload's 422 itself; nothing else may go wrong.
    assert.deepEqual(errors.filter((e) => !/status of 422/.test(e)), []);
  } finally {
    if (browser) await browser.close();
    await stopServer(server);
    fs.rmSync(dir, { recursive: true, force: true });
    fs.rmSync(elsewhere, { recursive: true, force: true });
  }
});
