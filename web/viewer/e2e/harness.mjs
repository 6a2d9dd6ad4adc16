// Shared plumbing of the viewer's end-to-end tests (viewer.e2e.test.mjs, replay.e2e.test.mjs):
// what is missing to run them (→ the test fails saying so), starting and stopping the built `throng serve`
// (THRONG_EXE) on 127.0.0.1 and reading the viewer URL it prints, launching Debian's headless
// chromium (playwright-core, SwiftShader) and opening the viewer with page errors collected.
// Reads THRONG_EXE, THRONG_CHROMIUM (default /usr/bin/chromium); downloads nothing.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
export const webRoot = path.resolve(here, '../..');
export const repo = path.resolve(webRoot, '..');
export const exe = process.env.THRONG_EXE || '';
export const chromiumPath = process.env.THRONG_CHROMIUM || '/usr/bin/chromium';

/** Why the e2e tests cannot run here, or null. */
export function missing() {
  if (!exe || !fs.existsSync(exe)) return `THRONG_EXE (${exe || 'unset'}) is not a built throng binary`;
  if (!fs.existsSync(path.join(webRoot, 'node_modules', 'playwright-core'))) return 'web/node_modules missing: run `cd web && npm ci`';
  if (!fs.existsSync(path.join(webRoot, 'dist', 'index.html'))) return 'web/dist missing: run `cd web && npm run build`';
  if (!fs.existsSync(chromiumPath)) return `${chromiumPath} missing: apt-get install chromium`;
  return null;
}

/** Throws (the test fails, it is never skipped) naming what is missing and how to get it. */
export function requirePrerequisites(what) {
  const why = missing();
  if (why) throw new Error(`${what} cannot run: ${why} (scripts/test.sh installs, builds and runs everything)`);
}

export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

/** Starts `throng serve INPUT` (scenario or recording; HTTP `port`, 0: any free one; `extra`: more
 * flags); resolves {proc, url, port, log} once it prints the viewer URL. */
export function startServer(input, port = 0, extra = []) {
  const args = ['serve', input, '--port', String(port), '--udp-port', '0', '--web', path.join(webRoot, 'dist'), ...extra];
  const proc = spawn(exe, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  const log = [];
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`throng serve printed no URL in 30 s:\n${log.join('')}`)), 30000);
    const onData = (d) => {
      log.push(d.toString());
      const m = /viewer\s+(http:\/\/127\.0\.0\.1:(\d+)\/)/.exec(log.join(''));
      if (m) { clearTimeout(timer); resolve({ proc, url: m[1], port: Number(m[2]), log }); }
    };
    proc.stdout.on('data', onData);
    proc.stderr.on('data', (d) => log.push(d.toString()));
    proc.on('exit', (code) => { clearTimeout(timer); reject(new Error(`throng serve exited (${code}):\n${log.join('')}`)); });
  });
}

/** SIGINT, then SIGKILL after 10 s; resolves the exit code. */
export function stopServer(server) {
  if (!server || server.proc.exitCode !== null) return Promise.resolve(server && server.proc.exitCode);
  return new Promise((resolve) => {
    const kill = setTimeout(() => server.proc.kill('SIGKILL'), 10000);
    server.proc.once('exit', (code) => { clearTimeout(kill); resolve(code); });
    server.proc.kill('SIGINT');
  });
}

export async function launchBrowser() {
  const { chromium } = await import('playwright-core');
  return chromium.launch({
    executablePath: chromiumPath, headless: true,
    args: ['--no-sandbox', '--ignore-gpu-blocklist', '--use-angle=swiftshader', '--use-gl=angle', '--enable-unsafe-swiftshader'],
  });
}

/** Opens the viewer at `url` (640×360); page errors and the viewer's own warnings go to `errors`. */
export async function openViewer(browser, url, errors) {
  const page = await browser.newPage({ viewport: { width: 640, height: 360 } });
  page.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
  page.on('console', (m) => {
    if (m.type() === 'error' || (m.type() === 'warning' && m.text().startsWith('throng:'))) errors.push(`console: ${m.text()}`);
  });
  await page.goto(url);
  return page;
}
