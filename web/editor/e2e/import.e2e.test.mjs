// End-to-end test of importing a floor plan into the editor: a WKT file picked with Import plan…
// becomes the walkable area and walls of an empty scenario (one undoable edit, checked at once);
// a broken file is refused with its line and column in the status line and changes nothing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { launchBrowser, requirePrerequisites, stopServer } from '../../viewer/e2e/harness.mjs';
import { openEditor, startEditor, waitForCheck } from './helpers.mjs';

test('a WKT floor plan imported into an empty scenario; a broken one refused', { timeout: 120000 }, async () => {
  requirePrerequisites('editor e2e');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-import-'));
  const server = await startEditor(path.join(dir, 'plan.json'));
  const browser = await launchBrowser();
  const errors = [];
  try {
    const page = await openEditor(browser, server, 'plan.json', errors, { width: 1000, height: 700, allow: /status of 422/ });
    await waitForCheck(page, /problem/, 'empty page');
    const wkt = 'GEOMETRYCOLLECTION (POLYGON ((0 0, 12 0, 12 8, 0 8)), LINESTRING (6 0, 6 3), LINESTRING (6 5, 6 8))';
    await page.setInputFiles('#import-file', { name: 'ground.wkt', mimeType: 'text/plain', buffer: Buffer.from(wkt) });
    await page.waitForFunction(() => /ground\.wkt: 1 walkable, 0 obstacles, 2 walls imported/.test(document.querySelector('#status').textContent));
    const doc = await page.evaluate(() => window.throngEditor.doc);
    assert.equal(doc.walkable.length, 1);
    assert.deepEqual(doc.walls.map((w) => [w.id, w.line]), [['wall1', [[6, 0], [6, 3]]], ['wall2', [[6, 5], [6, 8]]]]);
    await waitForCheck(page, /valid/, 'imported plan');
    await page.keyboard.press('Control+z');
    assert.deepEqual(await page.evaluate(() => window.throngEditor.doc.walkable), []);

    await page.setInputFiles('#import-file', { name: 'broken.wkt', mimeType: 'text/plain', buffer: Buffer.from('POLYGON ((0 0, 1 0') });
    await page.waitForFunction(() => /broken\.wkt not imported: line 1:\d+/.test(document.querySelector('#status').textContent));
    assert.deepEqual(await page.evaluate(() => window.throngEditor.doc.walkable), []);
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
    fs.rmSync(dir, { recursive: true, force: true });
  }
});
