// The editor's tools: what a click, a drag, a double-click or Enter does in the plan. Select moves
// vertices and whole elements (snapped), and picks goals for the selected crowd (or options of one
// of its waypoint choices); the drawing tools make polygons (clicks, or one drag for a rectangle),
// polylines and points, and turn the finished drawing into a scenario element with a fresh id.
// Edits go through `app.commit()` (undo, check).
import { rectangle, snapPoint, dist, distanceToSegment, polygonArea, polylineLength } from './geometry.js';
import { allVertices, uniqueId, verticesOf, isClosed } from './doc.js';
import { addOption } from './goals.js';

/** key: shortcut; shape: 'polygon' (closed), 'polyline' (open, max points), 'point'. */
export const TOOLS = {
  select: { key: 'v', label: 'Select', shape: null, help: 'select, drag vertices or elements; double-click an edge adds a vertex' },
  walkable: { key: 'w', label: 'Walkable', shape: 'polygon', help: 'walkable area: click corners, or drag a rectangle' },
  obstacle: { key: 'o', label: 'Obstacle', shape: 'polygon', help: 'obstacle (hole): click corners, or drag a rectangle' },
  wall: { key: 'l', label: 'Wall', shape: 'polyline', help: 'wall: click points, Enter or double-click ends; a drag draws one segment' },
  exit: { key: 'e', label: 'Exit', shape: 'polygon', help: 'exit area: drag a rectangle or click corners' },
  crowd: { key: 'c', label: 'Crowd', shape: 'polygon', help: 'crowd spawn area: drag a rectangle; then click points for its goals' },
  interest: { key: 'i', label: 'Interest', shape: 'point', help: 'interest point (a disc agents pass through): click' },
  action: { key: 'a', label: 'Action', shape: 'point', help: 'action point (agents stop, face, play a clip): click' },
  waypoint: { key: 'p', label: 'Waypoint', shape: 'point', help: 'waypoint (a small interest point on a route): click' },
  line: { key: 'm', label: 'Measure line', shape: 'polyline', max: 2, help: 'measurement line: two clicks or a drag' },
  area: { key: 'n', label: 'Measure area', shape: 'polygon', help: 'measurement area: drag a rectangle or click corners' },
};

const round = (p) => [Number(p[0].toFixed(3)), Number(p[1].toFixed(3))];

/** The new element a finished drawing makes: {layer, item}. */
export function elementFor(doc, tool, points) {
  const vs = points.map(round);
  switch (tool) {
    case 'walkable': return { layer: 'walkable', item: vs };
    case 'obstacle': return { layer: 'obstacles', item: vs };
    case 'wall': return { layer: 'walls', item: { id: uniqueId(doc, 'walls', 'wall'), line: vs, thickness: 0.2 } };
    case 'line': return { layer: 'measurements', item: { id: uniqueId(doc, 'measurements', 'line'), line: vs } };
    case 'area': return { layer: 'measurements', item: { id: uniqueId(doc, 'measurements', 'area'), polygon: vs } };
    case 'exit': return { layer: 'points', item: { id: uniqueId(doc, 'points', 'exit'), kind: 'exit', polygon: vs } };
    case 'crowd':
      return { layer: 'populations', item: { id: uniqueId(doc, 'populations', 'crowd'), groups: 20, spawn: { polygon: vs }, goals: [] } };
    case 'interest': return { layer: 'points', item: { id: uniqueId(doc, 'points', 'interest'), kind: 'interest', position: vs[0], radius: 0.5 } };
    case 'action':
      return { layer: 'points', item: { id: uniqueId(doc, 'points', 'action'), kind: 'action', position: vs[0], radius: 0.5, orientation: [1, 0] } };
    case 'waypoint': return { layer: 'points', item: { id: uniqueId(doc, 'points', 'waypoint'), kind: 'interest', position: vs[0], radius: 0.3 } };
    default: return null;
  }
}

export class ToolController {
  /** `app`: {doc, sel, cam, state, commit(), render(), select(sel), setStatus(text)}. */
  constructor(app, svg) {
    this.app = app;
    this.svg = svg;
    this.tool = 'select';
    this.draft = null;
    this.press = null;  // the pointer held down: {start, screen, mode, ...}
    svg.addEventListener('pointerdown', (e) => this.down(e));
    svg.addEventListener('pointermove', (e) => this.move(e));
    svg.addEventListener('pointerup', (e) => this.up(e));
    this.lastUp = null;  // {time, screen}: double-clicks are told by time and place (the plan is redrawn between the clicks)
    svg.addEventListener('wheel', (e) => this.wheel(e), { passive: false });
    svg.addEventListener('contextmenu', (e) => e.preventDefault());
  }

  setTool(name) {
    if (!TOOLS[name]) return;
    this.tool = name;
    this.draft = null;
    this.app.state.pickGoals = false;
    this.app.state.pickChoice = null;
    this.app.setStatus(TOOLS[name].help);
    this.app.render();
  }

  screenOf(e) {
    const r = this.svg.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  }

  /** The cursor snapped for drawing (or moving a vertex whose neighbours are `anchor`, `before`). */
  snap(screen, anchor = null, before = null, skip = null) {
    const { cam, state } = this.app;
    const raw = cam.toWorld(screen);
    if (!state.snap) return { point: raw, kind: 'none' };
    return snapPoint(raw, { grid: state.grid, vertices: allVertices(this.app.doc, skip), tolerance: 8 / cam.scale, anchor, before });
  }

  draftSnap(screen) {
    const pts = this.draft?.points || [];
    return this.snap(screen, pts[pts.length - 1] || null, pts[pts.length - 2] || null);
  }

  down(e) {
    const screen = this.screenOf(e);
    this.svg.setPointerCapture?.(e.pointerId);
    if (e.button === 1 || e.button === 2 || (this.tool === 'select' && !e.target.closest('[data-layer]') && !this.app.state.pickGoals)) {
      this.press = { mode: 'pan', screen, cx: this.app.cam.cx, cy: this.app.cam.cy };
      return;
    }
    if (this.tool === 'select') return this.downSelect(e, screen);
    this.press = { mode: 'draw', screen, start: this.draftSnap(screen).point };
  }

  downSelect(e, screen) {
    const target = e.target.closest('[data-layer]');
    if (!target) return;
    const layer = target.getAttribute('data-layer');
    const index = Number(target.getAttribute('data-index'));
    const sel = this.app.sel;
    if (this.app.state.pickGoals && sel?.layer === 'populations' && layer === 'points') {
      const id = this.app.doc.points[index]?.id;
      const pop = this.app.doc.populations[sel.index];
      const into = this.app.state.pickChoice;
      if (id && pop && into !== null && Array.isArray(pop.goals) && pop.goals[into] !== undefined) {
        // Exits are chosen among with the crowd's "exits" and "exitChoice", not in a waypoint choice.
        if (this.app.doc.points[index].kind === 'exit') {
          this.app.setStatus(`${id} is an exit: a waypoint choice is among interest or action points (tick exits under "exits")`);
        } else {
          pop.goals[into] = addOption(pop.goals[into], id);
          this.app.commit(`${id} added as an option of goal ${into + 1} of ${pop.id}`);
        }
      } else if (id && pop) {
        pop.goals = Array.isArray(pop.goals) ? [...pop.goals, id] : [id];
        this.app.commit(`goal ${id} added to ${pop.id}`);
      }
      return;
    }
    if (target.hasAttribute('data-vertex')) {
      const vertex = Number(target.getAttribute('data-vertex'));
      this.app.select({ layer, index, vertex });
      this.press = { mode: 'vertex', screen, moved: false };
      return;
    }
    this.app.select({ layer, index });
    const vs = verticesOf(this.app.doc, { layer, index });
    this.press = { mode: 'element', screen, moved: false, origin: this.app.cam.toWorld(screen), from: vs ? vs.map((v) => v.slice()) : null };
  }

  move(e) {
    const screen = this.screenOf(e);
    const { cam, state } = this.app;
    const p = this.press;
    if (p?.mode === 'pan') {
      cam.cx = p.cx - (screen[0] - p.screen[0]) / cam.scale;
      cam.cy = p.cy + (screen[1] - p.screen[1]) / cam.scale;
      return this.app.render();
    }
    if (p?.mode === 'vertex') return this.dragVertex(p, screen);
    if (p?.mode === 'element') return this.dragElement(p, screen);
    if (this.tool !== 'select') {
      const s = this.draftSnap(screen);
      state.cursor = s.point;
      state.snapKind = s.kind;
      if (p?.mode === 'draw' && !this.draft && dist(p.screen, screen) > 5 && TOOLS[this.tool].shape !== 'point') p.drag = true;
      if (p?.drag) state.dragPreview = TOOLS[this.tool].shape === 'polygon' ? rectangle(p.start, s.point) : [p.start, s.point];
      this.app.setCursorText(s.point, s.kind);
      this.app.render();
    }
  }

  dragVertex(p, screen) {
    const sel = this.app.sel;
    const vs = verticesOf(this.app.doc, sel);
    if (!vs || vs[sel.vertex] === undefined) return;
    const n = vs.length, i = sel.vertex, closed = isClosed(this.app.doc, sel);
    const prev = i > 0 ? vs[i - 1] : closed ? vs[n - 1] : null;
    const before = i > 1 ? vs[i - 2] : closed && n > 2 ? vs[(i - 2 + n) % n] : null;
    const s = this.snap(screen, prev, before, sel);
    vs[i][0] = s.point[0];
    vs[i][1] = s.point[1];
    p.moved = true;
    this.app.state.snapKind = s.kind;
    this.app.render();
  }

  dragElement(p, screen) {
    if (!p.from || dist(p.screen, screen) < 3) return;
    const vs = verticesOf(this.app.doc, this.app.sel);
    const w = this.app.cam.toWorld(screen);
    let dx = w[0] - p.origin[0], dy = w[1] - p.origin[1];
    if (this.app.state.snap && this.app.state.grid > 0) {
      const g = this.app.state.grid;
      dx = Math.round(dx / g) * g;
      dy = Math.round(dy / g) * g;
    }
    vs.forEach((v, k) => { v[0] = Number((p.from[k][0] + dx).toFixed(3)); v[1] = Number((p.from[k][1] + dy).toFixed(3)); });
    p.moved = true;
    this.app.render();
  }

  up(e) {
    const p = this.press;
    this.press = null;
    this.app.state.dragPreview = null;
    const screen = this.screenOf(e);
    const last = this.lastUp;
    this.lastUp = { time: e.timeStamp, screen };
    const second = last && e.timeStamp - last.time < 450 && dist(last.screen, screen) < 6 && !(p && p.moved) && !(p && p.drag);
    if (second) this.lastUp = null;
    if (second && this.tool === 'select' && !this.app.state.pickGoals) return this.insertVertex(screen);
    if (second && this.draft) {
      this.upDraw(p, screen);
      return this.finishDraft();
    }
    this.upDraw(p, screen);
  }

  upDraw(p, screen) {
    if (!p) return;
    if ((p.mode === 'vertex' || p.mode === 'element') && p.moved) return this.app.commit('moved');
    if (p.mode !== 'draw') return;
    const shape = TOOLS[this.tool].shape;
    if (p.drag) {
      const end = this.draftSnap(screen).point;
      return this.finish(shape === 'polygon' ? rectangle(p.start, end) : [p.start, end]);
    }
    const at = this.draftSnap(screen).point;
    if (shape === 'point') return this.finish([at]);
    if (!this.draft) this.draft = { points: [], closed: shape === 'polygon' };
    const pts = this.draft.points;
    if (shape === 'polygon' && pts.length >= 3 && dist(this.app.cam.toScreen(pts[0]), screen) < 8) return this.finishDraft();
    if (pts.length && dist(pts[pts.length - 1], at) < 1e-9) return;  // the second click of a double-click
    pts.push(at);
    if (TOOLS[this.tool].max && pts.length >= TOOLS[this.tool].max) return this.finishDraft();
    this.app.render();
  }

  /** Double-click on an edge of the selection: a new vertex there. */
  insertVertex(screen) {
    const sel = this.app.sel;
    const vs = verticesOf(this.app.doc, sel);
    if (!vs || vs.length < 2) return;
    const w = this.app.cam.toWorld(screen);
    const closed = isClosed(this.app.doc, sel);
    let best = -1, bestD = 8 / this.app.cam.scale;
    for (let i = 0; i < vs.length - (closed ? 0 : 1); i++) {
      const d = distanceToSegment(w, vs[i], vs[(i + 1) % vs.length]);
      if (d < bestD) { best = i; bestD = d; }
    }
    if (best < 0) return;
    vs.splice(best + 1, 0, this.snap(screen).point.map((c) => Number(c.toFixed(3))));
    this.app.sel = { ...sel, vertex: best + 1 };
    this.app.commit('vertex added');
  }

  /** Enter / double-click: ends the polygon or polyline being drawn. */
  finishDraft() {
    if (!this.draft) return;
    const pts = this.draft.points;
    const min = this.draft.closed ? 3 : 2;
    if (pts.length < min) {
      this.app.setStatus(`a ${this.draft.closed ? 'polygon' : 'line'} needs at least ${min} points`);
      return;
    }
    this.finish(pts);
  }

  finish(points) {
    this.draft = null;
    this.app.state.cursor = null;
    const shape = TOOLS[this.tool].shape;
    if ((shape === 'polygon' && polygonArea(points) < 1e-6) || (shape === 'polyline' && polylineLength(points) < 1e-6)) {
      this.app.setStatus('nothing drawn: the shape has no area or length');
      this.app.render();
      return;
    }
    const made = elementFor(this.app.doc, this.tool, points);
    if (!made) return;
    if (!Array.isArray(this.app.doc[made.layer])) this.app.doc[made.layer] = [];
    this.app.doc[made.layer].push(made.item);
    const index = this.app.doc[made.layer].length - 1;
    const tool = this.tool;
    this.app.sel = { layer: made.layer, index };
    if (tool === 'crowd') this.tool = 'select';  // next: pick its goals
    this.app.state.pickGoals = tool === 'crowd';
    this.app.state.pickChoice = null;
    this.app.commit(`${TOOLS[tool].label.toLowerCase()} added`);
    if (tool === 'crowd') this.app.setStatus('crowd added: click points (interest, exit…) for its goals in order; G or Esc ends');
  }

  cancel() {
    if (this.draft) { this.draft = null; this.app.render(); return true; }
    return false;
  }

  wheel(e) {
    e.preventDefault();
    this.app.cam.zoomAt(this.screenOf(e), Math.exp(-e.deltaY * 0.0015));
    this.app.render();
  }
}
