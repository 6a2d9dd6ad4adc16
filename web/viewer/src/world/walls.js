// Walls, railings and stair risers of a world (pure, no DOM, no three.js), from the scenario as the
// world description carries it (docs/scenario-format.md), world metres, z up:
// - walkableWalls(walkable): the stretches of the walkable polygons' edges that border no other
//   walkable polygon (the boundary of their union): where a person meets a wall. A shop whose
//   polygon overlaps a corridor's at its door gets walls all round but the door.
// - terrainWalls(terrain): along the edges of a multi-level world's walkable triangles, each
//   stretch is open (another walkable triangle continues at the same height), a riser (one
//   continues within kMaxStep lower: a step; the riser spans the two heights) or a wall or railing
//   (nothing walkable beyond it within kMaxStep: a room's wall, a gallery's or a stair's edge).
// - wallRectangles(wall): a scenario wall ({line: [[x, y], ...], thickness}) as the obstacle
//   rectangles the engine cuts out of the walkable area: each segment `thickness` wide, lengthened
//   by thickness / 2 at both ends so joints are covered (as libs/io's scenario_walls_parser.cpp).
// Edges are probed every `step` metres at kProbe beyond the edge, so a partly shared edge (a
// door, the foot of a staircase on a floor) is split where the neighbour ends, to that step.
import { kMaxStep, terrainHeightAt } from './terrain.js';

const kProbe = 0.03;  // [m] how far beyond an edge the neighbour is looked for
const kLevel = 0.01;  // [m] height differences below this are the same level

function bbox(poly) {
  const b = [Infinity, Infinity, -Infinity, -Infinity];
  for (const [x, y] of poly) {
    b[0] = Math.min(b[0], x); b[1] = Math.min(b[1], y); b[2] = Math.max(b[2], x); b[3] = Math.max(b[3], y);
  }
  return b;
}

/** Even-odd test of (x, y) against a polygon [[x, y], ...]. */
export function insidePolygon(x, y, poly) {
  let inside = false;
  for (let i = 0, j = poly.length - 1; i < poly.length; j = i++) {
    const [xi, yi] = poly[i], [xj, yj] = poly[j];
    if ((yi > y) !== (yj > y) && x < xi + ((y - yi) * (xj - xi)) / (yj - yi)) inside = !inside;
  }
  return inside;
}

function signedArea(poly) {
  let a = 0;
  for (let i = 0, j = poly.length - 1; i < poly.length; j = i++) a += poly[j][0] * poly[i][1] - poly[i][0] * poly[j][1];
  return a / 2;
}

/**
 * Walks the edge a → b in pieces of at most `step` metres, classifies each piece by `classify(x, y,
 * t)` (its middle, t in 0..1 along the edge; a value or null for open), and calls emit(t0, t1,
 * value) for each run of pieces with equal values (`same(v, w)`).
 */
function runs(a, b, step, classify, same, emit) {
  const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
  const n = Math.max(1, Math.ceil(len / step));
  let start = 0, current = null;
  for (let k = 0; k < n; ++k) {
    const t = (k + 0.5) / n;
    const v = classify(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), t);
    if (current !== null && (v === null || !same(current, v))) { emit(start, k / n, current); current = null; }
    if (v !== null && current === null) { start = k / n; current = v; }
  }
  if (current !== null) emit(start, 1, current);
}

/** Wall segments [{x0, y0, x1, y1}] [m] along the boundary of the union of the walkable polygons. */
export function walkableWalls(walkable, step = 0.1) {
  const polys = (walkable || []).filter((p) => Array.isArray(p) && p.length >= 3);
  const boxes = polys.map(bbox);
  const covered = (x, y, self) => polys.some((q, i) => i !== self && x >= boxes[i][0] && x <= boxes[i][2] &&
    y >= boxes[i][1] && y <= boxes[i][3] && insidePolygon(x, y, q));
  const out = [];
  polys.forEach((poly, pi) => {
    const sign = signedArea(poly) >= 0 ? 1 : -1;  // outward normal of a counter-clockwise edge: (dy, −dx)
    for (let i = 0; i < poly.length; ++i) {
      const a = poly[i], b = poly[(i + 1) % poly.length];
      const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
      if (!(len > 1e-9)) continue;
      const nx = (sign * (b[1] - a[1])) / len, ny = (-sign * (b[0] - a[0])) / len;
      runs(a, b, step, (x, y) => (covered(x + kProbe * nx, y + kProbe * ny, pi) ? null : true), () => true, (t0, t1) => {
        out.push({ x0: a[0] + t0 * (b[0] - a[0]), y0: a[1] + t0 * (b[1] - a[1]),
                   x1: a[0] + t1 * (b[0] - a[0]), y1: a[1] + t1 * (b[1] - a[1]) });
      });
    }
  });
  return out;
}

/** The edges used by exactly one walkable triangle (by vertex position, so a mesh whose parts repeat
 * their shared vertices still joins): [{a, b, c}] with c the triangle's third vertex. */
function boundaryEdges(terrain) {
  const verts = terrain.vertices || [];
  const key = (v) => `${Math.round(v[0] * 1000)},${Math.round(v[1] * 1000)},${Math.round((v[2] ?? 0) * 1000)}`;
  const edges = new Map();
  for (const f of terrain.walkable || []) {
    if (!Array.isArray(f) || f.length < 3) continue;
    const tri = [verts[f[0]], verts[f[1]], verts[f[2]]];
    if (tri.some((v) => !Array.isArray(v))) continue;
    for (let e = 0; e < 3; ++e) {
      const a = tri[e], b = tri[(e + 1) % 3], c = tri[(e + 2) % 3];
      const ka = key(a), kb = key(b);
      const k = ka < kb ? `${ka}|${kb}` : `${kb}|${ka}`;
      const seen = edges.get(k);
      if (seen) seen.n += 1; else edges.set(k, { n: 1, a, b, c });
    }
  }
  return [...edges.values()].filter((e) => e.n === 1);
}

/**
 * {walls: [{x0, y0, z0, x1, y1, z1}], risers: [{x0, y0, x1, y1, zLow, zHigh}]} [m] of a multi-level
 * world's walkable triangles: walls (1.2 m railings in the viewer) where nothing walkable continues
 * beyond an edge within kMaxStep of its height, risers where a lower walkable surface continues.
 */
export function terrainWalls(terrain, step = 0.25) {
  const walls = [], risers = [];
  if (!terrain || !Array.isArray(terrain.vertices)) return { walls, risers };
  for (const { a, b, c } of boundaryEdges(terrain)) {
    const dx = b[0] - a[0], dy = b[1] - a[1];
    const len = Math.hypot(dx, dy);
    if (!(len > 1e-6)) continue;  // a vertical edge
    let nx = dy / len, ny = -dx / len;
    if ((c[0] - a[0]) * nx + (c[1] - a[1]) * ny > 0) { nx = -nx; ny = -ny; }  // away from the triangle
    const za = a[2] ?? 0, zb = b[2] ?? 0;
    const classify = (x, y, t) => {
      const z = za + t * (zb - za);
      const h = terrainHeightAt(terrain, x + kProbe * nx, y + kProbe * ny, z);
      if (h === null || Math.abs(h - z) > kMaxStep) return { kind: 'wall' };
      if (Math.abs(h - z) <= kLevel || h > z) return null;  // open, or the step up (its own edge draws the riser)
      return { kind: 'riser', drop: z - h };
    };
    const same = (v, w) => v.kind === w.kind && (v.kind === 'wall' || Math.abs(v.drop - w.drop) <= kLevel);
    runs(a, b, step, classify, same, (t0, t1, v) => {
      const x0 = a[0] + t0 * dx, y0 = a[1] + t0 * dy, x1 = a[0] + t1 * dx, y1 = a[1] + t1 * dy;
      const z0 = za + t0 * (zb - za), z1 = za + t1 * (zb - za);
      if (v.kind === 'wall') walls.push({ x0, y0, z0, x1, y1, z1 });
      else risers.push({ x0, y0, x1, y1, zLow: Math.min(z0, z1) - v.drop, zHigh: Math.max(z0, z1) });
    });
  }
  return { walls, risers };
}

/** A scenario wall {line: [[x, y], ...], thickness = 0.2} as rectangles [[x, y] × 4], one per segment
 * of non-zero length, `thickness` wide and lengthened by thickness / 2 at both ends (what the engine
 * cuts out of the walkable area, so the drawing matches where nobody walks). */
export function wallRectangles(wall) {
  const t = Number.isFinite(wall?.thickness) ? wall.thickness : 0.2;
  const line = Array.isArray(wall?.line) ? wall.line : [];
  const out = [];
  for (let i = 0; i + 1 < line.length; ++i) {
    const [x0, y0] = line[i], [x1, y1] = line[i + 1];
    const len = Math.hypot(x1 - x0, y1 - y0);
    if (!(len > 1e-9)) continue;
    const ux = (x1 - x0) / len, uy = (y1 - y0) / len;  // along
    const h = t / 2;
    const ax = x0 - ux * h, ay = y0 - uy * h, bx = x1 + ux * h, by = y1 + uy * h;
    const nx = -uy * h, ny = ux * h;  // across
    out.push([[ax + nx, ay + ny], [ax - nx, ay - ny], [bx - nx, by - ny], [bx + nx, by + ny]]);
  }
  return out;
}

/** How far in front of a looking point its wall may be [m] (the museum's paintings are 1.7 m off). */
export const kExhibitReach = 2.5;

/**
 * What visitors look at: for every action point whose action (or clip) is a look and that faces a
 * wall — a segment of `segments` ([{x0, y0, x1, y1}]: the walkable area's boundary and the
 * obstacles' edges) within kExhibitReach along its orientation — an exhibit on that wall:
 * [{point, x, y, nx, ny, width}] (the point itself, the spot on the wall 2 cm in front of it, the
 * unit normal towards the point, a width of 1.6 × its radius clamped to 0.6–1.3 m).
 * Points facing no wall within reach (a statue in a square) get none.
 */
export function exhibitsOnWalls(points, segments) {
  const out = [];
  for (const p of points || []) {
    if (p.kind !== 'action' || !Array.isArray(p.position) || !/look/i.test(`${p.action || ''} ${p.clip || ''}`)) continue;
    const o = p.orientation || [1, 0];
    const l = Math.hypot(o[0], o[1]);
    if (!(l > 1e-9)) continue;
    const dx = o[0] / l, dy = o[1] / l, [px, py] = p.position;
    let best = Infinity;
    for (const s of segments) {
      const ex = s.x1 - s.x0, ey = s.y1 - s.y0;
      const den = dx * ey - dy * ex;
      if (Math.abs(den) < 1e-12) continue;
      const qx = s.x0 - px, qy = s.y0 - py;
      const t = (qx * ey - qy * ex) / den, u = (qx * dy - qy * dx) / den;
      if (t > 0 && t < best && u >= 0 && u <= 1) best = t;
    }
    if (!(best <= kExhibitReach)) continue;
    const at = best - 0.02;
    out.push({ point: p, x: px + dx * at, y: py + dy * at, nx: -dx, ny: -dy, width: Math.min(1.3, Math.max(0.6, 1.6 * (p.radius ?? 0.5))) });
  }
  return out;
}

/** The edges of polygons [[x, y], ...] as segments [{x0, y0, x1, y1}]. */
export function polygonEdges(polys) {
  const out = [];
  for (const poly of polys || []) {
    for (let i = 0; i < poly.length; ++i) {
      const a = poly[i], b = poly[(i + 1) % poly.length];
      out.push({ x0: a[0], y0: a[1], x1: b[0], y1: b[1] });
    }
  }
  return out;
}
