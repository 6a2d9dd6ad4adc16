// Multi-level terrain (pure, no DOM, no three.js): the scenario's `terrain` — {vertices: [[x, y, z]],
// walkable: [[i, j, k]], obstacles: [[i, j, k]]}, world metres, z up (docs/scenario-format.md) —
// read for the viewer: its bounds, the height of the walkable surface under a ground point (a
// vertical ray against each walkable triangle's xy projection, barycentric interpolation of z,
// the hit nearest a given height; triangles bucketed in a uniform xy grid), and one step of the
// local avatar over it (climbs or descends at most kMaxStep per move, never leaves the surface).

/** Height [m] above the current one at which the avatar looks for the floor under it. */
export const kClimb = 0.5;
/** Largest height change [m] of one avatar move (a stair step; a balcony's edge is refused). */
export const kMaxStep = 0.6;

const kEps = 1e-9;
const kMaxCells = 65536;  // grid cells at most (256 × 256)
const indexCache = new WeakMap();  // terrain object → its index

/** Bounds of the terrain's vertices: {minX, minY, maxX, maxY, minZ, maxZ} [m], or null when empty. */
export function terrainBounds(terrain) {
  const v = terrain && terrain.vertices;
  if (!Array.isArray(v) || v.length === 0) return null;
  const b = { minX: Infinity, minY: Infinity, maxX: -Infinity, maxY: -Infinity, minZ: Infinity, maxZ: -Infinity };
  for (const p of v) {
    const x = p[0], y = p[1], z = p[2] ?? 0;
    if (!Number.isFinite(x) || !Number.isFinite(y) || !Number.isFinite(z)) continue;
    if (x < b.minX) b.minX = x; if (x > b.maxX) b.maxX = x;
    if (y < b.minY) b.minY = y; if (y > b.maxY) b.maxY = y;
    if (z < b.minZ) b.minZ = z; if (z > b.maxZ) b.maxZ = z;
  }
  return Number.isFinite(b.minX) ? b : null;
}

/**
 * The walkable triangles of `terrain` in a uniform xy grid: {tris: Float64Array (9 per triangle:
 * x0 y0 z0 x1 y1 z1 x2 y2 z2), minX, minY, cell [m], nx, ny, cells: Array of triangle-index
 * arrays}. Triangles whose xy projection has no area (vertical ones) or with bad indices are left out.
 */
export function buildTerrainIndex(terrain) {
  const verts = (terrain && terrain.vertices) || [];
  const faces = (terrain && terrain.walkable) || [];
  const tris = [];
  let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
  for (const f of faces) {
    if (!Array.isArray(f) || f.length < 3) continue;
    const a = verts[f[0]], b = verts[f[1]], c = verts[f[2]];
    if (!a || !b || !c) continue;
    const area2 = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if (!(Math.abs(area2) > kEps)) continue;
    tris.push(a[0], a[1], a[2] ?? 0, b[0], b[1], b[2] ?? 0, c[0], c[1], c[2] ?? 0);
    minX = Math.min(minX, a[0], b[0], c[0]); maxX = Math.max(maxX, a[0], b[0], c[0]);
    minY = Math.min(minY, a[1], b[1], c[1]); maxY = Math.max(maxY, a[1], b[1], c[1]);
  }
  const n = tris.length / 9;
  if (n === 0) return { tris: new Float64Array(0), minX: 0, minY: 0, cell: 1, nx: 0, ny: 0, cells: [] };
  // About one cell per triangle, square cells, at most kMaxCells of them.
  const w = Math.max(maxX - minX, 1e-6), h = Math.max(maxY - minY, 1e-6);
  const cells = Math.min(kMaxCells, Math.max(1, n));
  const cell = Math.max(Math.sqrt((w * h) / cells), Math.max(w, h) / 256, 1e-3);
  const nx = Math.max(1, Math.ceil(w / cell)), ny = Math.max(1, Math.ceil(h / cell));
  const grid = Array.from({ length: nx * ny }, () => []);
  const t = Float64Array.from(tris);
  for (let k = 0; k < n; ++k) {
    const o = k * 9;
    const x0 = Math.min(t[o], t[o + 3], t[o + 6]), x1 = Math.max(t[o], t[o + 3], t[o + 6]);
    const y0 = Math.min(t[o + 1], t[o + 4], t[o + 7]), y1 = Math.max(t[o + 1], t[o + 4], t[o + 7]);
    const i0 = clampCell((x0 - minX) / cell, nx), i1 = clampCell((x1 - minX) / cell, nx);
    const j0 = clampCell((y0 - minY) / cell, ny), j1 = clampCell((y1 - minY) / cell, ny);
    for (let j = j0; j <= j1; ++j) for (let i = i0; i <= i1; ++i) grid[j * nx + i].push(k);
  }
  return { tris: t, minX, minY, cell, nx, ny, cells: grid };
}

function clampCell(v, n) {
  return Math.min(n - 1, Math.max(0, Math.floor(v)));
}

function indexOf(terrain) {
  let idx = indexCache.get(terrain);
  if (!idx) { idx = buildTerrainIndex(terrain); indexCache.set(terrain, idx); }
  return idx;
}

/**
 * Height [m] of the walkable surface under ground point (x, y) [m]: of the walkable triangles
 * whose xy projection holds the point (edges included), the interpolated height nearest `nearZ`
 * [m] (ties: the lower); null when no triangle is under the point. The index is built on the
 * first call for a terrain object and kept (the terrain must not change afterwards).
 */
export function terrainHeightAt(terrain, x, y, nearZ = 0) {
  if (!terrain || !Number.isFinite(x) || !Number.isFinite(y)) return null;
  const idx = indexOf(terrain);
  if (idx.nx === 0) return null;
  const fi = (x - idx.minX) / idx.cell, fj = (y - idx.minY) / idx.cell;
  // A point on the grid's outer edge still belongs to the last cell.
  if (fi < -1e-9 || fj < -1e-9 || fi > idx.nx + 1e-9 || fj > idx.ny + 1e-9) return null;
  const list = idx.cells[clampCell(fj, idx.ny) * idx.nx + clampCell(fi, idx.nx)];
  const t = idx.tris;
  let best = null, bestD = Infinity;
  for (const k of list) {
    const o = k * 9;
    const ax = t[o], ay = t[o + 1], bx = t[o + 3], by = t[o + 4], cx = t[o + 6], cy = t[o + 7];
    const d = (by - cy) * (ax - cx) + (cx - bx) * (ay - cy);
    const u = ((by - cy) * (x - cx) + (cx - bx) * (y - cy)) / d;
    const v = ((cy - ay) * (x - cx) + (ax - cx) * (y - cy)) / d;
    const w = 1 - u - v;
    const e = 1e-7;
    if (u < -e || v < -e || w < -e) continue;
    const z = u * t[o + 2] + v * t[o + 5] + w * t[o + 8];
    const dz = Math.abs(z - nearZ);
    if (dz < bestD - 1e-9 || (Math.abs(dz - bestD) <= 1e-9 && z < best)) { best = z; bestD = dz; }
  }
  return best;
}

/**
 * One move of an avatar standing at (x, y, z) [m] towards ground point (nx, ny) over `terrain`:
 * its new {x, y, z, onTerrain}, or null when the move is refused. The new height is
 * terrainHeightAt(terrain, nx, ny, z + kClimb), so it follows floors, ramps and stairs and does
 * not jump to a floor above. On the surface (`onTerrain`), a move off it, or one changing the
 * height by more than kMaxStep (an edge above a lower floor), is refused; off it (placed outside
 * the walkable triangles), it moves freely at its height until it steps onto them.
 */
export function stepOnTerrain(terrain, x, y, z, nx, ny, onTerrain = true) {
  const h = terrainHeightAt(terrain, nx, ny, z + kClimb);
  if (h === null) return onTerrain ? null : { x: nx, y: ny, z, onTerrain: false };
  if (onTerrain && Math.abs(h - z) > kMaxStep) return null;
  return { x: nx, y: ny, z: h, onTerrain: true };
}

/**
 * The walkable point nearest ground point (x, y) [m] at about height `nearZ`: (x, y) itself when
 * a floor is under it, else the first found on rings 0.5 m apart (24 directions each, east first,
 * counter-clockwise) out to `reach` [m]; {x, y, z} or null. Where a person is placed when the
 * view's centre is over no floor (a stairwell, outside the building).
 */
export function nearestOnTerrain(terrain, x, y, nearZ = 0, reach = 15) {
  const z0 = terrainHeightAt(terrain, x, y, nearZ);
  if (z0 !== null) return { x, y, z: z0 };
  for (let r = 0.5; r <= reach + 1e-9; r += 0.5) {
    for (let k = 0; k < 24; ++k) {
      const a = (k * Math.PI) / 12;
      const px = x + r * Math.cos(a), py = y + r * Math.sin(a);
      const z = terrainHeightAt(terrain, px, py, nearZ);
      if (z !== null) return { x: px, y: py, z };
    }
  }
  return null;
}
