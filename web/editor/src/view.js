// The plan view of the scenario editor: draws the document into an SVG in screen coordinates
// (metres → pixels through the camera: centre, scale, y up) — grid, walkable area, obstacles,
// walls, measurements, spawn areas, goal arrows (dotted to each option of a waypoint choice),
// points, the selection with its vertex handles, live lengths and areas, a background image to
// trace over, the diagnostics' markers, the polygon being drawn and the preview's agents. Every
// element carries data-layer/data-index (handles data-vertex) for picking.
import { centroid, dist, polygonArea, polylineLength } from './geometry.js';
import { LAYERS, anchorOf, isClosed, pointPosition, verticesOf } from './doc.js';
import { goalIds, isChoice } from './goals.js';

const NS = 'http://www.w3.org/2000/svg';

export function el(tag, attrs = {}, parent = null, text = null) {
  const node = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) if (v !== undefined && v !== null) node.setAttribute(k, String(v));
  if (text !== null) node.textContent = text;
  if (parent) parent.appendChild(node);
  return node;
}

/** Camera: world [m] ↔ screen [px]. */
export class Camera {
  constructor() { this.cx = 10; this.cy = 5; this.scale = 40; this.width = 800; this.height = 600; }
  toScreen([x, y]) { return [(x - this.cx) * this.scale + this.width / 2, this.height / 2 - (y - this.cy) * this.scale]; }
  toWorld([sx, sy]) { return [(sx - this.width / 2) / this.scale + this.cx, (this.height / 2 - sy) / this.scale + this.cy]; }
  zoomAt(screen, factor) {
    const before = this.toWorld(screen);
    this.scale = Math.min(2000, Math.max(0.5, this.scale * factor));
    const after = this.toWorld(screen);
    this.cx += before[0] - after[0];
    this.cy += before[1] - after[1];
  }
  fit(box) {
    if (!box) return;
    const w = Math.max(1, box.x1 - box.x0), h = Math.max(1, box.y1 - box.y0);
    this.cx = (box.x0 + box.x1) / 2;
    this.cy = (box.y0 + box.y1) / 2;
    this.scale = Math.max(0.5, Math.min(2000, 0.85 * Math.min(this.width / w, this.height / h)));
  }
}

const fmt = (v, digits = 2) => Number(v.toFixed(digits)).toString();
const pts = (cam, vs) => vs.map((v) => cam.toScreen(v).map((c) => c.toFixed(1)).join(',')).join(' ');

function drawGrid(g, cam, step) {
  const [x0, y1] = cam.toWorld([0, 0]);
  const [x1, y0] = cam.toWorld([cam.width, cam.height]);
  let minor = step > 0 ? step : 1;
  while (minor * cam.scale < 8) minor *= 2;
  const major = minor * 5;
  const path = (s) => {
    let d = '';
    for (let x = Math.ceil(x0 / s) * s; x <= x1; x += s) { const [sx] = cam.toScreen([x, 0]); d += `M${sx.toFixed(1)},0V${cam.height}`; }
    for (let y = Math.ceil(y0 / s) * s; y <= y1; y += s) { const [, sy] = cam.toScreen([0, y]); d += `M0,${sy.toFixed(1)}H${cam.width}`; }
    return d;
  };
  el('path', { d: path(minor), class: 'grid-minor' }, g);
  el('path', { d: path(major), class: 'grid-major' }, g);
  const [ox, oy] = cam.toScreen([0, 0]);
  el('path', { d: `M${ox - 6},${oy}H${ox + 6}M${ox},${oy - 6}V${oy + 6}`, class: 'origin' }, g);
}

function shape(g, cam, vs, closed, attrs) {
  return el(closed ? 'polygon' : 'polyline', { points: pts(cam, vs), ...attrs }, g);
}

function label(g, cam, at, text, cls = 'label', dy = 0) {
  const [x, y] = cam.toScreen(at);
  return el('text', { x: x.toFixed(1), y: (y + dy).toFixed(1), class: cls }, g, text);
}

function drawElement(g, cam, doc, layer, index, flagged) {
  const item = doc[layer][index];
  const sel = { layer, index };
  const vs = verticesOf(doc, sel);
  const base = { 'data-layer': layer, 'data-index': index };
  const bad = flagged ? ' flagged' : '';
  if (layer === 'walls' && vs && vs.length >= 2) {
    const width = Math.max(2, (item.thickness ?? 0.2) * cam.scale);
    shape(g, cam, vs, false, { ...base, class: `wall${bad}`, 'stroke-width': width.toFixed(1) });
  } else if (layer === 'points') {
    const pos = pointPosition(item);
    if (Array.isArray(item.polygon)) shape(g, cam, item.polygon, true, { ...base, class: `point ${item.kind}${bad}` });
    else if (pos) {
      const [x, y] = cam.toScreen(pos);
      el('circle', { ...base, cx: x, cy: y, r: Math.max(4, (item.radius ?? 0.5) * cam.scale), class: `point ${item.kind}${bad}` }, g);
    }
    if (pos && item.kind === 'action') {
      const o = item.orientation || [1, 0];
      const n = Math.hypot(o[0], o[1]) || 1;
      const tip = cam.toScreen([pos[0] + (o[0] / n) * 0.8, pos[1] + (o[1] / n) * 0.8]);
      const [x, y] = cam.toScreen(pos);
      el('line', { x1: x, y1: y, x2: tip[0], y2: tip[1], class: 'orientation', 'marker-end': 'url(#arrow)' }, g);
    }
    if (pos) label(g, cam, pos, item.id || '?');
  } else if (vs && vs.length) {
    const cls = { walkable: 'walkable', obstacles: 'obstacle', measurements: 'measurement', populations: 'spawn' }[layer];
    if (vs.length === 1) {
      const [x, y] = cam.toScreen(vs[0]);
      el('circle', { ...base, cx: x, cy: y, r: 6, class: `${cls}${bad}` }, g);
    } else {
      shape(g, cam, vs, isClosed(doc, sel), { ...base, class: `${cls}${bad}` });
    }
    if (layer === 'populations') {
      const size = Array.isArray(item.size) ? `${item.size[0]}–${item.size[1]}` : item.size ?? 1;
      label(g, cam, anchorOf(doc, sel), `${item.id || 'crowd'} · ${item.groups ?? 1}×${size}`);
    } else if (layer === 'measurements') label(g, cam, anchorOf(doc, sel), item.id || '', 'label small');
  }
}

/** Arrows from each population's spawn through its goals, numbered in order (a waypoint choice:
 * dotted arrows to each of its options, numbered with a "?"). */
function drawGoals(g, cam, doc, selected) {
  const byId = new Map((doc.points || []).map((p) => [p.id, pointPosition(p)]));
  (doc.populations || []).forEach((pop, index) => {
    if (!Array.isArray(pop.goals)) return;
    let from = anchorOf(doc, { layer: 'populations', index });
    const active = selected && selected.layer === 'populations' && selected.index === index;
    pop.goals.forEach((goal, k) => {
      // A waypoint choice: a dotted arrow to each option, the next goal's arrow from their centre.
      const choice = isChoice(goal);
      const tos = goalIds(goal).map((id) => byId.get(id)).filter(Boolean);
      if (!from || !tos.length) return;
      for (const to of tos) {
        const a = cam.toScreen(from), b = cam.toScreen(to);
        el('line', { x1: a[0], y1: a[1], x2: b[0], y2: b[1], class: `goal-arrow${choice ? ' choice' : ''}${active ? ' active' : ''}`,
          'marker-end': 'url(#arrow)' }, g);
        label(g, cam, [(from[0] + to[0]) / 2, (from[1] + to[1]) / 2], choice ? `${k + 1}?` : String(k + 1), 'label goal-order');
      }
      from = [tos.reduce((s, p) => s + p[0], 0) / tos.length, tos.reduce((s, p) => s + p[1], 0) / tos.length];
    });
  });
}

/** Handles on every vertex of the selection, edge lengths and the area. */
function drawSelection(g, cam, doc, sel) {
  const vs = verticesOf(doc, sel);
  if (!vs) return;
  const closed = isClosed(doc, sel);
  if (vs.length > 1) shape(g, cam, vs, closed, { class: 'selected-outline' });
  const n = vs.length;
  for (let i = 0; i < n && n > 1; i++) {
    if (!closed && i === n - 1) break;
    const a = vs[i], b = vs[(i + 1) % n];
    label(g, cam, [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2], `${fmt(dist(a, b))} m`, 'label measure');
  }
  vs.forEach((v, i) => {
    const [x, y] = cam.toScreen(v);
    el('rect', { x: x - 5, y: y - 5, width: 10, height: 10, class: `handle${sel.vertex === i ? ' active' : ''}`,
                 'data-layer': sel.layer, 'data-index': sel.index, 'data-vertex': i }, g);
  });
  if (closed && n >= 3) label(g, cam, centroid(vs), `${fmt(polygonArea(vs))} m²`, 'label measure area', 16);
  else if (!closed && n >= 2) label(g, cam, vs[n - 1], `${fmt(polylineLength(vs))} m`, 'label measure');
}

function drawDraft(g, cam, draft, cursor, snapKind) {
  if (!draft) return;
  const vs = cursor ? [...draft.points, cursor] : draft.points;
  if (vs.length > 1) shape(g, cam, vs, false, { class: 'draft' });
  for (const v of draft.points) {
    const [x, y] = cam.toScreen(v);
    el('circle', { cx: x, cy: y, r: 4, class: 'draft-vertex' }, g);
  }
  if (cursor && draft.points.length) {
    const last = draft.points[draft.points.length - 1];
    label(g, cam, [(last[0] + cursor[0]) / 2, (last[1] + cursor[1]) / 2], `${fmt(dist(last, cursor))} m`, 'label measure');
    if (draft.closed && vs.length >= 3) label(g, cam, cursor, `${fmt(polygonArea(vs))} m²`, 'label measure area');
  }
  if (cursor && snapKind && snapKind !== 'none') {
    const [x, y] = cam.toScreen(cursor);
    el('circle', { cx: x, cy: y, r: 7, class: `snap ${snapKind}` }, g);
  }
}

function drawDiagnostics(g, cam, doc, diagnostics) {
  diagnostics.forEach((d, i) => {
    const at = d.element ? anchorOf(doc, d.element) : null;
    if (!at) return;
    const [x, y] = cam.toScreen(at);
    const m = el('g', { class: 'diagnostic', 'data-diagnostic': i, transform: `translate(${x.toFixed(1)},${(y - 14).toFixed(1)})` }, g);
    el('circle', { r: 9 }, m);
    el('text', { y: 4 }, m, '!');
    el('title', {}, m, d.message);
  });
}

function drawPreview(g, cam, frame) {
  if (!frame) return;
  const r = Math.max(2, 0.2 * cam.scale);
  for (let i = 0; i < frame.ids.length; i++) {
    const [x, y] = cam.toScreen([frame.xy[2 * i], frame.xy[2 * i + 1]]);
    el('circle', { cx: x.toFixed(1), cy: y.toFixed(1), r: r.toFixed(1), class: 'agent' }, g);
  }
}

/** A floor plan image to trace over: its lower-left corner at (x0, y0), `width` × `height` metres. */
function drawBackground(svg, cam, bg) {
  const [x, y] = cam.toScreen([bg.x0, bg.y0 + bg.height]);
  el('image', { href: bg.href, x: x.toFixed(1), y: y.toFixed(1), width: (bg.width * cam.scale).toFixed(1),
                height: (bg.height * cam.scale).toFixed(1), opacity: 0.45, preserveAspectRatio: 'none', class: 'background' }, svg);
}

/** Redraws everything. `state`: doc, sel, draft, cursor, snapKind, diagnostics, grid, previewFrame. */
export function render(svg, cam, state) {
  svg.replaceChildren();
  const defs = el('defs', {}, svg);
  const marker = el('marker', { id: 'arrow', viewBox: '0 0 10 10', refX: 9, refY: 5, markerWidth: 7, markerHeight: 7, orient: 'auto-start-reverse' }, defs);
  el('path', { d: 'M0,0L10,5L0,10z', class: 'arrow-head' }, marker);
  drawGrid(el('g', { class: 'grid' }, svg), cam, state.grid);
  if (state.background) drawBackground(svg, cam, state.background);
  const flagged = new Set(state.diagnostics.filter((d) => d.element && d.element.index != null)
    .map((d) => `${d.element.layer}/${d.element.index}`));
  const world = el('g', { class: 'world' }, svg);
  for (const layer of LAYERS) {
    (state.doc[layer] || []).forEach((_, index) => drawElement(world, cam, state.doc, layer, index, flagged.has(`${layer}/${index}`)));
  }
  drawGoals(el('g', { class: 'goals' }, svg), cam, state.doc, state.sel);
  drawPreview(el('g', { class: 'preview' }, svg), cam, state.previewFrame);
  if (state.sel && state.sel.index != null) drawSelection(el('g', { class: 'selection' }, svg), cam, state.doc, state.sel);
  drawDraft(el('g', { class: 'drafting' }, svg), cam, state.draft, state.cursor, state.snapKind);
  drawDiagnostics(el('g', { class: 'diagnostics' }, svg), cam, state.doc, state.diagnostics);
}
