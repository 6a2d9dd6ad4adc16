// throng's scenario editor (docs/editor.md), the page `throng edit` serves: loads the scenario from
// GET /api/scenario, lets the user draw it (tools.js) and fill in its properties (panel.js), checks
// every edit with POST /api/check (debounced) and shows each diagnostic on the plan at the element
// its JSON pointer names, previews it with POST /api/preview (frames animated in the plan), saves
// it with POST /api/save (Ctrl+S; an invalid scenario only after the user has seen why) or
// downloads it, imports a DXF or WKT floor plan (POST /api/import). Picks a crowd's goals on the
// plan, or the options of one of its waypoint choices. Undo/redo over snapshots; keyboard shortcuts
// with a help overlay (?).
import schema from '../../../scenarios/schema/scenario.schema.json';
import { bounds } from './geometry.js';
import {
  History, LAYERS, allVertices, elementForPointer, emptyScenario, isClosed, mergePlan, removeElement, verticesOf,
} from './doc.js';
import { Camera, render } from './view.js';
import { TOOLS, ToolController } from './tools.js';
import { Panel } from './panel.js';

const $ = (id) => document.getElementById(id);
const CHECK_DELAY_MS = 350;

async function postJson(path, body) {
  const res = await fetch(path, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: typeof body === 'string' ? body : JSON.stringify(body) });
  let json = null;
  try { json = await res.json(); } catch { json = { ok: false, error: `HTTP ${res.status}` }; }
  return { status: res.status, json };
}

class EditorApp {
  constructor() {
    this.svg = $('plan');
    this.cam = new Camera();
    this.doc = emptyScenario();
    this.sel = null;
    this.state = { grid: 0.5, snap: true, diagnostics: [], cursor: null, snapKind: null, pickGoals: false, pickChoice: null, previewFrame: null, dragPreview: null };
    this.history = new History(this.doc);
    this.checkSeq = 0;
    this.checkTimer = null;
    this.preview = null;
    this.file = null;
    this.canSave = false;
    this.dirty = false;
    this.tools = new ToolController(this, this.svg);
    this.panel = new Panel(this, $('properties'), schema);
    this.buildToolbar();
    this.bindKeys();
    this.bindButtons();
    new ResizeObserver(() => this.resize()).observe(this.svg);
    this.resize();
  }

  async load() {
    try {
      const res = await fetch('api/scenario');
      const info = await res.json();
      this.file = info.file;
      this.canSave = info.canSave;
      try {
        this.doc = JSON.parse(info.text);
      } catch (e) {
        this.setStatus(`${info.file} is not JSON (${e.message}); starting from an empty scenario`);
        this.doc = emptyScenario();
      }
    } catch {
      this.setStatus('no server: the editor works, but checks, preview and save need `throng edit`');
    }
    $('file-name').textContent = this.file || '(unsaved: download)';
    this.history = new History(this.doc);
    this.fit();
    this.panel.render();
    this.scheduleCheck(0);
  }

  // --- edits ------------------------------------------------------------------------------------

  /** After every edit: history, redraw, form, check, preview reset. */
  commit(what = 'edit') {
    if (!this.history.push(this.doc)) { this.render(); return; }
    this.changed(what);
  }

  replaceDoc(doc, what) {
    if (!doc) return;
    this.doc = doc;
    if (this.sel && !this.doc[this.sel.layer]?.[this.sel.index]) this.sel = null;
    this.changed(what);
  }

  /** The document changed (`what` for the status line): unsaved, preview stopped, redrawn, re-checked. */
  changed(what) {
    this.dirty = true;
    this.stopPreview(true);
    this.render();
    this.panel.render();
    this.scheduleCheck();
    this.setStatus(what);
    this.updateTitle();
  }

  undo() { this.replaceDoc(this.history.undo(), 'undone'); }
  redo() { this.replaceDoc(this.history.redo(), 'redone'); }

  select(sel) {
    this.sel = sel;
    if (!sel || sel.layer !== 'populations') { this.state.pickGoals = false; this.state.pickChoice = null; }
    this.render();
    this.panel.render();
  }

  deleteSelection() {
    const sel = this.sel;
    if (!sel || sel.index == null) return;
    const vs = verticesOf(this.doc, sel);
    const min = isClosed(this.doc, sel) ? 3 : 2;
    if (sel.vertex != null && vs && vs.length > min) {
      vs.splice(sel.vertex, 1);
      this.sel = { layer: sel.layer, index: sel.index };
      this.commit('vertex deleted');
      return;
    }
    removeElement(this.doc, sel);
    this.sel = null;
    this.commit(`${sel.layer} ${sel.index} deleted`);
  }

  nudge(dx, dy) {
    const vs = verticesOf(this.doc, this.sel);
    if (!vs) return;
    const step = this.state.grid > 0 ? this.state.grid : 0.1;
    const moved = this.sel.vertex != null ? [vs[this.sel.vertex]] : vs;
    for (const v of moved) { v[0] = Number((v[0] + dx * step).toFixed(3)); v[1] = Number((v[1] + dy * step).toFixed(3)); }
    this.commit('moved');
  }

  togglePickGoals() {
    if (this.sel?.layer !== 'populations') { this.setStatus('select a crowd first, then G picks its goals'); return; }
    this.state.pickGoals = !this.state.pickGoals;
    this.state.pickChoice = null;
    if (this.state.pickGoals && this.tools.tool !== 'select') this.tools.tool = 'select';
    this.setStatus(this.state.pickGoals ? 'click points on the plan: each becomes the next goal (G or Esc ends)' : 'goals picked');
    this.renderToolbar();
    this.panel.render();
  }

  /** Picking on the plan adds options to the selected crowd's goal `index` (a waypoint choice). */
  pickOptions(index) {
    if (this.sel?.layer !== 'populations') return;
    this.state.pickGoals = true;
    this.state.pickChoice = index;
    if (this.tools.tool !== 'select') this.tools.tool = 'select';
    this.setStatus(`click points on the plan: each becomes an option of goal ${index + 1} (G or Esc ends)`);
    this.renderToolbar();
    this.panel.render();
  }

  // --- check ------------------------------------------------------------------------------------

  scheduleCheck(delay = CHECK_DELAY_MS) {
    clearTimeout(this.checkTimer);
    $('check-state').textContent = 'checking…';
    $('check-state').className = 'pending';
    this.checkTimer = setTimeout(() => this.check(), delay);
  }

  async check() {
    const seq = ++this.checkSeq;
    let result;
    try {
      result = await postJson('api/check', JSON.stringify(this.doc));
    } catch {
      $('check-state').textContent = 'not checked (no server)';
      return;
    }
    if (seq !== this.checkSeq) return;  // an older answer: a newer check is on its way
    this.setDiagnostics(result.json.diagnostics || [], result.json.ok === true, result.json.summary);
  }

  setDiagnostics(list, ok, summary) {
    this.state.diagnostics = list.map((d) => ({ ...d, element: elementForPointer(this.doc, d.pointer) }));
    const state = $('check-state');
    state.className = ok ? 'ok' : 'bad';
    state.textContent = ok ? `✓ valid${summary ? ` · ${summary.agents_min === summary.agents_max ? summary.agents_min : `${summary.agents_min}–${summary.agents_max}`} agents` : ''}`
                           : `${list.length} problem${list.length === 1 ? '' : 's'}`;
    const ul = $('diagnostics');
    ul.replaceChildren(...this.state.diagnostics.map((d, i) => {
      const li = document.createElement('li');
      li.dataset.diagnostic = i;
      li.dataset.pointer = d.pointer;
      li.textContent = `${d.pointer || '/'}: ${d.message}`;
      li.addEventListener('click', () => this.selectDiagnostic(i));
      return li;
    }));
    this.render();
  }

  selectDiagnostic(i) {
    const d = this.state.diagnostics[i];
    if (!d?.element || d.element.index == null) { this.setStatus(d ? d.message : ''); return; }
    const sel = { layer: d.element.layer, index: d.element.index };
    if (d.element.vertex != null) sel.vertex = d.element.vertex;
    this.select(sel);
    this.setStatus(d.message);
  }

  // --- preview ----------------------------------------------------------------------------------

  async runPreview() {
    const seconds = Number($('preview-seconds').value) || 20;
    this.stopPreview(true);
    $('preview-state').textContent = 'simulating…';
    const controller = new AbortController();
    this.previewAbort = controller;
    let result;
    try {
      const res = await fetch('api/preview', { method: 'POST', headers: { 'Content-Type': 'application/json' }, signal: controller.signal,
        body: JSON.stringify({ scenario: this.doc, seconds, fps: 10 }) });
      result = { status: res.status, json: await res.json() };
    } catch (e) {
      if (e.name !== 'AbortError') $('preview-state').textContent = 'preview failed (no server?)';
      return;
    }
    if (!result.json.ok) {
      $('preview-state').textContent = result.json.error || 'the scenario has problems: fix them first';
      if (result.json.diagnostics) this.setDiagnostics(result.json.diagnostics, false);
      return;
    }
    this.preview = { frames: result.json.frames, fps: result.json.fps, end: result.json.end, start: performance.now(), index: 0, playing: true };
    $('preview-slider').max = String(result.json.frames.length - 1);
    $('preview-panel').classList.add('active');
    this.animate();
  }

  animate() {
    const p = this.preview;
    if (!p) return;
    if (p.playing) {
      const speed = Number($('preview-speed').value) || 1;
      p.index = Math.min(p.frames.length - 1, Math.floor(((performance.now() - p.start) / 1000) * p.fps * speed));
      if (p.index >= p.frames.length - 1) p.playing = false;
    }
    this.showFrame(p.index);
    if (p.playing) requestAnimationFrame(() => this.animate());
  }

  showFrame(i) {
    const p = this.preview;
    const frame = p.frames[i];
    this.state.previewFrame = frame;
    $('preview-slider').value = String(i);
    $('preview-state').textContent = `t = ${frame.t.toFixed(1)} s · ${frame.ids.length} agents${i === p.frames.length - 1 ? ` · ended: ${p.end}` : ''}`;
    this.render();
  }

  togglePlay() {
    const p = this.preview;
    if (!p) return;
    p.playing = !p.playing;
    if (p.playing) {
      if (p.index >= p.frames.length - 1) p.index = 0;
      const speed = Number($('preview-speed').value) || 1;
      p.start = performance.now() - (p.index / p.fps / speed) * 1000;
      this.animate();
    }
  }

  stopPreview(quiet = false) {
    if (this.previewAbort) this.previewAbort.abort();
    this.previewAbort = null;
    const had = this.preview || this.state.previewFrame;
    this.preview = null;
    this.state.previewFrame = null;
    $('preview-panel').classList.remove('active');
    if (had && !quiet) this.setStatus('preview reset');
    if (had) $('preview-state').textContent = '';
    this.render();
  }

  // --- save -------------------------------------------------------------------------------------

  async save(force = false) {
    if (!this.canSave) { this.download(); return; }
    const { status, json } = await postJson('api/save', { scenario: this.doc, force });
    if (json.saved) {
      this.dirty = false;
      this.updateTitle();
      this.setStatus(json.ok ? `saved ${this.file}` : `saved ${this.file} with ${json.diagnostics.length} problems`);
      this.hideDialog();
      return;
    }
    if (status === 422) {
      this.setDiagnostics(json.diagnostics, false);
      this.showSaveDialog(json.diagnostics);
      return;
    }
    this.setStatus(`not saved: ${json.error || `HTTP ${status}`}`);
  }

  showSaveDialog(diagnostics) {
    $('save-problems').replaceChildren(...diagnostics.map((d) => {
      const li = document.createElement('li');
      li.textContent = `${d.pointer || '/'}: ${d.message}`;
      return li;
    }));
    $('save-dialog').classList.remove('hidden');
  }

  hideDialog() { $('save-dialog').classList.add('hidden'); }

  download() {
    const blob = new Blob([`${JSON.stringify(this.doc, null, 2)}\n`], { type: 'application/json' });
    const a = document.createElement('a');
    a.href = URL.createObjectURL(blob);
    a.download = this.file || `${this.doc.name || 'scenario'}.json`;
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }

  /** A DXF or WKT floor plan through POST /api/import: its shapes are added to the plan (one edit). */
  async importPlan(file) {
    if (!file) return;
    $('import-file').value = '';
    const text = await file.text();
    let result;
    try {
      result = await postJson('api/import', { name: file.name, text });
    } catch {
      this.setStatus('import needs the server (`throng edit`)');
      return;
    }
    if (!result.json.ok) {
      const first = (result.json.diagnostics || [])[0];
      this.setStatus(`${file.name} not imported: ${first ? `line ${first.line}:${first.column}: ${first.message}` : result.json.error}`);
      return;
    }
    const n = mergePlan(this.doc, result.json.fragment);
    this.sel = null;
    this.commit(`${file.name}: ${n.walkable} walkable, ${n.obstacles} obstacles, ${n.walls} walls imported`);
    this.fit();
  }

  /** A floor plan image, scaled by the width in metres the user gives (not saved in the scenario). */
  loadBackground(file) {
    if (!file) return;
    const reader = new FileReader();
    reader.onload = () => {
      const img = new Image();
      img.onload = () => {
        const width = Number(window.prompt(`Width of ${file.name} in metres (${img.width} pixels)?`, '20'));
        if (!(width > 0)) return;
        this.state.background = { href: reader.result, x0: 0, y0: 0, width, height: (width * img.height) / img.width };
        this.cam.fit({ x0: 0, y0: 0, x1: width, y1: this.state.background.height });
        this.render();
        this.setStatus(`background ${file.name}: ${width} m wide, lower-left corner at 0, 0`);
      };
      img.src = reader.result;
    };
    reader.readAsDataURL(file);
    $('background-file').value = '';
  }

  // --- view -------------------------------------------------------------------------------------

  resize() {
    const r = this.svg.getBoundingClientRect();
    this.cam.width = r.width || 800;
    this.cam.height = r.height || 600;
    this.render();
  }

  fit() {
    const vs = allVertices(this.doc);
    this.cam.fit(vs.length ? bounds(vs) : { x0: 0, y0: 0, x1: 20, y1: 12 });
    this.render();
  }

  render() {
    const t = this.tools;
    const draft = t.draft || (this.state.dragPreview ? { points: this.state.dragPreview, closed: TOOLS[t.tool].shape === 'polygon' } : null);
    render(this.svg, this.cam, { ...this.state, doc: this.doc, sel: this.sel, draft, cursor: this.state.dragPreview ? null : t.draft ? this.state.cursor : null });
    this.renderToolbar();
  }

  setStatus(text) { $('status').textContent = text; $('status').title = text; }
  setCursorText(p, kind) { $('cursor').textContent = `${p[0].toFixed(2)}, ${p[1].toFixed(2)} m${kind && kind !== 'none' ? ` · ${kind}` : ''}`; }
  updateTitle() { document.title = `${this.dirty ? '• ' : ''}${this.file || 'scenario'} — throng editor`; }

  buildToolbar() {
    const bar = $('tools');
    for (const [name, t] of Object.entries(TOOLS)) {
      const b = document.createElement('button');
      b.dataset.tool = name;
      b.title = `${t.help} (${t.key.toUpperCase()})`;
      b.innerHTML = `${t.label} <kbd>${t.key.toUpperCase()}</kbd>`;
      b.addEventListener('click', () => this.tools.setTool(name));
      bar.append(b);
    }
  }

  renderToolbar() {
    for (const b of document.querySelectorAll('#tools button')) b.classList.toggle('on', b.dataset.tool === this.tools.tool);
    $('snap-toggle').checked = this.state.snap;
  }

  bindButtons() {
    $('undo').addEventListener('click', () => this.undo());
    $('redo').addEventListener('click', () => this.redo());
    $('save').addEventListener('click', () => this.save());
    $('download').addEventListener('click', () => this.download());
    $('fit').addEventListener('click', () => this.fit());
    $('help-button').addEventListener('click', () => $('help').classList.toggle('hidden'));
    $('background').addEventListener('click', () => {
      if (this.state.background) { this.state.background = null; this.render(); return; }
      $('background-file').click();
    });
    $('background-file').addEventListener('change', (e) => this.loadBackground(e.target.files[0]));
    $('import').addEventListener('click', () => $('import-file').click());
    $('import-file').addEventListener('change', (e) => this.importPlan(e.target.files[0]));
    $('help').addEventListener('click', () => $('help').classList.add('hidden'));
    $('snap-toggle').addEventListener('change', (e) => { this.state.snap = e.target.checked; });
    $('grid-step').addEventListener('change', (e) => { this.state.grid = Math.max(0, Number(e.target.value) || 0); this.render(); });
    $('preview-run').addEventListener('click', () => this.runPreview());
    $('preview-play').addEventListener('click', () => this.togglePlay());
    $('preview-reset').addEventListener('click', () => this.stopPreview());
    $('preview-slider').addEventListener('input', (e) => { if (this.preview) { this.preview.playing = false; this.preview.index = Number(e.target.value); this.showFrame(this.preview.index); } });
    $('save-force').addEventListener('click', () => this.save(true));
    $('save-cancel').addEventListener('click', () => this.hideDialog());
    window.addEventListener('beforeunload', (e) => { if (this.dirty && this.canSave) e.preventDefault(); });
  }

  bindKeys() {
    window.addEventListener('keydown', (e) => {
      if (e.target.closest && e.target.closest('input, select, textarea')) {
        if (e.key === 'Enter') e.target.blur();
        if (!(e.ctrlKey || e.metaKey)) return;
      }
      if (this.shortcut(e)) e.preventDefault();
    });
  }

  /** One key; true when it did something. */
  shortcut(e) {
    const k = e.key.toLowerCase();
    const ctrl = e.ctrlKey || e.metaKey;
    if (ctrl && k === 's') { this.save(); return true; }
    if (ctrl && k === 'z') { if (e.shiftKey) this.redo(); else this.undo(); return true; }
    if (ctrl && k === 'y') { this.redo(); return true; }
    if (ctrl && k === 'd') { this.download(); return true; }
    if (ctrl || e.altKey) return false;
    if (e.key === '?') { $('help').classList.toggle('hidden'); return true; }
    if (e.key === 'Escape') {
      if (!$('help').classList.contains('hidden')) $('help').classList.add('hidden');
      else if (!$('save-dialog').classList.contains('hidden')) this.hideDialog();
      else if (this.tools.cancel()) this.setStatus('drawing cancelled');
      else if (this.state.pickGoals) this.togglePickGoals();
      else if (this.preview) this.stopPreview();
      else this.select(null);
      return true;
    }
    if (e.key === 'Enter') { this.tools.finishDraft(); return true; }
    if (e.key === 'Delete' || e.key === 'Backspace') { this.deleteSelection(); return true; }
    const arrows = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };
    if (arrows[e.key]) { this.nudge(...arrows[e.key]); return true; }
    if (k === 'g') { this.togglePickGoals(); return true; }
    if (k === 'r') { this.runPreview(); return true; }
    if (k === ' ') { this.togglePlay(); return true; }
    if (k === 'f') { this.fit(); return true; }
    if (k === 's') { this.state.snap = !this.state.snap; this.setStatus(`snapping ${this.state.snap ? 'on' : 'off'}`); this.renderToolbar(); return true; }
    if (k === '+' || k === '=') { this.cam.zoomAt([this.cam.width / 2, this.cam.height / 2], 1.25); this.render(); return true; }
    if (k === '-') { this.cam.zoomAt([this.cam.width / 2, this.cam.height / 2], 0.8); this.render(); return true; }
    const tool = Object.entries(TOOLS).find(([, t]) => t.key === k);
    if (tool) { this.tools.setTool(tool[0]); return true; }
    return false;
  }
}

const app = new EditorApp();
window.throngEditor = app;  // for the end-to-end tests and the console
app.load();
export { LAYERS };
