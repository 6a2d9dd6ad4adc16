// End-to-end test of the editor's other tools and gestures: a polygon drawn by clicks and closed on
// its first corner, a vertex dragged and snapped at a right angle, a vertex added on an edge and
// deleted, measurement lines and areas, interest and action points (orientation from the form),
// the wheel zoom, the arrow keys, the help overlay, a diagnostic's marker at the vertex its pointer
// names; the result checks valid and is saved with its measurements.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { launchBrowser, requirePrerequisites, stopServer } from '../../viewer/e2e/harness.mjs';
import { at, click, drag, openEditor, startEditor, waitForCheck } from './helpers.mjs';

test('every tool and gesture leaves the scenario it should', { timeout: 150000 }, async () => {
  requirePrerequisites('editor e2e');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-tools-'));
  const file = path.join(dir, 'tools.json');
  const server = await startEditor(file);
  const browser = await launchBrowser();
  const errors = [];
  try {
    const page = await openEditor(browser, server, 'tools.json', errors, { width: 1100, height: 720 });
    await page.evaluate(() => { const a = window.throngEditor; a.cam.fit({ x0: -1, y0: -1, x1: 13, y1: 9 }); a.render(); });
    const doc = () => page.evaluate(() => window.throngEditor.doc);

    // A walkable polygon by clicks, closed by clicking its first corner again.
    await page.keyboard.press('w');
    for (const p of [[0, 0], [10, 0], [10, 8], [0, 8], [0, 0]]) await click(page, p);
    assert.deepEqual((await doc()).walkable, [[[0, 0], [10, 0], [10, 8], [0, 8]]]);
    assert.match(await page.locator('#measures').textContent(), /area 80\.00 m² · perimeter 36\.00 m/);

    // Drag the corner (10, 8) to near (10.08, 9.1): it snaps to the right angle along x = 10 on the grid.
    await page.keyboard.press('v');
    const from = await at(page, [10, 8]);
    const to = await at(page, [10.08, 9.1]);
    await page.mouse.move(...from);
    await page.mouse.down();
    await page.mouse.move(...to, { steps: 4 });
    await page.mouse.up();
    assert.deepEqual((await doc()).walkable[0], [[0, 0], [10, 0], [10, 9], [0, 8]]);
    // Double-click the bottom edge adds a vertex there; Delete removes it again.
    await page.mouse.dblclick(...(await at(page, [5, 0])));
    assert.deepEqual((await doc()).walkable[0][1], [5, 0]);
    assert.equal(await page.evaluate(() => window.throngEditor.sel.vertex), 1);
    await page.keyboard.press('Delete');
    assert.equal((await doc()).walkable[0].length, 4);

    // Measurement line (two clicks) and area (a drag); interest and action points.
    await page.keyboard.press('m');
    await click(page, [6, 1]);
    await click(page, [6, 7]);
    await page.keyboard.press('n');
    await drag(page, [7, 2], [9, 5]);
    await page.keyboard.press('i');
    await click(page, [2, 6]);
    await page.keyboard.press('a');
    await click(page, [4, 6]);
    await page.fill('[data-field="orientation°"]', '90');
    await page.press('[data-field="orientation°"]', 'Enter');
    let d = await doc();
    assert.deepEqual(d.measurements, [{ id: 'line1', line: [[6, 1], [6, 7]] }, { id: 'area1', polygon: [[7, 2], [9, 2], [9, 5], [7, 5]] }]);
    assert.deepEqual(d.points.map((p) => [p.id, p.kind, p.position]), [['interest1', 'interest', [2, 6]], ['action1', 'action', [4, 6]]]);
    assert.deepEqual(d.points[1].orientation, [0, 1]);

    // The arrow keys move the selected point by one grid step.
    await page.keyboard.press('ArrowRight');
    assert.deepEqual((await doc()).points[1].position, [4.5, 6]);

    // A vertex outside every limit: the diagnostic names that vertex and its marker sits on it.
    await page.keyboard.press('v');
    await click(page, [1, 1]);  // the walkable area
    await page.evaluate(() => { const a = window.throngEditor; a.doc.walkable[0][3] = [0, 200000]; a.commit('far'); });
    await waitForCheck(page, /problem/, 'a vertex out of range');
    const pointer = await page.locator('#diagnostics li').first().getAttribute('data-pointer');
    assert.match(pointer, /^\/walkable\/0\/3/);
    assert.equal(await page.locator('svg .diagnostic').count() >= 1, true);
    await page.keyboard.press('Control+z');
    await waitForCheck(page, /valid/, 'undone');

    // Zoom at the cursor, help overlay.
    const before = await page.evaluate(() => window.throngEditor.cam.scale);
    await page.mouse.move(...(await at(page, [5, 4])));
    await page.mouse.wheel(0, -300);
    assert.ok(await page.evaluate(() => window.throngEditor.cam.scale) > before);
    await page.keyboard.press('?');
    assert.equal(await page.locator('#help').isVisible(), true);
    await page.keyboard.press('Escape');
    assert.equal(await page.locator('#help').isVisible(), false);

    await page.keyboard.press('Control+s');
    await page.waitForFunction(() => /saved/.test(document.querySelector('#status').textContent));
    const saved = JSON.parse(fs.readFileSync(file, 'utf8'));
    assert.equal(saved.measurements.length, 2);
    assert.deepEqual(saved.points[1].orientation, [0, 1]);
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
    fs.rmSync(dir, { recursive: true, force: true });
  }
});
