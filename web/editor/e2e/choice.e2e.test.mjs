// End-to-end test of waypoint choices in the editor (docs/editor.md; docs/scenario-format.md,
// Waypoint choices): in a room with two booths and an exit, a crowd's first goal is picked on the
// plan, turned into a choice ("or…", then the second booth clicked; the exit refused as an option
// and offering no "or…" itself), its shares typed (a wrong count refused with the reason), its
// split switched to least targeted (the shares go), an option removed (the choice becomes a plain
// goal) and the removal undone; the check finds the scenario valid, Ctrl+S saves it, and the file
// passes `throng check` and runs.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { exe, launchBrowser, requirePrerequisites, stopServer } from '../../viewer/e2e/harness.mjs';
import { click, drag, openEditor, startEditor, waitForCheck } from './helpers.mjs';

const goalsOf = (page) => page.evaluate(() => window.throngEditor.doc.populations[0].goals);

test('a waypoint choice made, split and shares edited, saved and run', { timeout: 180000 }, async () => {
  requirePrerequisites('editor e2e');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-choice-'));
  const file = path.join(dir, 'booths.json');
  const server = await startEditor(file);
  const browser = await launchBrowser();
  const errors = [];
  try {
    const page = await openEditor(browser, server, 'booths.json', errors);
    await page.evaluate(() => { const a = window.throngEditor; a.cam.fit({ x0: -1, y0: -1, x1: 21, y1: 11 }); a.render(); });

    await page.keyboard.press('w');
    await drag(page, [0, 0], [20, 10]);
    await page.keyboard.press('p');
    await click(page, [10, 3]);
    await click(page, [10, 7]);
    await page.keyboard.press('e');
    await drag(page, [19, 4], [20, 6]);
    await page.keyboard.press('c');
    await drag(page, [1, 1], [5, 9]);
    await click(page, [10, 3]);    // goal 1: the south booth
    await click(page, [19.5, 5]);  // goal 2: the exit
    await page.keyboard.press('g');
    assert.deepEqual(await goalsOf(page), ['waypoint1', 'exit1']);

    // "or…" on goal 1, then the north booth on the plan: a choice between the two.
    assert.equal(await page.locator('[data-choice="1"]').count(), 0, 'an exit goal offers no "or…"');
    await page.click('[data-choice="0"]');
    await click(page, [10, 7]);
    await click(page, [19.5, 5]);  // the exit: refused as an option, said why
    assert.match(await page.locator('#status').textContent(), /exit1 is an exit/);
    await page.keyboard.press('g');
    assert.deepEqual(await goalsOf(page), [{ choose: ['waypoint1', 'waypoint2'] }, 'exit1']);
    assert.equal(await page.locator('#goal-list li.choice .option').count(), 2);

    // Shares: one per option, or the reason it is refused.
    await page.fill('[data-field="goals.0.shares"]', '3');
    await page.press('[data-field="goals.0.shares"]', 'Enter');
    assert.match(await page.locator('.field:has(> [data-field="goals.0.shares"]) > .field-error').textContent(), /1 shares for 2 options/);
    await page.fill('[data-field="goals.0.shares"]', '3, 1');
    await page.press('[data-field="goals.0.shares"]', 'Enter');
    assert.deepEqual((await goalsOf(page))[0], { choose: ['waypoint1', 'waypoint2'], shares: [3, 1] });
    await waitForCheck(page, /valid/, 'a choice with shares');

    // Least targeted: no shares.
    await page.selectOption('[data-field="goals.0.split"]', 'leastTargeted');
    assert.deepEqual((await goalsOf(page))[0], { choose: ['waypoint1', 'waypoint2'], split: 'leastTargeted' });
    assert.equal(await page.locator('[data-field="goals.0.shares"]').count(), 0);

    // Removing an option leaves a plain goal; undo brings the choice back.
    await page.click('[data-option="waypoint2"]');
    assert.deepEqual(await goalsOf(page), ['waypoint1', 'exit1']);
    await page.keyboard.press('Control+z');
    assert.deepEqual((await goalsOf(page))[0], { choose: ['waypoint1', 'waypoint2'], split: 'leastTargeted' });
    await waitForCheck(page, /valid/, 'a least-targeted choice');

    await page.keyboard.press('Escape');
    await page.keyboard.press('Control+s');
    await page.waitForFunction(() => /saved/.test(document.querySelector('#status').textContent));
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
  }
  const saved = JSON.parse(fs.readFileSync(file, 'utf8'));
  assert.deepEqual(saved.populations[0].goals, [{ choose: ['waypoint1', 'waypoint2'], split: 'leastTargeted' }, 'exit1']);
  const check = spawnSync(exe, ['check', file], { encoding: 'utf8' });
  assert.equal(check.status, 0, `throng check: ${check.stdout}${check.stderr}`);
  const run = spawnSync(exe, ['run', file, '--duration', '5', '--json', '--out', path.join(dir, 'c.sqlite')], { encoding: 'utf8' });
  assert.equal(run.status, 0, `throng run: ${run.stdout}${run.stderr}`);
  fs.rmSync(dir, { recursive: true, force: true });
});
