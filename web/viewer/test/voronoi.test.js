// The density map's Voronoi definition (src/crowd/voronoi.js): PedPy's Σ_i |V_i ∩ M| / |V_i| / |M|
// with rasterised Voronoi cells cut to a circle — hand-computed rooms, obstacles left out, the
// cut-off, a lattice's known density, the shares against a brute-force nearest-agent count; the
// speed map's Voronoi definition (Σ_i v_i |V_i ∩ M| / Σ_i |V_i ∩ M|) on hand-computed cells.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { VoronoiDensityGrid, VoronoiSpeedGrid, voronoiShares, walkableSamples } from '../src/crowd/voronoi.js';
import { SpeedGrid } from '../src/crowd/heatmap.js';

const room = (w, h) => ({ walkable: [[[0, 0], [w, 0], [w, h], [0, h]]] });
const bounds = (w, h) => ({ minX: 0, minY: 0, maxX: w, maxY: h });

test('two agents in a 4 m × 2 m room: each owns half, a quarter person per 1 m cell', () => {
  const g = new VoronoiDensityGrid(bounds(4, 2), room(4, 2), 1, 5, 10);
  g.record(Float32Array.from([1, 3]), Float32Array.from([1, 1]), 2, 0);
  for (let j = 0; j < 2; ++j) for (let i = 0; i < 4; ++i) assert.ok(Math.abs(g.density(i, j) - 0.25) < 1e-6, `cell ${i},${j}: ${g.density(i, j)}`);
});

test('an agent alone owns its cut-off circle: shares sum to one, inside the circle only', () => {
  const g = new VoronoiDensityGrid(bounds(20, 20), room(20, 20), 1, 5, 2);
  g.record(Float32Array.from([10]), Float32Array.from([10]), 1, 0);
  let persons = 0;
  for (let j = 0; j < 20; ++j) for (let i = 0; i < 20; ++i) persons += g.density(i, j);
  assert.ok(Math.abs(persons - 1) < 1e-6);
  assert.equal(g.density(0, 0), 0);
  assert.equal(g.density(13, 10), 0, 'beyond the 2 m cut-off');
  // The circle's area is π·2² ≈ 12.6 m²: a cell wholly inside holds about 1/12.6 person.
  assert.ok(Math.abs(g.density(10, 10) - 1 / (Math.PI * 4)) < 0.01, String(g.density(10, 10)));
});

test('obstacles and walls are not walkable: no sample there, the neighbours share the rest', () => {
  const scenario = { ...room(4, 2), obstacles: [[[2, 0], [4, 0], [4, 2], [2, 2]]] };
  const g = new VoronoiDensityGrid(bounds(4, 2), scenario, 1, 5, 10);
  assert.equal(g.samples.x.length, 2 * 2 * 16);
  g.record(Float32Array.from([1]), Float32Array.from([1]), 1, 0);
  assert.equal(g.density(2, 0), 0);
  assert.ok(Math.abs(g.density(0, 0) - 0.25) < 1e-6);
});

test('a square lattice 0.5 m apart reads 4 persons/m² inside it', () => {
  const xs = [], ys = [];
  for (let a = 0; a < 20; ++a) for (let b = 0; b < 20; ++b) { xs.push(0.25 + a * 0.5); ys.push(0.25 + b * 0.5); }
  const g = new VoronoiDensityGrid(bounds(10, 10), room(10, 10), 1, 5, 2);
  g.record(Float32Array.from(xs), Float32Array.from(ys), xs.length, 0);
  for (const [i, j] of [[2, 2], [5, 5], [7, 3]]) assert.ok(Math.abs(g.density(i, j) - 4) < 1e-6, String(g.density(i, j)));
});

test('shares equal a brute-force nearest-agent count, and average over the window', () => {
  const g = new VoronoiDensityGrid(bounds(6, 5), room(6, 5), 1, 5, 1.5);
  let seed = 7;
  const rnd = () => { seed = (seed * 16807) % 2147483647; return seed / 2147483647; };
  const x = Float32Array.from({ length: 25 }, () => rnd() * 6), y = Float32Array.from({ length: 25 }, () => rnd() * 5);
  const shares = voronoiShares(g.samples, x, y, 25, 1.5, g.nx * g.ny);
  const owner = [], owned = new Array(25).fill(0);
  for (let s = 0; s < g.samples.x.length; ++s) {
    let best = -1, bestD = 1.5 * 1.5;
    for (let i = 0; i < 25; ++i) {
      const d = (x[i] - g.samples.x[s]) ** 2 + (y[i] - g.samples.y[s]) ** 2;
      if (d < bestD) { bestD = d; best = i; }
    }
    owner.push(best);
    if (best >= 0) owned[best]++;
  }
  const expected = new Float64Array(g.nx * g.ny);
  owner.forEach((o, s) => { if (o >= 0) expected[g.samples.cell[s]] += 1 / owned[o]; });
  for (let k = 0; k < expected.length; ++k) assert.ok(Math.abs(shares[k] - expected[k]) < 1e-5, `cell ${k}`);
  // Two frames: the mean of their densities; time going back starts afresh.
  g.record(x, y, 25, 0);
  g.record(Float32Array.from([3]), Float32Array.from([2.5]), 1, 1);
  const alone = voronoiShares(g.samples, Float32Array.from([3]), Float32Array.from([2.5]), 1, 1.5, g.nx * g.ny);
  assert.ok(Math.abs(g.density(3, 2) - (expected[2 * 6 + 3] + alone[2 * 6 + 3]) / 2) < 1e-5);
  g.record(x, y, 25, 0.5);
  assert.equal(g.frames.length, 1);
});

test('a world without walkable polygons (a terrain) samples its whole bounds', () => {
  const g = new VoronoiDensityGrid(bounds(2, 2), {}, 1, 5, 2);
  assert.equal(walkableSamples(g, {}).x.length, 4 * 16);
});

test('Voronoi speed: each agent\'s speed fills its Voronoi cell, also the grid cells nobody stands in', () => {
  // 4 m × 2 m room, one agent in each half, at (0.5, 1.2) and (3.5, 1.2) in the second frame, having
  // walked 1 and 2 m in the second before: the Voronoi boundary is x = 2 in that frame.
  const walk = new VoronoiSpeedGrid(bounds(4, 2), room(4, 2), 1, 5, 10);
  walk.recordSpeeds(Int32Array.from([1, 2]), Float32Array.from([0.5, 3.5]), Float32Array.from([0.2, -0.8]), 2, 0);
  walk.recordSpeeds(Int32Array.from([1, 2]), Float32Array.from([0.5, 3.5]), Float32Array.from([1.2, 1.2]), 2, 1);
  assert.equal(walk.definition, 'voronoi');
  for (let j = 0; j < 2; ++j) {
    for (const i of [0, 1]) assert.ok(Math.abs(walk.speed(i, j) - 1) < 1e-6, `cell ${i},${j}: ${walk.speed(i, j)}`);
    for (const i of [2, 3]) assert.ok(Math.abs(walk.speed(i, j) - 2) < 1e-6, `cell ${i},${j}: ${walk.speed(i, j)}`);
  }
  // Standing agents: 0 m/s everywhere (a speed, not "no sample").
  const g = new VoronoiSpeedGrid(bounds(4, 2), room(4, 2), 1, 5, 10);
  for (const t of [0, 1]) g.recordSpeeds(Int32Array.from([1, 2]), Float32Array.from([0.5, 3.5]), Float32Array.from([1, 1]), 2, t);
  for (let j = 0; j < 2; ++j) for (let i = 0; i < 4; ++i) assert.equal(g.speed(i, j), 0);
  // The classic map has speeds only where the agents stand.
  const classic = new SpeedGrid(bounds(4, 2), 1, 5);
  classic.recordSpeeds(Int32Array.from([1, 2]), Float32Array.from([0.5, 3.5]), Float32Array.from([0.2, -0.8]), 2, 0);
  classic.recordSpeeds(Int32Array.from([1, 2]), Float32Array.from([0.5, 3.5]), Float32Array.from([1.2, 1.2]), 2, 1);
  assert.equal(classic.speed(1, 0), null);
  assert.ok(Math.abs(classic.speed(0, 1) - 1) < 1e-6);
});

test('Voronoi speed: a cell shared by two cells is their area-weighted mean', () => {
  // 2 m × 1 m, 1 m cells, 4 × 4 samples each (columns at x 0.125 … 0.875): agents at x 0.25 and
  // 1.25 split at x 0.75 in the second frame, so cell 0 is three quarters the first's (1 m/s) and a
  // quarter the second's (3 m/s); the first frame has no speeds and counts for nothing.
  const g = new VoronoiSpeedGrid(bounds(2, 1), room(2, 1), 1, 5, 10);
  g.recordSpeeds(Int32Array.from([1, 2]), Float32Array.from([0.25, 1.25]), Float32Array.from([0, -1]), 2, 0);
  g.recordSpeeds(Int32Array.from([1, 2]), Float32Array.from([0.25, 1.25]), Float32Array.from([0.5, 0.5]), 2, 0.5);
  assert.ok(Math.abs(g.speed(0, 0) - 1.5) < 1e-6, String(g.speed(0, 0)));
  assert.ok(Math.abs(g.speed(1, 0) - 3) < 1e-6, String(g.speed(1, 0)));
  // A third frame, both standing: the window's mean, by area, halves cell 0's.
  g.recordSpeeds(Int32Array.from([1, 2]), Float32Array.from([0.25, 1.25]), Float32Array.from([0.5, 0.5]), 2, 1);
  assert.ok(Math.abs(g.speed(0, 0) - 0.75) < 1e-6, String(g.speed(0, 0)));
});

test('Voronoi speed: an agent new in the frame owns its cell but gives no speed there; the cut-off leaves cells empty', () => {
  const g = new VoronoiSpeedGrid(bounds(4, 2), room(4, 2), 1, 5, 10);
  g.recordSpeeds(Int32Array.from([1]), Float32Array.from([0.5]), Float32Array.from([0.5]), 1, 0);
  g.recordSpeeds(Int32Array.from([1, 2]), Float32Array.from([0.5, 3.5]), Float32Array.from([1.5, 0.5]), 2, 1);
  assert.ok(Math.abs(g.speed(0, 0) - 1) < 1e-6 && Math.abs(g.speed(1, 1) - 1) < 1e-6);
  assert.equal(g.speed(2, 0), null, 'agent 2 is new: its Voronoi cell has no speed');
  assert.equal(g.speed(3, 1), null);
  const far = new VoronoiSpeedGrid(bounds(20, 20), room(20, 20), 1, 5, 2);
  far.recordSpeeds(Int32Array.from([1]), Float32Array.from([10]), Float32Array.from([10]), 1, 0);
  far.recordSpeeds(Int32Array.from([1]), Float32Array.from([10]), Float32Array.from([11]), 1, 1);
  assert.ok(Math.abs(far.speed(10, 10) - 1) < 1e-6);
  assert.equal(far.speed(0, 0), null, 'beyond the cut-off');
});
