// End-to-end test of the viewer's export (issue 20, src/ui/export.js) against a real `throng serve
// scenarios/museum.json` in Debian's headless chromium: K downloads throng-museum-<time>.png, a
// valid PNG of the canvas's size that is not blank and shows what the canvas shows (its mean grey
// level close to the canvas read back); V starts a WebM recording (the red indicator shows and
// counts), V again stops it and downloads throng-museum-<time>.webm, a non-empty file that starts
// with the EBML magic bytes 1A 45 DF A3; the help lists K and V; the controls, one row taller,
// still end above the agent panel. Run: THRONG_EXE=build/apps/throng/throng node --test
// web/viewer/e2e/export.e2e.test.mjs. Fails, like the other e2e tests, when something it needs is missing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { repo, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer } from './harness.mjs';

/** Grey-level statistics of a PNG (bytes) decoded by the page: {width, height, mean, sd, levels}. */
function pngStats(page, bytes) {
  return page.evaluate(async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.naturalWidth; c.height = img.naturalHeight;
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    let n = 0, sum = 0, sum2 = 0;
    const levels = new Set();
    for (let o = 0; o < d.length; o += 16) {
      const v = d[o + 3] === 0 ? 0 : Math.round(0.299 * d[o] + 0.587 * d[o + 1] + 0.114 * d[o + 2]);
      ++n; sum += v; sum2 += v * v; levels.add(v);
    }
    const mean = sum / n;
    return { width: c.width, height: c.height, mean, sd: Math.sqrt(Math.max(0, sum2 / n - mean * mean)), levels: levels.size };
  }, Buffer.from(bytes).toString('base64'));
}

async function downloaded(page, key) {
  const [dl] = await Promise.all([page.waitForEvent('download', { timeout: 20000 }), page.keyboard.press(key)]);
  return { name: dl.suggestedFilename(), bytes: fs.readFileSync(await dl.path()) };
}

test('export: K downloads a PNG of the view, V records a WebM video', { timeout: 90000 }, async () => {
  requirePrerequisites('export e2e');
  const server = await startServer(path.join(repo, 'scenarios/museum.json'));
  const browser = await launchBrowser();
  const errors = [];
  try {
    const page = await openViewer(browser, `${server.url}?lod=off`, errors);
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 0, null, { timeout: 30000 });
    await page.waitForTimeout(800);

    const png = await downloaded(page, 'k');
    assert.match(png.name, /^throng-museum-\d{8}-\d{6}\.png$/);
    assert.deepEqual([...png.bytes.subarray(0, 8)], [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a], 'PNG signature');
    const canvas = await page.evaluate(() => ({ w: globalThis.__throng.renderer.domElement.width, h: globalThis.__throng.renderer.domElement.height }));
    assert.deepEqual([png.bytes.readUInt32BE(16), png.bytes.readUInt32BE(20)], [canvas.w, canvas.h], 'the PNG has the canvas size');
    const stats = await pngStats(page, png.bytes);
    assert.ok(stats.sd > 8 && stats.levels > 20, `the PNG is not blank: ${JSON.stringify(stats)}`);
    const live = await page.evaluate(() => { const p = globalThis.__throng.pixels(4); return p.grey.reduce((a, b) => a + b, 0) / p.grey.length; });
    assert.ok(Math.abs(live - stats.mean) < 12, `the PNG shows the view (mean grey ${stats.mean.toFixed(1)} vs ${live.toFixed(1)} on the canvas)`);

    await page.keyboard.press('?');
    const helpRows = await page.evaluate(() => [...document.querySelectorAll('#help th')].map((t) => t.textContent));
    assert.ok(['K', 'V'].every((k) => helpRows.includes(k)), `the help lists the export keys: ${helpRows}`);
    await page.keyboard.press('Escape');
    assert.equal(await page.isVisible('#rec-indicator'), false, 'no indicator before recording');
    await page.keyboard.press('v');
    await page.waitForTimeout(1600);
    assert.equal(await page.isVisible('#rec-indicator'), true, 'the recording indicator shows');
    assert.match(await page.textContent('#rec-indicator'), /REC 0:0[12]/);
    assert.equal(await page.evaluate(() => globalThis.__throng.exporter.recording), true);
    const webm = await downloaded(page, 'v');
    assert.match(webm.name, /^throng-museum-\d{8}-\d{6}\.webm$/);
    assert.ok(webm.bytes.length > 1000, `the WebM holds frames (${webm.bytes.length} bytes)`);
    assert.deepEqual([...webm.bytes.subarray(0, 4)], [0x1a, 0x45, 0xdf, 0xa3], 'EBML magic');
    assert.equal(await page.isVisible('#rec-indicator'), false, 'the indicator goes when the recording stops');
    // The export row keeps the controls clear of the agent panel below them.
    const [controls, agent] = await page.evaluate(() => ['controls', 'agent-panel'].map((id) => {
      const el = document.getElementById(id), was = el.classList.contains('hidden');
      el.classList.remove('hidden');
      const r = el.getBoundingClientRect();
      if (was) el.classList.add('hidden');
      return { top: r.top, bottom: r.bottom };
    }));
    assert.ok(controls.bottom <= agent.top, `the controls (bottom ${controls.bottom}) end above the agent panel (top ${agent.top})`);
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
  }
});
