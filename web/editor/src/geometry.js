// Pure plan geometry of the scenario editor (no DOM): lengths, polygon area and centroid, the
// simplicity check the validator applies (docs/scenario-format.md: edges meet only at consecutive
// vertices), point-in-polygon, distance to a segment, and snapping of a cursor position to the
// grid, to existing vertices and to right angles. Coordinates are metres, [x, y] arrays.

export const dist = (a, b) => Math.hypot(b[0] - a[0], b[1] - a[1]);

/** Total length of a polyline [m] (closed adds the last edge back to the first point). */
export function polylineLength(points, closed = false) {
  let total = 0;
  for (let i = 1; i < points.length; i++) total += dist(points[i - 1], points[i]);
  if (closed && points.length > 2) total += dist(points[points.length - 1], points[0]);
  return total;
}

/** Signed area (shoelace) [m²]: positive counter-clockwise. */
export function signedArea(polygon) {
  let a = 0;
  for (let i = 0, n = polygon.length; i < n; i++) {
    const p = polygon[i], q = polygon[(i + 1) % n];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return a / 2;
}

export const polygonArea = (polygon) => Math.abs(signedArea(polygon));

/** Area centroid; the vertex mean for a degenerate polygon. */
export function centroid(polygon) {
  const a = signedArea(polygon);
  if (Math.abs(a) < 1e-12) {
    const n = Math.max(1, polygon.length);
    return [polygon.reduce((s, p) => s + p[0], 0) / n, polygon.reduce((s, p) => s + p[1], 0) / n];
  }
  let cx = 0, cy = 0;
  for (let i = 0, n = polygon.length; i < n; i++) {
    const p = polygon[i], q = polygon[(i + 1) % n];
    const f = p[0] * q[1] - q[0] * p[1];
    cx += (p[0] + q[0]) * f;
    cy += (p[1] + q[1]) * f;
  }
  return [cx / (6 * a), cy / (6 * a)];
}

function orient(a, b, c) {
  const v = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  return Math.abs(v) < 1e-12 ? 0 : Math.sign(v);
}

function onSegment(a, b, p) {
  return Math.min(a[0], b[0]) - 1e-12 <= p[0] && p[0] <= Math.max(a[0], b[0]) + 1e-12 &&
         Math.min(a[1], b[1]) - 1e-12 <= p[1] && p[1] <= Math.max(a[1], b[1]) + 1e-12;
}

/** Whether segments ab and cd share a point (touching counts). */
export function segmentsIntersect(a, b, c, d) {
  const o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 !== o2 && o3 !== o4) return true;
  return (o1 === 0 && onSegment(a, b, c)) || (o2 === 0 && onSegment(a, b, d)) ||
         (o3 === 0 && onSegment(c, d, a)) || (o4 === 0 && onSegment(c, d, b));
}

/** Drops consecutive repeated points and a closing repeat of the first (as the loader does). */
export function cleanPolygon(polygon) {
  const out = [];
  for (const p of polygon) {
    if (!out.length || dist(out[out.length - 1], p) > 1e-9) out.push(p);
  }
  while (out.length > 1 && dist(out[0], out[out.length - 1]) <= 1e-9) out.pop();
  return out;
}

/** Why `polygon` would be refused (at least 3 distinct points, area ≥ 1e-6 m², simple), or null. */
export function polygonProblem(polygon) {
  const p = cleanPolygon(polygon);
  if (p.length < 3) return 'fewer than 3 distinct points';
  if (polygonArea(p) < 1e-6) return 'zero area';
  const n = p.length;
  for (let i = 0; i < n; i++) {
    for (let j = i + 1; j < n; j++) {
      const adjacent = j === i + 1 || (i === 0 && j === n - 1);
      const a = p[i], b = p[(i + 1) % n], c = p[j], d = p[(j + 1) % n];
      if (adjacent) {
        // Consecutive edges may only share their common vertex: a spike folding back crosses.
        const shared = j === i + 1 ? b : a;
        const other1 = j === i + 1 ? a : b, other2 = j === i + 1 ? d : c;
        if (orient(other1, shared, other2) === 0 &&
            (other2[0] - shared[0]) * (other1[0] - shared[0]) + (other2[1] - shared[1]) * (other1[1] - shared[1]) > 0) {
          return `edges ${i} and ${j} fold back on each other`;
        }
        continue;
      }
      if (segmentsIntersect(a, b, c, d)) return `edges ${i} and ${j} cross`;
    }
  }
  return null;
}

export const isSimplePolygon = (polygon) => polygonProblem(polygon) === null;

/** Even-odd point-in-polygon. */
export function pointInPolygon(p, polygon) {
  let inside = false;
  for (let i = 0, j = polygon.length - 1; i < polygon.length; j = i++) {
    const a = polygon[i], b = polygon[j];
    if ((a[1] > p[1]) !== (b[1] > p[1]) && p[0] < ((b[0] - a[0]) * (p[1] - a[1])) / (b[1] - a[1]) + a[0]) inside = !inside;
  }
  return inside;
}

/** Distance from p to segment ab [m]. */
export function distanceToSegment(p, a, b) {
  const dx = b[0] - a[0], dy = b[1] - a[1];
  const len2 = dx * dx + dy * dy;
  const t = len2 === 0 ? 0 : Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2));
  return Math.hypot(p[0] - (a[0] + t * dx), p[1] - (a[1] + t * dy));
}

/** Rounds to `step` and trims float noise (0.1 + 0.2 → 0.3). */
export function roundTo(value, step) {
  if (!(step > 0)) return value;
  return Number((Math.round(value / step) * step).toFixed(6));
}

/** The four corners of the rectangle spanned by a and b, counter-clockwise from the lowest x, y. */
export function rectangle(a, b) {
  const x0 = Math.min(a[0], b[0]), x1 = Math.max(a[0], b[0]), y0 = Math.min(a[1], b[1]), y1 = Math.max(a[1], b[1]);
  return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
}

/**
 * Snaps `p` for drawing. Options: grid (step [m], 0 = off), vertices (existing points), tolerance
 * (capture distance [m], usually a few pixels), anchor (the previous vertex: right angles and axes
 * relative to it), before (the vertex before the anchor: right angles to that segment).
 * Returns {point, kind}: kind 'vertex', 'right-angle', 'axis', 'grid' or 'none'. A vertex wins,
 * then a right angle or an axis through the anchor (the point moved onto that line, then along it
 * to the grid), then the grid.
 */
export function snapPoint(p, { grid = 0, vertices = [], tolerance = 0.2, anchor = null, before = null } = {}) {
  let best = null, bestD = tolerance;
  for (const v of vertices) {
    const d = dist(p, v);
    if (d <= bestD) { best = v; bestD = d; }
  }
  if (best) return { point: [best[0], best[1]], kind: 'vertex' };
  if (anchor) {
    const dirs = [];
    if (before && dist(before, anchor) > 1e-9) {
      const ux = (anchor[0] - before[0]) / dist(before, anchor), uy = (anchor[1] - before[1]) / dist(before, anchor);
      dirs.push({ d: [-uy, ux], kind: 'right-angle' }, { d: [ux, uy], kind: 'right-angle' });
    }
    dirs.push({ d: [1, 0], kind: 'axis' }, { d: [0, 1], kind: 'axis' });
    for (const { d, kind } of dirs) {
      const t = (p[0] - anchor[0]) * d[0] + (p[1] - anchor[1]) * d[1];
      const q = [anchor[0] + t * d[0], anchor[1] + t * d[1]];
      if (dist(p, q) <= tolerance && Math.abs(t) > 1e-9) {
        const along = grid > 0 ? roundTo(t, grid) : t;
        const r = [anchor[0] + along * d[0], anchor[1] + along * d[1]];
        const exact = (v) => Number(v.toFixed(6));
        return { point: [exact(r[0]), exact(r[1])], kind };
      }
    }
  }
  if (grid > 0) return { point: [roundTo(p[0], grid), roundTo(p[1], grid)], kind: 'grid' };
  return { point: [p[0], p[1]], kind: 'none' };
}

/** Smallest box around every point: {x0, y0, x1, y1}, or null without points. */
export function bounds(points) {
  if (!points.length) return null;
  const b = { x0: Infinity, y0: Infinity, x1: -Infinity, y1: -Infinity };
  for (const [x, y] of points) {
    b.x0 = Math.min(b.x0, x); b.y0 = Math.min(b.y0, y); b.x1 = Math.max(b.x1, x); b.y1 = Math.max(b.y1, y);
  }
  return b;
}
