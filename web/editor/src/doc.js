// The scenario document the editor edits — the scenario JSON object itself, so that every
// diagnostic's JSON pointer names a place in it — and pure operations on it (no DOM): the editable
// elements and their vertices, JSON pointer ↔ element, anchors for markers, unique ids, removal
// (references to a removed point go with it, from waypoint choices too), merging an imported plan,
// and the undo/redo history.
import { centroid } from './geometry.js';
import { removeOption, renameInGoal } from './goals.js';

/** The collections the plan shows, in drawing order (docs/scenario-format.md). */
export const LAYERS = ['walkable', 'obstacles', 'walls', 'measurements', 'populations', 'points'];

/** A minimal scenario (what a new file starts from when the server sends none). */
export function emptyScenario(name = 'scenario') {
  return { format: 'throng/1', name, duration: 60, walkable: [], points: [], populations: [] };
}

/** The vertex array of an element ({layer, index}) — mutable, in the document — or null. */
export function verticesOf(doc, sel) {
  if (!sel || sel.index == null) return null;
  const list = doc[sel.layer];
  const item = Array.isArray(list) ? list[sel.index] : undefined;
  if (item === undefined) return null;
  switch (sel.layer) {
    case 'walkable': case 'obstacles': return Array.isArray(item) ? item : null;
    case 'walls': return Array.isArray(item.line) ? item.line : null;
    case 'measurements': return Array.isArray(item.line) ? item.line : Array.isArray(item.polygon) ? item.polygon : null;
    case 'points': return Array.isArray(item.polygon) ? item.polygon : Array.isArray(item.position) ? [item.position] : null;
    case 'populations': {
      const s = item.spawn || {};
      return Array.isArray(s.polygon) ? s.polygon : Array.isArray(s.position) ? [s.position] : null;
    }
    default: return null;
  }
}

/** Whether the element's vertices form a closed polygon (else a polyline or a single position). */
export function isClosed(doc, sel) {
  if (sel.layer === 'walkable' || sel.layer === 'obstacles') return true;
  const item = doc[sel.layer]?.[sel.index];
  if (!item) return false;
  if (sel.layer === 'populations') return Array.isArray(item.spawn?.polygon);
  return Array.isArray(item.polygon);
}

/** The JSON pointer of an element (and of one of its vertices). */
export function elementPointer(doc, sel) {
  if (!sel) return '';
  let p = `/${sel.layer}/${sel.index}`;
  if (sel.vertex == null) return p;
  const item = doc[sel.layer]?.[sel.index];
  switch (sel.layer) {
    case 'walls': return `${p}/line/${sel.vertex}`;
    case 'measurements': return `${p}/${Array.isArray(item?.line) ? 'line' : 'polygon'}/${sel.vertex}`;
    case 'points': return Array.isArray(item?.polygon) ? `${p}/polygon/${sel.vertex}` : `${p}/position`;
    case 'populations': return Array.isArray(item?.spawn?.polygon) ? `${p}/spawn/polygon/${sel.vertex}` : `${p}/spawn/position`;
    default: return `${p}/${sel.vertex}`;
  }
}

const unescape = (t) => t.replace(/~1/g, '/').replace(/~0/g, '~');

/**
 * The element a JSON pointer names: {layer, index, vertex?, field?}, {layer} for a whole
 * collection ("/walkable"), or null for the document itself or a key the plan does not show.
 * "/populations/0/goals/1" gives {layer: 'populations', index: 0, field: 'goals', item: 1}.
 */
export function elementForPointer(doc, pointer) {
  if (typeof pointer !== 'string' || !pointer.startsWith('/')) return null;
  const t = pointer.slice(1).split('/').map(unescape);
  const layer = t[0];
  if (!LAYERS.includes(layer)) return null;
  if (t.length === 1 || !/^\d+$/.test(t[1])) return { layer, index: null };
  const index = Number(t[1]);
  const count = Array.isArray(doc?.[layer]) ? doc[layer].length : 0;
  if (index >= count) return { layer, index: null };
  const sel = { layer, index };
  const num = (s) => (s !== undefined && /^\d+$/.test(s) ? Number(s) : undefined);
  let vertex;
  if (layer === 'walkable' || layer === 'obstacles') vertex = num(t[2]);
  else if ((layer === 'walls' && t[2] === 'line') || (layer === 'measurements' && (t[2] === 'line' || t[2] === 'polygon')) ||
           (layer === 'points' && t[2] === 'polygon')) vertex = num(t[3]);
  else if (layer === 'populations' && t[2] === 'spawn' && t[3] === 'polygon') vertex = num(t[4]);
  else if (t.length > 2) {
    sel.field = t[2];
    if (num(t[3]) !== undefined) sel.item = num(t[3]);
  }
  if (vertex !== undefined) sel.vertex = vertex;
  return sel;
}

/** Where a marker for the element goes: its vertex, else its centre. null when it has no place. */
export function anchorOf(doc, sel) {
  if (!sel || sel.index == null) return null;
  const item = doc[sel.layer]?.[sel.index];
  if (sel.layer === 'points' && Array.isArray(item?.position)) return item.position.slice(0, 2);
  const vs = verticesOf(doc, sel);
  if (!vs || !vs.length) return null;
  if (sel.vertex != null && vs[sel.vertex]) return vs[sel.vertex].slice(0, 2);
  if (isClosed(doc, sel) && vs.length >= 3) return centroid(vs);
  if (vs.length >= 2) return [(vs[0][0] + vs[1][0]) / 2, (vs[0][1] + vs[1][1]) / 2];
  return vs[0].slice(0, 2);
}

/** Where a point is: its disc's centre or its polygon's centroid. */
export function pointPosition(point) {
  if (Array.isArray(point?.position)) return point.position.slice(0, 2);
  if (Array.isArray(point?.polygon) && point.polygon.length >= 3) return centroid(point.polygon);
  return null;
}

/** An id not yet used in `layer` (`prefix`1, `prefix`2, ...). */
export function uniqueId(doc, layer, prefix) {
  const used = new Set((doc[layer] || []).map((e) => e && e.id));
  for (let i = 1; ; i++) if (!used.has(`${prefix}${i}`)) return `${prefix}${i}`;
}

/** Every vertex of the plan (for snapping), except those of `skip` ({layer, index}). */
export function allVertices(doc, skip = null) {
  const out = [];
  for (const layer of LAYERS) {
    (doc[layer] || []).forEach((_, index) => {
      if (skip && skip.layer === layer && skip.index === index) return;
      for (const v of verticesOf(doc, { layer, index }) || []) if (Array.isArray(v)) out.push(v);
    });
  }
  return out;
}

/** Removes an element; removing a point drops it from every population's goals (and waypoint
 * choices) and exits. */
export function removeElement(doc, sel) {
  const list = doc[sel.layer];
  if (!Array.isArray(list) || !list[sel.index]) return;
  const [removed] = list.splice(sel.index, 1);
  if (sel.layer === 'points' && removed?.id) {
    for (const pop of doc.populations || []) {
      if (Array.isArray(pop.goals)) pop.goals = pop.goals.map((g) => removeOption(g, removed.id)).filter((g) => g !== null);
      if (Array.isArray(pop.exits)) {
        pop.exits = pop.exits.filter((g) => g !== removed.id);
        if (!pop.exits.length) { delete pop.exits; delete pop.exitChoice; }
      }
    }
  }
  if (!list.length && sel.layer !== 'walkable' && sel.layer !== 'points' && sel.layer !== 'populations') delete doc[sel.layer];
}

/**
 * Adds an imported plan fragment ({walkable, obstacles, walls}, io::importPlan's) to the document:
 * its walkable polygons replace an empty walkable area (else join it), obstacles and walls are
 * appended, each wall with a fresh id. Returns how many of each were added.
 */
export function mergePlan(doc, fragment) {
  const added = { walkable: 0, obstacles: 0, walls: 0 };
  for (const poly of fragment.walkable || []) { (doc.walkable ||= []).push(poly); added.walkable++; }
  for (const poly of fragment.obstacles || []) { (doc.obstacles ||= []).push(poly); added.obstacles++; }
  for (const wall of fragment.walls || []) {
    const id = wall.id && !(doc.walls || []).some((w) => w.id === wall.id) ? wall.id : uniqueId(doc, 'walls', 'wall');
    (doc.walls ||= []).push({ ...wall, id });
    added.walls++;
  }
  return added;
}

/** Renames a point and every reference to it. */
export function renamePoint(doc, index, id) {
  const old = doc.points[index].id;
  doc.points[index].id = id;
  for (const pop of doc.populations || []) {
    if (Array.isArray(pop.goals)) pop.goals = pop.goals.map((g) => renameInGoal(g, old, id));
    if (Array.isArray(pop.exits)) pop.exits = pop.exits.map((g) => (g === old ? id : g));
    if (pop.spawn?.point === old) pop.spawn.point = id;
  }
}

/** Undo/redo over snapshots of the document (JSON text). */
export class History {
  constructor(doc, limit = 200) {
    this.limit = limit;
    this.past = [];
    this.future = [];
    this.current = JSON.stringify(doc);
  }
  /** Records `doc` after an edit; false when nothing changed. */
  push(doc) {
    const next = JSON.stringify(doc);
    if (next === this.current) return false;
    this.past.push(this.current);
    if (this.past.length > this.limit) this.past.shift();
    this.current = next;
    this.future = [];
    return true;
  }
  undo() {
    if (!this.past.length) return null;
    this.future.push(this.current);
    this.current = this.past.pop();
    return JSON.parse(this.current);
  }
  redo() {
    if (!this.future.length) return null;
    this.past.push(this.current);
    this.current = this.future.pop();
    return JSON.parse(this.current);
  }
}
