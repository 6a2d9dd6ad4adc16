// Voronoi density on a grid (the density map's Voronoi definition, docs/viewer.md) — pure, no
// three.js. PedPy's Voronoi density of a measurement area M is ρ_V = Σ_i |V_i ∩ M| / |V_i| / |M|,
// V_i the Voronoi cell of pedestrian i — the part of the walkable area nearer to i than to anyone
// else — cut to the circle of radius kVoronoiCutoff around i (PedPy's `Cutoff`: without it a lone
// walker's cell is the whole hall). Here M is each grid cell, and the cells V_i are rasterised:
// the walkable area is sampled every cell / kVoronoiSamples metres (sample centres inside a walkable
// polygon and outside every obstacle and wall), each sample belongs to the nearest agent within the
// cut-off (found through a hash grid of cut-off-sized buckets), |V_i| is its samples' count and
// |V_i ∩ M| the count of those in M, so each frame gives per cell Σ_i n_i,M / n_i persons.
// VoronoiDensityGrid averages these over the last seconds exactly as DensityGrid averages counts.
// The speed map's Voronoi definition (VoronoiSpeedGrid) is Steffen & Seyfried's (2010; PedPy's
// Voronoi speed): the speed field v(x) = v_i on V_i, averaged over the cell — Σ_i v_i |V_i ∩ M|
// over Σ_i |V_i ∩ M|, i.e. over the part of the cell someone's (cut) Voronoi cell covers. PedPy
// divides by |M| instead, which reads a cell half beyond everyone's cut-off as half the speed;
// where the cells cover M the two agree. v_i is the agent's speed since the previous frame
// (SpeedGrid); an agent without one (new in the frame, or a jump) still owns its Voronoi cell
// but that area counts for neither sum.
import { DensityGrid, SpeedGrid, kHeatCell, kHeatSeconds } from './heatmap.js';
import { insidePolygon, wallRectangles } from '../world/walls.js';

export const kVoronoiCutoff = 2.0;  // [m] radius a Voronoi cell is cut to
export const kVoronoiSamples = 4;   // samples per cell side (0.25 m at 1 m cells)

/** Sample points of the walkable area: {x, y: Float32Array, cell: Int32Array (grid cell index)}. */
export function walkableSamples(grid, scenario, perSide = kVoronoiSamples) {
  const walkable = (scenario.walkable || []).filter((p) => Array.isArray(p) && p.length >= 3);
  const solid = [...(scenario.obstacles || []), ...(scenario.walls || []).flatMap(wallRectangles)]
    .filter((p) => Array.isArray(p) && p.length >= 3);
  const xs = [], ys = [], cells = [];
  const step = grid.cell / perSide;
  for (let j = 0; j < grid.ny; ++j) {
    for (let i = 0; i < grid.nx; ++i) {
      for (let b = 0; b < perSide; ++b) {
        for (let a = 0; a < perSide; ++a) {
          const x = grid.minX + i * grid.cell + (a + 0.5) * step, y = grid.minY + j * grid.cell + (b + 0.5) * step;
          // A world without walkable polygons (a terrain): every sample counts.
          if (walkable.length && !walkable.some((p) => insidePolygon(x, y, p))) continue;
          if (solid.some((p) => insidePolygon(x, y, p))) continue;
          xs.push(x); ys.push(y); cells.push(j * grid.nx + i);
        }
      }
    }
  }
  return { x: Float32Array.from(xs), y: Float32Array.from(ys), cell: Int32Array.from(cells) };
}

/**
 * Which agent owns each sample (walkableSamples): the nearest within `cutoff` (ties: the lower
 * row), -1 for none; {owner: Int32Array per sample, owned: Int32Array per agent (its samples)}.
 */
export function voronoiOwners(samples, x, y, count, cutoff) {
  const n = samples.x.length;
  const owner = new Int32Array(n).fill(-1);
  const owned = new Int32Array(count);
  if (count === 0) return { owner, owned };
  const buckets = new Map();
  const key = (bx, by) => bx * 73856093 ^ by * 19349663;
  for (let i = 0; i < count; ++i) {
    const k = key(Math.floor(x[i] / cutoff), Math.floor(y[i] / cutoff));
    let list = buckets.get(k);
    if (!list) { list = []; buckets.set(k, list); }
    list.push(i);
  }
  const r2 = cutoff * cutoff;
  for (let s = 0; s < n; ++s) {
    const sx = samples.x[s], sy = samples.y[s];
    const bx = Math.floor(sx / cutoff), by = Math.floor(sy / cutoff);
    let best = -1, bestD = r2;
    for (let dy = -1; dy <= 1; ++dy) {
      for (let dx = -1; dx <= 1; ++dx) {
        const list = buckets.get(key(bx + dx, by + dy));
        if (!list) continue;
        for (const i of list) {
          const d = (x[i] - sx) ** 2 + (y[i] - sy) ** 2;
          if (d < bestD || (d === bestD && best >= 0 && i < best)) { bestD = d; best = i; }
        }
      }
    }
    if (best >= 0 && bestD <= r2) { owner[s] = best; owned[best]++; }
  }
  return { owner, owned };
}

/**
 * Persons per grid cell by Voronoi shares for one frame: out[cell] = Σ_i n_i,cell / n_i, the
 * samples (walkableSamples) owned by agent i — nearest within `cutoff` — in the cell over all of
 * agent i's samples. An agent owning no sample (off the sampled area) adds nothing.
 */
export function voronoiShares(samples, x, y, count, cutoff, cells, out = new Float32Array(cells)) {
  out.fill(0);
  const { owner, owned } = voronoiOwners(samples, x, y, count, cutoff);
  for (let s = 0; s < owner.length; ++s) if (owner[s] >= 0) out[samples.cell[s]] += 1 / owned[owner[s]];
  return out;
}

/** The density map's Voronoi variant: DensityGrid's window and averaging, Voronoi shares per frame. */
export class VoronoiDensityGrid extends DensityGrid {
  /** scenario: the world description's scenario (walkable, obstacles, walls). */
  constructor(bounds, scenario = {}, cell = kHeatCell, seconds = kHeatSeconds, cutoff = kVoronoiCutoff) {
    super(bounds, cell, seconds);
    this.definition = 'voronoi';
    this.cutoff = cutoff;
    this.samples = walkableSamples(this, scenario);
  }

  /** One frame's persons per cell by Voronoi shares (DensityGrid.record keeps the window). */
  frameCounts(x, y, count) { return voronoiShares(this.samples, x, y, count, this.cutoff, this.nx * this.ny); }
}

/** The speed map's Voronoi variant: SpeedGrid's speeds and window, weighted by Voronoi area. */
export class VoronoiSpeedGrid extends SpeedGrid {
  constructor(bounds, scenario = {}, cell = kHeatCell, seconds = kHeatSeconds, cutoff = kVoronoiCutoff) {
    super(bounds, cell, seconds);
    this.definition = 'voronoi';
    this.cutoff = cutoff;
    this.samples = walkableSamples(this, scenario);
  }

  /** Per cell: samples covered by agents with a speed, and the sum of those agents' speeds over them. */
  frameSums(x, y, v, count) {
    const counts = new Uint16Array(this.nx * this.ny), sums = new Float32Array(this.nx * this.ny);
    const { owner } = voronoiOwners(this.samples, x, y, count, this.cutoff);
    for (let s = 0; s < owner.length; ++s) {
      const o = owner[s];
      if (o < 0 || Number.isNaN(v[o])) continue;
      counts[this.samples.cell[s]] += 1;
      sums[this.samples.cell[s]] += v[o];
    }
    return { counts, sums };
  }
}
