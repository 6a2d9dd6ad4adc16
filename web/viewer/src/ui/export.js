// Export of the view from the page: a PNG screenshot (key K, the PNG button) and a WebM video
// (key V, the Rec button: start / stop, a red "● REC m:ss" indicator while it records), both
// downloaded as throng-<scenario>-<YYYYMMDD-HHMMSS>.<ext>. The screenshot renders a frame and
// reads the canvas in the same task (no preserveDrawingBuffer needed); the video records
// canvas.captureStream() with MediaRecorder (VP9, else VP8, else the browser's WebM).
// Pure helpers (exportName, videoMime) are unit-tested in test/export.test.js.

import { clock } from './hud.js';

const pad = (n) => String(n).padStart(2, '0');

/** File name for an export: throng-<scenario>-<YYYYMMDD-HHMMSS>.<ext>, the scenario name reduced
 * to [A-Za-z0-9_-] ("view" when it has none), the time in UTC. */
export function exportName(scenario, date, ext) {
  const s = String(scenario || '').trim().replace(/[^A-Za-z0-9_-]+/g, '_').replace(/^_+|_+$/g, '') || 'view';
  const t = `${date.getUTCFullYear()}${pad(date.getUTCMonth() + 1)}${pad(date.getUTCDate())}-` +
    `${pad(date.getUTCHours())}${pad(date.getUTCMinutes())}${pad(date.getUTCSeconds())}`;
  return `throng-${s}-${t}.${ext}`;
}

/** The first WebM type `isSupported` (MediaRecorder.isTypeSupported) accepts, or null. */
export function videoMime(isSupported) {
  for (const m of ['video/webm;codecs=vp9', 'video/webm;codecs=vp8', 'video/webm']) if (isSupported(m)) return m;
  return null;
}

/** Hands `blob` to the browser as a download named `name`. */
export function download(blob, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 60000);
}

export class Exporter {
  /** canvas: the WebGL canvas; render(): draws the current view now; scenario(): its name;
   * indicator: the element shown while recording; onChange(recording): after start / stop. */
  constructor(canvas, render, scenario, indicator, onChange = () => {}) {
    this.canvas = canvas;
    this.render = render;
    this.scenario = scenario;
    this.indicator = indicator;
    this.onChange = onChange;
    this.recorder = null;
    this.timer = 0;
  }

  get recording() { return this.recorder !== null; }

  /** Downloads a PNG of the view; resolves the file name. */
  screenshot() {
    this.render();  // read back in the same task: the drawing buffer still holds this frame
    const name = exportName(this.scenario(), new Date(), 'png');
    return new Promise((resolve, reject) => this.canvas.toBlob((b) => {
      if (!b) { reject(new Error('throng: the canvas gave no PNG')); return; }
      download(b, name);
      resolve(name);
    }, 'image/png'));
  }

  /** Starts recording the view (false when the browser cannot), or stops and downloads it. */
  toggleRecording() {
    if (this.recorder) { this.stop(); return true; }
    return this.start();
  }

  start(fps = 30) {
    const Rec = globalThis.MediaRecorder;
    const mime = Rec && this.canvas.captureStream ? videoMime((m) => Rec.isTypeSupported(m)) : null;
    if (!mime) { console.warn('throng: this browser cannot record the canvas as WebM'); return false; }
    const chunks = [];
    const name = exportName(this.scenario(), new Date(), 'webm');
    const rec = new Rec(this.canvas.captureStream(fps), { mimeType: mime, videoBitsPerSecond: 8e6 });
    rec.ondataavailable = (e) => { if (e.data && e.data.size) chunks.push(e.data); };
    rec.onstop = () => {
      for (const t of rec.stream.getTracks()) t.stop();
      download(new Blob(chunks, { type: 'video/webm' }), name);
    };
    rec.start(250);
    this.recorder = rec;
    const began = performance.now();
    const tick = () => { this.indicator.textContent = `● REC ${clock((performance.now() - began) / 1000)}`; };
    tick();
    this.timer = setInterval(tick, 250);
    this.indicator.classList.remove('hidden');
    this.onChange(true);
    return true;
  }

  stop() {
    if (!this.recorder) return;
    clearInterval(this.timer);
    this.recorder.stop();
    this.recorder = null;
    this.indicator.classList.add('hidden');
    this.onChange(false);
  }
}
