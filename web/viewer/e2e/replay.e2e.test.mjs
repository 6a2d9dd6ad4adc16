// End-to-end test of replay in the browser viewer (issue 8): records 20 s of the museum with the
// built `throng run` (THRONG_EXE), serves the recording with `throng serve FILE.sqlite --port 0`,
// opens the viewer in Debian's headless chromium and checks: the timeline appears with the
// recording's duration (ReplayStatus); playing, the time advances and crowd frames arrive with
// agents drawn; Pause stops the time (and the crowd); scrubbing to a time jumps there (status time,
// frame ticks and positions — the same positions each time that moment is sought); a faster speed
// makes the time run faster; Join, Edit and Guide say what they do on a recording; the in-page
// demo replay (?demo&replay) offers nobody to join. Run: THRONG_EXE=build/apps/throng/throng node --test web/viewer/e2e/replay.e2e.test.mjs
// Fails (never skips) without THRONG_EXE, web/node_modules, web/dist or chromium, saying which.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { exe, repo, requirePrerequisites, sleep, startServer, stopServer, launchBrowser, openViewer } from './harness.mjs';

/** The page's view of the replay: last status, its log (with receipt times) and the last frame. */
function probe(page) {
  return page.evaluate(() => {
    const p = globalThis.__replayProbe;
    const f = p.frame;
    return { status: globalThis.__throng.source.replay, log: p.log.slice(), frames: p.frames,
      frame: f && { simTick: f.simTick, count: f.count, pos: Object.fromEntries([...f.ids].map((id, i) => [id, [f.x[i], f.y[i]]])) },
      drawn: globalThis.__throng.state.count, label: document.querySelector('#tl-time').textContent,
      playText: document.querySelector('#tl-play').textContent };
  });
}

/** Waits until the page's last ReplayStatus satisfies `pred` (a function source over `s`). */
function waitStatus(page, pred, timeout = 8000) {
  return page.waitForFunction(`(() => { const s = globalThis.__throng.source.replay; return !!s && (${pred}); })()`, null, { timeout });
}

/** Mean distance [m] between the agents two frames share, and how many they share. */
function moved(a, b) {
  let sum = 0, n = 0;
  for (const [id, p] of Object.entries(a.pos)) {
    const q = b.pos[id];
    if (!q) continue;
    sum += Math.hypot(p[0] - q[0], p[1] - q[1]);
    n++;
  }
  return { mean: n ? sum / n : 0, n };
}

/** Seeks with the timeline's slider (an input event, as dragging it does) to `t` seconds. */
async function scrubTo(page, t, duration) {
  await page.evaluate((v) => {
    const s = document.querySelector('#tl-scrub');
    s.value = String(v);
    s.dispatchEvent(new Event('input', { bubbles: true }));
    s.dispatchEvent(new Event('change', { bubbles: true }));
  }, Math.round((t / duration) * 1000));
}

/** Frame ticks → seconds of the recording. */
async function frameAfter(page, frames) {
  await page.waitForFunction((n) => globalThis.__replayProbe.frames > n, frames, { timeout: 8000 });
  await sleep(400);  // a few frames at the new time (delta-coded frames settle)
  return probe(page);
}

test('viewer replays a recording from throng serve FILE.sqlite', { timeout: 60000 }, async () => {
  requirePrerequisites('replay e2e');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-replay-e2e-'));
  const file = path.join(dir, 'museum.sqlite');
  const rec = spawnSync(exe, ['run', path.join(repo, 'scenarios/museum.json'), '--duration', '20', '--out', file, '--quiet'],
    { encoding: 'utf8', timeout: 30000 });
  assert.equal(rec.status, 0, `throng run: ${rec.stderr}`);
  const server = await startServer(file);
  let browser;
  const errors = [];
  try {
    browser = await launchBrowser();
    const page = await openViewer(browser, server.url, errors);
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.source, null, { timeout: 20000 });
    await page.evaluate(() => {
      const p = globalThis.__replayProbe = { log: [], frames: 0, frame: null };
      const src = globalThis.__throng.source;
      src.on('timeline', (s) => p.log.push({ ...s, at: performance.now() }));
      src.on('frame', (f) => { p.frames++; p.frame = f; });
    });

    // The timeline appears with the recording's duration (the world description says it too).
    await page.waitForFunction(() => !document.querySelector('#timeline').classList.contains('hidden')
      && globalThis.__throng.source.replay, null, { timeout: 15000 });
    const info = await page.evaluate(() => ({ replay: globalThis.__throng.description.replay, kind: globalThis.__throng.source.kind }));
    assert.equal(info.kind, 'replay');
    let p = await probe(page);
    assert.ok(Math.abs(p.status.duration - 20) < 1, `duration ${p.status.duration} s (world: ${JSON.stringify(info.replay)})`);
    assert.match(p.label, /\/ 0:2[01]$/, `timeline label "${p.label}"`);

    // The controls say what they do on a recording: Join walks among a crowd that does not react,
    // Edit opens the scenario it was made from, its groups cannot be guided.
    const controls = await page.evaluate(() => ({
      join: { disabled: document.querySelector('#join-button').disabled, title: document.querySelector('#join-button').title },
      status: document.querySelector('#join-status').textContent, edit: document.querySelector('#edit-link').title,
      guide: { disabled: document.querySelector('#guide-button').disabled, title: document.querySelector('#guide-button').title },
    }));
    assert.ok(!controls.join.disabled && /do not react/.test(controls.join.title), JSON.stringify(controls));
    assert.match(controls.status, /a recording/);
    assert.match(controls.edit, /scenario this recording was made from/);
    assert.ok(controls.guide.disabled && /recording cannot be guided/.test(controls.guide.title), JSON.stringify(controls));

    // Play (if it does not already): the time advances, frames arrive, agents are drawn.
    if (!p.status.playing) await page.click('#tl-play');
    await waitStatus(page, 's.playing');
    const t0 = (await probe(page)).status.time;
    await waitStatus(page, `s.time > ${t0 + 1}`, 6000);
    await page.waitForFunction(() => globalThis.__replayProbe.frames > 5, null, { timeout: 5000 });
    p = await probe(page);
    assert.ok(p.frames > 5 && p.drawn > 5, `frames ${p.frames}, agents drawn ${p.drawn}`);
    assert.equal(p.playText, '❚❚', 'the play button shows pause while playing');

    // Pause: the time stops, and so does the crowd.
    await page.click('#tl-play');
    await waitStatus(page, '!s.playing');
    const paused = await frameAfter(page, (await probe(page)).frames);
    await sleep(1500);
    const still = await probe(page);
    assert.ok(Math.abs(still.status.time - paused.status.time) < 1e-6, `paused at ${paused.status.time} s, then ${still.status.time} s`);
    assert.equal(still.playText, '▶');
    if (still.frame.simTick === paused.frame.simTick) {
      assert.ok(moved(paused.frame, still.frame).mean < 1e-3, 'the crowd stands still while paused');
    }

    // Scrub to 15 s: the status and the frames jump there; the agents are elsewhere.
    const duration = p.status.duration;
    const before = still;
    await scrubTo(page, 15, duration);
    await waitStatus(page, 'Math.abs(s.time - 15) < 0.2');
    const at15 = await frameAfter(page, before.frames);
    assert.ok(!at15.status.playing, 'seeking while paused stays paused');
    assert.match(at15.label, /^0:1[45] \//, `timeline label "${at15.label}"`);
    const jump = moved(before.frame, at15.frame);
    assert.ok(jump.mean > 1, `agents jumped ${jump.mean.toFixed(2)} m (${jump.n} shared) from ${before.status.time.toFixed(1)} s to 15 s`);
    // Back to 3 s and to 15 s again: the same positions as the first time at 15 s.
    await scrubTo(page, 3, duration);
    await waitStatus(page, 'Math.abs(s.time - 3) < 0.2');
    const at3 = await frameAfter(page, at15.frames);
    assert.ok(moved(at3.frame, at15.frame).mean > 1, 'at 3 s the agents are elsewhere');
    await scrubTo(page, 15, duration);
    await waitStatus(page, 'Math.abs(s.time - 15) < 0.2');
    const again = await frameAfter(page, at3.frames);
    const same = moved(at15.frame, again.frame);
    assert.ok(same.n > 5 && same.mean < 0.3, `seeking 15 s twice shows the same crowd (mean difference ${same.mean.toFixed(3)} m over ${same.n})`);
    assert.ok(at3.frame.simTick < at15.frame.simTick && Math.abs(again.frame.simTick - at15.frame.simTick) <= 2,
      `frame ticks follow the seeks: ${at15.frame.simTick} (15 s), ${at3.frame.simTick} (3 s), ${again.frame.simTick} (15 s)`);

    // Speed: 4× from 2 s runs the time about four times faster than the wall clock.
    await scrubTo(page, 2, duration);
    await waitStatus(page, 'Math.abs(s.time - 2) < 0.2');
    await page.selectOption('#tl-speed', '4');
    await waitStatus(page, 's.speed === 4');
    const n0 = (await probe(page)).log.length;
    await page.click('#tl-play');
    await waitStatus(page, 's.playing');
    await sleep(2500);
    const log = (await probe(page)).log.slice(n0).filter((s) => s.playing && s.speed === 4);
    assert.ok(log.length >= 2, `status while playing at 4×: ${JSON.stringify(log)}`);
    const a = log[0], b = log[log.length - 1];
    const measured = (b.time - a.time) / ((b.at - a.at) / 1000);
    assert.ok(measured > 2.5 && measured < 6, `time runs at ${measured.toFixed(2)}× the wall clock at speed 4`);
    assert.deepEqual(errors.filter((e) => !/WebSocket|Failed to load resource/.test(e)), [], 'no page errors');
  } finally {
    if (browser) await browser.close();
    await stopServer(server);
    fs.rmSync(dir, { recursive: true, force: true });
  }
});

test('the in-page demo replay (?demo&replay) offers nobody to join and raises no page error', { timeout: 60000 }, async () => {
  requirePrerequisites('replay e2e');
  const server = await startServer(path.join(repo, 'scenarios/museum.json'));
  let browser;
  const errors = [];
  try {
    browser = await launchBrowser();
    const page = await openViewer(browser, `${server.url}?demo&replay`, errors);
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.source
      && !document.querySelector('#timeline').classList.contains('hidden'), null, { timeout: 20000 });
    const join = await page.evaluate(() => ({ disabled: document.querySelector('#join-button').disabled,
      status: document.querySelector('#join-status').textContent }));
    assert.ok(join.disabled, `Join is off: ${JSON.stringify(join)}`);
    assert.match(join.status, /nobody to join/);
    assert.deepEqual(errors, []);
  } finally {
    if (browser) await browser.close();
    await stopServer(server);
  }
});
