// End-to-end: a scenario with "walls" and "measurements" (scenarios/bottleneck.json with its door
// post turned into a wall, a measurement line across the gap and an area in front of it) served by
// `throng serve` in Debian's headless chromium: the wall is drawn, the measurements panel shows,
// and its live figures count the people crossing the line and standing in the area.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { repo, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer } from './harness.mjs';

function scenario(dir) {
  const s = JSON.parse(fs.readFileSync(path.join(repo, 'scenarios/bottleneck.json'), 'utf8'));
  s.name = 'bottleneck-measured';
  // A 0.4 m wall standing in the room, away from everyone's way (drawn, walked round).
  s.walls = [{ id: 'screen', line: [[3, 9.5], [6, 9.5]], thickness: 0.4 }];
  s.measurements = [
    { id: 'gap', line: [[10, 4.5], [10, 5.5]] },
    { id: 'front', polygon: [[6.5, 3], [9, 3], [9, 7], [6.5, 7]] },
  ];
  const file = path.join(dir, 'measured.json');
  fs.writeFileSync(file, JSON.stringify(s));
  return file;
}

test('measurements: the panel counts the people crossing the line and standing in the area', { timeout: 120000 }, async () => {
  requirePrerequisites('measure e2e');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'throng-measure-'));
  const server = await startServer(scenario(dir));
  const browser = await launchBrowser();
  const errors = [];
  try {
    const page = await openViewer(browser, `${server.url}?lod=off`, errors);
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 0, null, { timeout: 30000 });
    assert.equal(await page.isVisible('#measure'), true, 'the measurements panel shows');
    assert.equal(await page.evaluate(() => globalThis.__throng.worldPart('measurements')?.userData.count), 2);
    // The first people reach the gap within seconds of simulated time; wait for the line to count.
    await page.waitForFunction(() => globalThis.__throng.measurements.rows()[0].meter.total >= 3, null, { timeout: 60000 });
    const rows = await page.evaluate(() => globalThis.__throng.measurements.rows().map((r) => ({ id: r.id, text: r.text,
      flow: r.meter.flow ? r.meter.flow() : null, density: r.meter.density ? r.meter.density() : null })));
    assert.deepEqual(rows.map((r) => r.id), ['gap', 'front']);
    assert.ok(rows[0].flow > 0 && rows[0].flow < 5, `flow through the 1 m gap: ${rows[0].flow}`);
    assert.ok(rows[1].density > 0.2, `people queue in front of the gap: ${rows[1].density} /m²`);
    await page.waitForTimeout(700);  // the panel redraws twice a second
    const text = await page.textContent('#measure');
    assert.match(text, /gap/);
    assert.match(text, /\/m² · [0-9.]+ m\/s/);
    const fd = await page.evaluate(() => globalThis.__throng.measurements.rows()[1].meter.fd.length);
    assert.ok(fd >= 2, `fundamental-diagram samples: ${fd}`);
    // The Edit link opens the served scenario in the editor at /editor/ (check and preview, no save).
    assert.equal(await page.getAttribute('#edit-link', 'href'), 'editor/');
    const served = await page.evaluate(async () => (await fetch('editor/api/scenario')).json());
    assert.equal(served.canSave, false);
    assert.equal(JSON.parse(served.text).name, 'bottleneck-measured');
    const check = await page.evaluate(async (text) => (await fetch('editor/api/check', { method: 'POST', body: text })).json(), served.text);
    assert.equal(check.ok, true, JSON.stringify(check.diagnostics));
    const editor = await browser.newPage({ viewport: { width: 1000, height: 700 } });
    await editor.goto(`${server.url}editor/`);
    await editor.waitForFunction(() => document.body.textContent.includes('measured'), null, { timeout: 20000 });
    await editor.close();
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
    fs.rmSync(dir, { recursive: true, force: true });
  }
});
