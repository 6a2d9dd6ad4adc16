// End-to-end test of the "done when": a new user builds the bottleneck scenario
// (scenarios/bottleneck.json) in the editor from an empty page — walkable area, two obstacles
// leaving a 1 m gap, a waypoint in the gap, an exit, a crowd of 100 whose goals are picked on the
// plan, its model, a model parameter and a pre-movement time set in the schema-generated form, over
// a background image — checks it valid, saves
// it with Ctrl+S and runs it with `throng run`. Then an invalid scenario is not saved until the user,
// shown why, chooses Save anyway.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { exe, launchBrowser, requirePrerequisites, sleep, stopServer } from '../../viewer/e2e/harness.mjs';
import { click, drag, openEditor, startEditor, waitForCheck } from './helpers.mjs';

test('the bottleneck from an empty page, saved and run; an invalid save only when forced', { timeout: 180000 }, async () => {
  requirePrerequisites('editor e2e');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-bottleneck-'));
  const file = path.join(dir, 'bottleneck.json');
  const server = await startEditor(file);
  const browser = await launchBrowser();
  const errors = [];
  let savedValid = '';
  try {
    // A refused save is answered 422 by design (chromium logs it as a failed resource): not an error.
    const page = await openEditor(browser, server, 'bottleneck.json', errors, { allow: /status of 422/ });
    await page.evaluate(() => { const a = window.throngEditor; a.cam.fit({ x0: -1, y0: -1, x1: 21, y1: 11 }); a.render(); });

    await page.keyboard.press('w');
    await drag(page, [0, 0], [20, 10]);
    await page.keyboard.press('o');
    await drag(page, [9, 0], [10, 4.5]);
    await drag(page, [9, 5.5], [10, 10]);
    await page.keyboard.press('p');
    await click(page, [9.5, 5]);
    await page.keyboard.press('e');
    await drag(page, [19, 4], [20, 6]);
    await page.keyboard.press('c');
    await drag(page, [1, 1], [8, 9]);
    await click(page, [9.5, 5]);   // goal 1: the waypoint in the gap
    await click(page, [19.5, 5]);  // goal 2: the exit
    await page.keyboard.press('g');
    assert.equal(await page.locator('#goal-list li').count(), 2);
    await page.fill('[data-field=groups]', '100');
    await page.press('[data-field=groups]', 'Enter');
    await page.selectOption('[data-field=model]', 'avm');
    await page.fill('[data-field=timeGap]', '20');  // above the schema's maximum: refused, said why
    await page.press('[data-field=timeGap]', 'Enter');
    assert.match(await page.locator('.field:has([data-field=timeGap]) .field-error').textContent(), /maximum 10/);
    await page.fill('[data-field=timeGap]', '0.6');
    await page.press('[data-field=timeGap]', 'Enter');
    // Pre-movement: a distribution without its keys is a problem until they are given.
    await page.selectOption('[data-field=preMovement]', 'uniform');
    await waitForCheck(page, /problem/, 'pre-movement without min and max');
    await page.fill('[data-field="preMovement.min"]', '0');
    await page.press('[data-field="preMovement.min"]', 'Enter');
    await page.fill('[data-field="preMovement.max"]', '2');
    await page.press('[data-field="preMovement.max"]', 'Enter');
    // The waypoint in the gap as a checkpoint: each walker aims at it along its own lane.
    await page.keyboard.press('Escape');
    await click(page, [9.5, 5]);
    assert.deepEqual(await page.evaluate(() => window.throngEditor.sel), { layer: 'points', index: 0 });
    await page.selectOption('[data-field=aim]', 'lane');
    // A floor plan image to trace over, 20 m wide.
    page.once('dialog', (d) => d.accept('20'));
    await page.setInputFiles('#background-file', path.join(path.dirname(new URL(import.meta.url).pathname), '../../../docs/img/museum.png'));
    await page.waitForFunction(() => document.querySelector('svg image.background'));
    await page.evaluate(() => { const a = window.throngEditor; a.cam.fit({ x0: -1, y0: -1, x1: 21, y1: 11 }); a.render(); });

    const doc = await page.evaluate(() => window.throngEditor.doc);
    assert.deepEqual(doc.walkable, [[[0, 0], [20, 0], [20, 10], [0, 10]]]);
    assert.deepEqual(doc.obstacles, [[[9, 0], [10, 0], [10, 4.5], [9, 4.5]], [[9, 5.5], [10, 5.5], [10, 10], [9, 10]]]);
    assert.deepEqual(doc.points.map((p) => [p.id, p.kind]), [['waypoint1', 'interest'], ['exit1', 'exit']]);
    assert.deepEqual(doc.points[1].polygon, [[19, 4], [20, 4], [20, 6], [19, 6]]);
    assert.equal(doc.points[0].aim, 'lane');
    const crowd = doc.populations[0];
    assert.deepEqual(crowd.spawn.polygon, [[1, 1], [8, 1], [8, 9], [1, 9]]);
    assert.deepEqual(crowd.goals, ['waypoint1', 'exit1']);
    assert.equal(crowd.groups, 100);
    assert.deepEqual(crowd.model, { name: 'avm', timeGap: 0.6 });
    assert.deepEqual(crowd.preMovement, { distribution: 'uniform', min: 0, max: 2 });
    await waitForCheck(page, /valid · 100 agents/, 'the bottleneck');

    await page.keyboard.press('Escape');
    await page.keyboard.press('Control+s');
    await page.waitForFunction(() => /saved/.test(document.querySelector('#status').textContent));
    savedValid = fs.readFileSync(file, 'utf8');
    assert.equal(JSON.parse(savedValid).populations[0].groups, 100);

    // Delete the walkable area: the save is refused, showing why, until Save anyway.
    await click(page, [15, 8]);
    assert.deepEqual(await page.evaluate(() => window.throngEditor.sel), { layer: 'walkable', index: 0 });
    await page.keyboard.press('Delete');
    await waitForCheck(page, /problem/, 'no walkable area');
    await page.keyboard.press('Control+s');
    await page.locator('#save-dialog:not(.hidden)').waitFor();
    assert.match(await page.locator('#save-problems').textContent(), /walkable/);
    await page.click('#save-cancel');
    await sleep(200);
    assert.equal(fs.readFileSync(file, 'utf8'), savedValid);
    await page.keyboard.press('Control+s');
    await page.locator('#save-dialog:not(.hidden)').waitFor();
    await page.click('#save-force');
    await page.waitForFunction(() => /saved .* with \d+ problem/.test(document.querySelector('#status').textContent));
    assert.deepEqual(JSON.parse(fs.readFileSync(file, 'utf8')).walkable, []);
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
  }
  const bad = spawnSync(exe, ['check', file], { encoding: 'utf8' });
  assert.equal(bad.status, 1, 'the forced save should fail `throng check`');
  fs.writeFileSync(file, savedValid);
  const run = spawnSync(exe, ['run', file, '--duration', '5', '--json', '--out', path.join(dir, 'b.sqlite')], { encoding: 'utf8' });
  assert.equal(run.status, 0, `throng run: ${run.stdout}${run.stderr}`);
  fs.rmSync(dir, { recursive: true, force: true });
});
