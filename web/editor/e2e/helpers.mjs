// Shared plumbing of the editor's end-to-end tests: starting the built `throng edit` (THRONG_EXE)
// on a file and reading the URL it prints, and driving the plan with the mouse at positions given
// in metres (through the page's camera), opening its page with errors collected. Downloads nothing.
import { spawn } from 'node:child_process';
import assert from 'node:assert/strict';
import path from 'node:path';
import { exe, sleep, webRoot } from '../../viewer/e2e/harness.mjs';

export function startEditor(file) {
  const proc = spawn(exe, ['edit', file, '--port', '0', '--web', path.join(webRoot, 'dist')], { stdio: ['ignore', 'pipe', 'pipe'] });
  const log = [];
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`throng edit printed no URL in 30 s:\n${log.join('')}`)), 30000);
    const onData = (d) => {
      log.push(d.toString());
      const m = /editor\s+(http:\/\/127\.0\.0\.1:(\d+)\/)/.exec(log.join(''));
      if (m) { clearTimeout(timer); resolve({ proc, url: m[1], log }); }
    };
    proc.stdout.on('data', onData);
    proc.stderr.on('data', (d) => log.push(d.toString()));
    proc.on('exit', (code) => { clearTimeout(timer); reject(new Error(`throng edit exited (${code}):\n${log.join('')}`)); });
  });
}

/**
 * A new page of the editor served by `server`, once it shows `fileName`. Page errors and console
 * errors go to `errors` (the test fails on any); `allow` is a pattern of console errors that are
 * expected (a refused save is answered 422 by design, which chromium logs as a failed resource).
 */
export async function openEditor(browser, server, fileName, errors, { width = 1200, height = 760, allow = null } = {}) {
  const page = await browser.newPage({ viewport: { width, height } });
  page.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
  page.on('console', (m) => { if (m.type() === 'error' && !(allow && allow.test(m.text()))) errors.push(`console: ${m.text()}`); });
  await page.goto(server.url);
  await page.waitForFunction((name) => window.throngEditor && document.querySelector('#file-name').textContent === name, fileName);
  return page;
}

/** Page coordinates of a plan position [m]. */
export async function at(page, p) {
  return page.evaluate(([x, y]) => {
    const app = window.throngEditor;
    const r = app.svg.getBoundingClientRect();
    const [sx, sy] = app.cam.toScreen([x, y]);
    return [r.left + sx, r.top + sy];
  }, p);
}

export async function drag(page, a, b) {
  const [x0, y0] = await at(page, a);
  const [x1, y1] = await at(page, b);
  await page.mouse.move(x0, y0);
  await page.mouse.down();
  await page.mouse.move((x0 + x1) / 2, (y0 + y1) / 2, { steps: 3 });
  await page.mouse.move(x1, y1, { steps: 3 });
  await page.mouse.up();
}

export async function click(page, p) {
  const [x, y] = await at(page, p);
  await page.mouse.click(x, y);
}

export const checkState = (page) => page.locator('#check-state').textContent();

export async function waitForCheck(page, pattern, what) {
  for (let i = 0; i < 100; i++) {
    const text = await checkState(page);
    if (pattern.test(text)) return text;
    await sleep(100);
  }
  assert.fail(`${what}: the check state is "${await checkState(page)}"`);
}
