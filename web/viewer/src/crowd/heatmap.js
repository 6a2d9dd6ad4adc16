// Density and speed heatmap overlays (keys M and G). Density: PedPy's classic density on a grid, from the crowd frames the page
// receives. DensityGrid (pure) counts, per square cell of kHeatCell metres over the world's bounds,
// the agents whose position lies in it in each frame, keeps the frames of the last kHeatSeconds of
// simulated time (starting afresh when time runs backwards: a replay seeked back), and gives per
// cell the mean over those frames of N_cell / cell² [persons/m²] — the classic density of each
// cell, averaged over the window (docs/viewer.md; the same definition as `throng plot`'s density
// heatmap, docs/plot.md, over a shorter time). Heatmap (three.js) draws it as a texture on a plane
// just above the ground floor, each cell coloured on colour_by.js's ramp (0 … kDensityMax), empty
// cells transparent. SpeedGrid (pure): per cell, the mean ground speed of the agents in it over the
// same window — each agent's speed between two successive frames (distance / time; a jump over
// kSpeedJump metres, or an agent new in the frame, gives no sample), counted in the cell where it
// is now; drawn on the same ramp over 0 … kSpeedMax, cells nobody crossed transparent (voronoi.js:
// the same map by Voronoi cells).
// Scene coordinates: (x, z, −y).
import * as THREE from 'three';
import { kDensityMax, kSpeedMax, rampColour } from './colour_by.js';

export const kHeatCell = 1.0;    // [m] cell size
export const kHeatSeconds = 5;   // [s] of simulated time averaged
export const kSpeedJump = 5;     // [m] a move longer than this between frames is a jump, not walking
const kMaxCells = 1 << 20;       // a huge world gets coarser cells rather than a huge texture

export class DensityGrid {
  /** bounds: {minX, minY, maxX, maxY} [m]. */
  constructor(bounds, cell = kHeatCell, seconds = kHeatSeconds) {
    const w = Math.max(bounds.maxX - bounds.minX, cell), h = Math.max(bounds.maxY - bounds.minY, cell);
    this.cell = Math.max(cell, Math.sqrt((w * h) / kMaxCells));
    this.minX = bounds.minX;
    this.minY = bounds.minY;
    this.nx = Math.max(1, Math.ceil(w / this.cell));
    this.ny = Math.max(1, Math.ceil(h / this.cell));
    this.definition = 'classic';  // the density's definition (voronoi.js: 'voronoi')
    this.seconds = seconds;
    this.frames = [];  // [{t, counts: Uint16Array}], oldest first
    this.sum = new Float64Array(this.nx * this.ny);
  }

  clear() { this.frames = []; this.sum.fill(0); }

  /** One crowd frame at simulated time t [s]: the first `count` positions of x, y [m]. */
  record(x, y, count, t) {
    const last = this.frames[this.frames.length - 1];
    if (last && t < last.t) this.clear();
    else if (last && t === last.t) return;  // the same frame again
    const counts = this.frameCounts(x, y, count);
    this.frames.push({ t, counts });
    for (let k = 0; k < counts.length; ++k) this.sum[k] += counts[k];
    while (this.frames.length > 1 && this.frames[0].t < t - this.seconds) {
      const old = this.frames.shift().counts;
      for (let k = 0; k < old.length; ++k) this.sum[k] -= old[k];
    }
  }

  /** One frame's persons per cell: here (classic) each agent counts once in the cell where it is
   * (voronoi.js: shared by Voronoi area). */
  frameCounts(x, y, count) {
    const counts = new Uint16Array(this.nx * this.ny);
    for (let i = 0; i < count; ++i) {
      const ci = Math.floor((x[i] - this.minX) / this.cell), cj = Math.floor((y[i] - this.minY) / this.cell);
      if (ci >= 0 && ci < this.nx && cj >= 0 && cj < this.ny) counts[cj * this.nx + ci] += 1;
    }
    return counts;
  }

  /** Classic density of cell (i, j) [persons/m²]: its count averaged over the window's frames / cell². */
  density(i, j) {
    if (!this.frames.length) return 0;
    return this.sum[j * this.nx + i] / (this.frames.length * this.cell * this.cell);
  }

  /** The density at world point (x, y) [persons/m²] (0 outside the grid). */
  densityAt(x, y) {
    const i = Math.floor((x - this.minX) / this.cell), j = Math.floor((y - this.minY) / this.cell);
    return i >= 0 && i < this.nx && j >= 0 && j < this.ny ? this.density(i, j) : 0;
  }

  recordFrame(f, t) { this.record(f.x, f.y, f.count, t); }
  /** What the overlay draws in cell (i, j), or null (transparent). */
  value(i, j) { const d = this.density(i, j); return d > 0 ? d : null; }
}

export class SpeedGrid extends DensityGrid {
  constructor(bounds, cell = kHeatCell, seconds = kHeatSeconds) {
    super(bounds, cell, seconds);
    this.speedSum = new Float64Array(this.nx * this.ny);
    this.last = new Map();  // id → [x, y, t] in the previous frame
  }

  clear() { super.clear(); if (this.speedSum) this.speedSum.fill(0); if (this.last) this.last.clear(); }

  /** One crowd frame at simulated time t [s]: ids, x, y [m] of its first `count` agents. */
  recordSpeeds(ids, x, y, count, t) {
    const lastFrame = this.frames[this.frames.length - 1];
    if (lastFrame && t < lastFrame.t) this.clear();
    else if (lastFrame && t === lastFrame.t) return;
    const v = new Float32Array(count).fill(NaN);  // each agent's speed since the last frame, NaN: none
    const now = new Map();
    for (let i = 0; i < count; ++i) {
      now.set(ids[i], [x[i], y[i], t]);
      const p = this.last.get(ids[i]);
      if (!p || t <= p[2]) continue;
      const d = Math.hypot(x[i] - p[0], y[i] - p[1]);
      if (d <= kSpeedJump) v[i] = d / (t - p[2]);
    }
    this.last = now;
    const { counts, sums } = this.frameSums(x, y, v, count);
    this.frames.push({ t, counts, sums });
    for (let k = 0; k < counts.length; ++k) { this.sum[k] += counts[k]; this.speedSum[k] += sums[k]; }
    while (this.frames.length > 1 && this.frames[0].t < t - this.seconds) {
      const old = this.frames.shift();
      for (let k = 0; k < old.counts.length; ++k) { this.sum[k] -= old.counts[k]; this.speedSum[k] -= old.sums[k]; }
    }
  }

  /** One frame's weights and weighted speeds per cell: here (classic) each agent with a speed
   * sample counts once, with its speed, in the cell where it is (voronoi.js: by Voronoi area). */
  frameSums(x, y, v, count) {
    const counts = new Uint16Array(this.nx * this.ny), sums = new Float32Array(this.nx * this.ny);
    for (let i = 0; i < count; ++i) {
      if (Number.isNaN(v[i])) continue;
      const ci = Math.floor((x[i] - this.minX) / this.cell), cj = Math.floor((y[i] - this.minY) / this.cell);
      if (ci < 0 || ci >= this.nx || cj < 0 || cj >= this.ny) continue;
      counts[cj * this.nx + ci] += 1;
      sums[cj * this.nx + ci] += v[i];
    }
    return { counts, sums };
  }

  /** Mean speed [m/s] of the samples in cell (i, j) over the window, or null when it has none. */
  speed(i, j) {
    const k = j * this.nx + i;
    return this.sum[k] > 0 ? this.speedSum[k] / this.sum[k] : null;
  }

  /** The mean speed at world point (x, y) [m/s], or null (no samples, or outside the grid). */
  speedAt(x, y) {
    const i = Math.floor((x - this.minX) / this.cell), j = Math.floor((y - this.minY) / this.cell);
    return i >= 0 && i < this.nx && j >= 0 && j < this.ny ? this.speed(i, j) : null;
  }

  recordFrame(f, t) { this.recordSpeeds(f.ids, f.x, f.y, f.count, t); }
  value(i, j) { return this.speed(i, j); }
}

const kKinds = {
  density: { Grid: DensityGrid, max: kDensityMax, lift: 0.04 },
  speed: { Grid: SpeedGrid, max: kSpeedMax, lift: 0.05 },
};

export class Heatmap {
  /** bounds: worldBounds (minZ: the plane's height); kind: 'density' or 'speed'; grid: another
   * grid of the same bounds and cell to draw (the Voronoi density, voronoi.js), else the kind's. */
  constructor(scene, bounds, kind = 'density', grid = null) {
    const k = kKinds[kind];
    this.kind = kind;
    this.max = k.max;
    this.grid = grid || new k.Grid(bounds);
    const g = this.grid;
    this.data = new Uint8Array(g.nx * g.ny * 4);
    this.texture = new THREE.DataTexture(this.data, g.nx, g.ny, THREE.RGBAFormat);
    this.texture.magFilter = THREE.NearestFilter;
    this.texture.minFilter = THREE.NearestFilter;
    const w = g.nx * g.cell, h = g.ny * g.cell;
    const plane = new THREE.PlaneGeometry(w, h);
    plane.rotateX(-Math.PI / 2);  // (u, v) = (0, 0) at world (minX, minY)
    plane.translate(g.minX + w / 2, (bounds.minZ || 0) + k.lift, -(g.minY + h / 2));
    this.mesh = new THREE.Mesh(plane, new THREE.MeshBasicMaterial({ map: this.texture, transparent: true, depthWrite: false }));
    this.mesh.name = `${kind}-heatmap`;
    this.mesh.renderOrder = 2;
    this.mesh.visible = false;
    scene.add(this.mesh);
    this.stale = false;
  }

  get enabled() { return this.mesh.visible; }
  set enabled(on) {
    this.mesh.visible = on;
    if (!on) this.grid.clear();
  }

  /** Draws `grid` from now on (same bounds and cell: the classic ↔ Voronoi switch); starts afresh. */
  setGrid(grid) {
    if (grid.nx !== this.grid.nx || grid.ny !== this.grid.ny) throw new Error('heatmap: a grid of another size');
    this.grid = grid;
    grid.clear();
    this.stale = true;
  }

  /** A crowd frame at simulated time t [s] (counted only while shown). */
  record(frame, t) {
    if (!this.enabled) return;
    this.grid.recordFrame(frame, t);
    this.stale = true;
  }

  /** Refills the texture from the grid (once per drawn frame after new crowd frames). */
  update() {
    if (!this.stale) return;
    this.stale = false;
    const g = this.grid, d = this.data;
    for (let j = 0; j < g.ny; ++j) {
      for (let i = 0; i < g.nx; ++i) {
        const v = g.value(i, j), o = (j * g.nx + i) * 4, f = v === null ? 0 : Math.min(v / this.max, 1);
        const c = rampColour(f);
        d[o] = (c >> 16) & 255; d[o + 1] = (c >> 8) & 255; d[o + 2] = c & 255;
        d[o + 3] = v === null ? 0 : Math.round(90 + 110 * f);
      }
    }
    this.texture.needsUpdate = true;
  }
}
