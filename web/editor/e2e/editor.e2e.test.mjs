// End-to-end test of the scenario editor (docs/editor.md): the built `throng edit` (THRONG_EXE) on a
// fresh file in a temporary directory, Debian's headless chromium (playwright-core) driving the page
// with the mouse and keyboard as a user would. From an empty page: draw a walkable room, walls that
// leave a door, close the door with a third wall, draw an exit behind it and a crowd whose goal is
// the exit (picked by clicking it); the check reports the unreachable goal on the plan and in the
// list; deleting the door's wall fixes it; the preview's frames arrive and its agents move; Ctrl+S
// saves; the saved file passes `throng check` and `throng run --duration 5`. Every step must
// succeed or the test fails. THRONG_EDITOR_SHOT=FILE.png also saves a screenshot (docs/img).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { exe, launchBrowser, requirePrerequisites, sleep, stopServer } from '../../viewer/e2e/harness.mjs';
import { click, drag, openEditor, startEditor, waitForCheck } from './helpers.mjs';

test('a room with a door, a crowd and an exit, from an empty page to a file that runs', { timeout: 180000 }, async () => {
  requirePrerequisites('editor e2e');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-editor-'));
  const file = path.join(dir, 'room.json');
  const server = await startEditor(file);
  const browser = await launchBrowser();
  const errors = [];
  try {
    const page = await openEditor(browser, server, 'room.json', errors);
    // The empty scenario has no walkable area: the check says so.
    await waitForCheck(page, /problem/, 'empty page');
    assert.match(await page.locator('#diagnostics li').first().textContent(), /walkable/);
    await page.evaluate(() => { const a = window.throngEditor; a.cam.fit({ x0: -1, y0: -1, x1: 15, y1: 9 }); a.render(); });

    // The room: 14 × 8 m, a wall at x = 8 with a door between y = 3 and y = 5.
    await page.keyboard.press('w');
    await drag(page, [0, 0], [14, 8]);
    await page.keyboard.press('l');
    await drag(page, [8, 0], [8, 3]);
    await drag(page, [8, 5], [8, 8]);
    await drag(page, [8, 3], [8, 5]);  // closes the door
    await page.keyboard.press('e');
    await drag(page, [12, 3], [13.5, 5]);
    await page.keyboard.press('c');
    await drag(page, [1, 1], [5, 7]);
    await click(page, [12.75, 4]);  // picks the exit as the crowd's goal
    await page.keyboard.press('Escape');
    const doc = await page.evaluate(() => window.throngEditor.doc);
    assert.deepEqual(doc.walkable, [[[0, 0], [14, 0], [14, 8], [0, 8]]]);
    assert.equal(doc.walls.length, 3);
    assert.deepEqual(doc.walls[2].line, [[8, 3], [8, 5]]);
    assert.equal(doc.points[0].kind, 'exit');
    assert.deepEqual(doc.populations[0].goals, [doc.points[0].id]);

    // The exit cannot be reached: a diagnostic on the plan and in the list names the goal.
    await waitForCheck(page, /problem/, 'closed door');
    const items = await page.locator('#diagnostics li').allTextContents();
    assert.ok(items.some((t) => /^\/populations\/0/.test(t) && /reach/i.test(t)), `no unreachable-goal diagnostic in ${JSON.stringify(items)}`);
    assert.ok(await page.locator('svg .diagnostic').count() >= 1, 'no diagnostic marker on the plan');
    await page.locator('#diagnostics li', { hasText: /reach/i }).first().click();
    assert.equal(await page.evaluate(() => window.throngEditor.sel.layer), 'populations');
    if (process.env.THRONG_EDITOR_SHOT) await page.screenshot({ path: process.env.THRONG_EDITOR_SHOT });

    // Open the door: select its wall and delete it.
    await page.keyboard.press('v');
    await page.keyboard.press('Escape');
    await click(page, [8, 4]);
    assert.deepEqual(await page.evaluate(() => window.throngEditor.sel), { layer: 'walls', index: 2 });
    await page.keyboard.press('Delete');
    await waitForCheck(page, /valid/, 'door opened');
    assert.equal(await page.locator('#diagnostics li').count(), 0);
    // Undo brings the wall back, redo removes it again.
    await page.keyboard.press('Control+z');
    assert.equal(await page.evaluate(() => window.throngEditor.doc.walls.length), 3);
    await page.keyboard.press('Control+Shift+z');
    assert.equal(await page.evaluate(() => window.throngEditor.doc.walls.length), 2);
    await waitForCheck(page, /valid/, 'after redo');

    // Preview: frames arrive and the agents move towards the exit.
    await page.fill('#preview-seconds', '10');
    await page.click('#preview-run');
    await page.waitForFunction(() => window.throngEditor.preview && window.throngEditor.preview.frames.length > 50, null, { timeout: 60000 });
    const moved = await page.evaluate(() => {
      const f = window.throngEditor.preview.frames;
      const first = f[0], last = f[f.length - 1];
      const x = (frame) => frame.xy.filter((_, i) => i % 2 === 0).reduce((s, v) => s + v, 0) / Math.max(1, frame.ids.length);
      return { agents: first.ids.length, from: x(first), to: x(last), t: last.t };
    });
    assert.equal(moved.agents, 20);
    assert.ok(moved.to > moved.from + 2, `the crowd did not walk east: mean x ${moved.from} → ${moved.to}`);
    await page.waitForFunction(() => document.querySelectorAll('svg .agent').length > 0);
    if (process.env.THRONG_EDITOR_SHOT) {
      await sleep(1500);
      await page.screenshot({ path: process.env.THRONG_EDITOR_SHOT.replace(/\.png$/, '-preview.png') });
    }
    await page.click('#preview-reset');
    assert.equal(await page.locator('svg .agent').count(), 0);

    // Exit choice in the crowd's form: its exit ticked, the nearest rule, the exit marked familiar.
    await page.keyboard.press('v');
    await click(page, [3, 4]);  // inside the crowd's spawn area
    assert.equal(await page.evaluate(() => window.throngEditor.sel.layer), 'populations');
    const exitId = await page.evaluate(() => window.throngEditor.doc.points[0].id);
    await page.check(`#exits-list input[data-exit="${exitId}"]`);
    await page.selectOption('[data-field="exitChoice.rule"]', 'nearest');
    await page.check(`#familiar-list input[data-exit="${exitId}"]`);
    await waitForCheck(page, /valid/, 'exit choice');
    assert.deepEqual(await page.evaluate(() => { const p = window.throngEditor.doc.populations[0]; return [p.exits, p.exitChoice]; }),
      [[exitId], { rule: 'nearest', familiar: [exitId] }]);

    // Save with Ctrl+S.
    await page.locator('#plan').focus();
    await page.keyboard.press('Control+s');
    for (let i = 0; i < 50 && !fs.existsSync(file); i++) await sleep(100);
    assert.ok(fs.existsSync(file), 'Ctrl+S wrote no file');
    await page.waitForFunction(() => /saved/.test(document.querySelector('#status').textContent));
    const saved = fs.readFileSync(file, 'utf8');
    assert.match(saved, /\n {2}"walkable": \[\n {4}\[\n {6}\[0, 0\],\n {6}\[14, 0\],\n/);  // formatted for diffs
    assert.deepEqual(JSON.parse(saved).populations[0].exitChoice, { rule: 'nearest', familiar: [exitId] });
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
  }
  const check = spawnSync(exe, ['check', file], { encoding: 'utf8' });
  assert.equal(check.status, 0, `throng check: ${check.stdout}${check.stderr}`);
  const run = spawnSync(exe, ['run', file, '--duration', '5', '--quiet', '--out', path.join(dir, 'room.sqlite')], { encoding: 'utf8' });
  assert.equal(run.status, 0, `throng run: ${run.stdout}${run.stderr}`);
  fs.rmSync(dir, { recursive: true, force: true });
});
