// Multi-level terrain (src/world/terrain.js) and world bounds (src/world/world_view.js): the floor
// height under a point on a two-floor model with a ramp, the avatar's steps over it, the grid
// index against an analytic slope, and worldBounds of terrain and flat scenarios.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { terrainHeightAt, terrainBounds, buildTerrainIndex, stepOnTerrain, kMaxStep, nearestOnTerrain } from '../src/world/terrain.js';
import { worldBounds, pointHeight } from '../src/world/world_view.js';

// Ground 0..20 × 0..10 at z 0; upper floor 10..20 × 0..10 at z 3 (above the ground's right half);
// a ramp 4..10 × 8..10 rising from z 0 at x 4 to z 3 at x 10, where it meets the upper floor;
// one obstacle triangle (a pillar face) that must not count as floor.
function twoFloors() {
  const vertices = [
    [0, 0, 0], [20, 0, 0], [20, 10, 0], [0, 10, 0],      // 0–3 ground
    [10, 0, 3], [20, 0, 3], [20, 10, 3], [10, 10, 3],    // 4–7 upper floor
    [4, 8, 0], [10, 8, 3], [10, 10, 3], [4, 10, 0],      // 8–11 ramp
    [2, 2, 0], [2, 2, 2.4], [3, 2, 0],                   // 12–14 obstacle
  ];
  return {
    vertices,
    walkable: [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7], [8, 9, 10], [8, 10, 11]],
    obstacles: [[12, 13, 14]],
  };
}

const near = (a, b, eps = 1e-9) => assert.ok(a !== null && Math.abs(a - b) <= eps, `${a} ≠ ${b}`);

test('terrainHeightAt picks the floor nearest the given height', () => {
  const t = twoFloors();
  near(terrainHeightAt(t, 15, 5, 0), 0);
  near(terrainHeightAt(t, 15, 5, 0.5), 0);      // standing on the ground: not the floor 3 m above
  near(terrainHeightAt(t, 15, 5, 3.5), 3);      // standing upstairs
  near(terrainHeightAt(t, 15, 5, 100), 3);
  near(terrainHeightAt(t, 15, 5, -5), 0);
  near(terrainHeightAt(t, 5, 5, 3.5), 0);       // only the ground under it
  near(terrainHeightAt(t, 15, 5, 1.5), 0);      // a tie: the lower
});

test('terrainHeightAt interpolates on the ramp', () => {
  const t = twoFloors();
  near(terrainHeightAt(t, 7, 9, 2), 1.5, 1e-9);
  near(terrainHeightAt(t, 5, 8.5, 1), 0.5, 1e-9);
  near(terrainHeightAt(t, 9.5, 9.9, 3), 2.75, 1e-9);
  near(terrainHeightAt(t, 7, 9, 0), 0);         // the ground under the ramp
  for (let x = 4; x <= 10; x += 0.25) near(terrainHeightAt(t, x, 9, (x - 4) / 2 + 0.5), (x - 4) / 2, 1e-9);
});

test('terrainHeightAt is null off the geometry, edges included', () => {
  const t = twoFloors();
  assert.equal(terrainHeightAt(t, 25, 5, 0), null);
  assert.equal(terrainHeightAt(t, -0.01, 5, 0), null);
  assert.equal(terrainHeightAt(t, 5, 10.5, 0), null);
  assert.equal(terrainHeightAt(t, 5, -1e-3, 0), null);
  assert.equal(terrainHeightAt(t, NaN, 5, 0), null);
  assert.equal(terrainHeightAt(null, 5, 5, 0), null);
  assert.equal(terrainHeightAt({ vertices: [], walkable: [] }, 5, 5, 0), null);
  near(terrainHeightAt(t, 0, 0, 0), 0);         // a corner
  near(terrainHeightAt(t, 20, 10, 5), 3);       // the far corner, upstairs
  near(terrainHeightAt(t, 20, 4, 0), 0);        // the right edge
});

test('the obstacle triangles are not floor', () => {
  const t = twoFloors();
  near(terrainHeightAt(t, 2.5, 2, 2), 0);
  assert.equal(terrainHeightAt({ vertices: t.vertices, walkable: t.obstacles }, 2.5, 2, 0), null);  // vertical: no area
});

test('the grid index agrees with an analytic slope on many triangles', () => {
  const n = 40, vertices = [], walkable = [];
  const z = (x, y) => 0.1 * x + 0.05 * y + 1;
  for (let j = 0; j <= n; ++j) for (let i = 0; i <= n; ++i) vertices.push([i * 0.5, j * 0.5, z(i * 0.5, j * 0.5)]);
  for (let j = 0; j < n; ++j) {
    for (let i = 0; i < n; ++i) {
      const a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      walkable.push([a, b, d], [a, d, c]);
    }
  }
  const t = { vertices, walkable };
  const idx = buildTerrainIndex(t);
  assert.ok(idx.nx * idx.ny > 100, 'a grid, not one bucket');
  let seed = 7;
  const rnd = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648);
  for (let k = 0; k < 500; ++k) {
    const x = rnd() * 20, y = rnd() * 20;
    near(terrainHeightAt(t, x, y, 0), z(x, y), 1e-9);
  }
  assert.equal(terrainHeightAt(t, 20.1, 3, 0), null);
});

test('the avatar walks up the ramp onto the upper floor and not off its edge', () => {
  const t = twoFloors();
  let a = { x: 2, y: 9, z: 0, onTerrain: true };
  for (let x = 2.1; x <= 14; x += 0.1) {
    const s = stepOnTerrain(t, a.x, a.y, a.z, x, 9, a.onTerrain);
    assert.ok(s, `refused at x ${x}`);
    assert.ok(Math.abs(s.z - a.z) <= kMaxStep);
    a = s;
  }
  near(a.z, 3);
  // Upstairs at y 5, walking towards x < 10: the upper floor ends, the ground is 3 m below.
  assert.equal(stepOnTerrain(t, 10.05, 5, 3, 9.95, 5, true), null);
  // On the ground, walking under the upper floor stays on the ground.
  near(stepOnTerrain(t, 9.95, 5, 0, 10.05, 5, true).z, 0);
  // Walking off the geometry is refused; an avatar placed off it moves freely until it is on.
  assert.equal(stepOnTerrain(t, 0.05, 5, 0, -0.05, 5, true), null);
  assert.deepEqual(stepOnTerrain(t, -1, 5, 0, -0.9, 5, false), { x: -0.9, y: 5, z: 0, onTerrain: false });
  assert.deepEqual(stepOnTerrain(t, -0.05, 5, 0, 0.05, 5, false), { x: 0.05, y: 5, z: 0, onTerrain: true });
});

test('a stair of 0.3 m steps is climbed, a 1 m step is not', () => {
  // Steps 1 m deep along x, each 0.3 m higher: [0,1]×[0,2] at 0, [1,2]×[0,2] at 0.3, …; then a 1 m wall-step.
  const vertices = [], walkable = [];
  const heights = [0, 0.3, 0.6, 0.9, 1.9];
  heights.forEach((h, i) => {
    const o = vertices.length;
    vertices.push([i, 0, h], [i + 1, 0, h], [i + 1, 2, h], [i, 2, h]);
    walkable.push([o, o + 1, o + 2], [o, o + 2, o + 3]);
  });
  const t = { vertices, walkable };
  let a = { x: 0.5, y: 1, z: 0, onTerrain: true };
  for (let x = 0.6; x < 3.95; x += 0.1) a = stepOnTerrain(t, a.x, a.y, a.z, x, 1, a.onTerrain) || a;
  near(a.z, 0.9);
  assert.equal(stepOnTerrain(t, 3.95, 1, 0.9, 4.05, 1, true), null);
});

test('terrainBounds and worldBounds include the terrain with its heights', () => {
  const t = twoFloors();
  assert.deepEqual(terrainBounds(t), { minX: 0, minY: 0, maxX: 20, maxY: 10, minZ: 0, maxZ: 3 });
  assert.equal(terrainBounds({ vertices: [] }), null);
  assert.deepEqual(worldBounds({ terrain: t }), { minX: 0, minY: 0, maxX: 20, maxY: 10, minZ: 0, maxZ: 3 });
  const raised = { vertices: [[-5, 1, 4], [5, 1, 4], [5, 30, 7]], walkable: [[0, 1, 2]] };
  assert.deepEqual(worldBounds({ terrain: raised }), { minX: -5, minY: 1, maxX: 5, maxY: 30, minZ: 4, maxZ: 7 });
});

test('flat scenario bounds are unchanged (z 0)', () => {
  const flat = { walkable: [[[0, 0], [30, 0], [30, 24], [0, 24]], [[30, 10], [40, 10], [40, 14]]],
    obstacles: [[[10, 10], [12, 10], [12, 12]]] };
  assert.deepEqual(worldBounds(flat), { minX: 0, minY: 0, maxX: 40, maxY: 24, minZ: 0, maxZ: 0 });
  assert.deepEqual(worldBounds({}), { minX: -10, minY: -10, maxX: 10, maxY: 10, minZ: 0, maxZ: 0 });
});

test('points stand at their height', () => {
  assert.equal(pointHeight({ position: [1, 2] }), 0);
  assert.equal(pointHeight({ position: [1, 2, 3] }), 3);
  assert.equal(pointHeight({ polygon: [[0, 0], [1, 0], [1, 1]], height: 6 }), 6);
  assert.equal(pointHeight({ polygon: [[0, 0, 3], [1, 0, 3], [1, 1, 3]] }), 3);
  assert.equal(pointHeight({ polygon: [[0, 0], [1, 0], [1, 1]] }), 0);
});

test('nearestOnTerrain: the point itself over a floor, else the nearest floor found on rings around it', () => {
  const t = twoFloors();
  assert.deepEqual(nearestOnTerrain(t, 15, 5, 3.5), { x: 15, y: 5, z: 3 });
  const p = nearestOnTerrain(t, 22, 5, 0);  // 2 m east of the building
  assert.ok(p && Math.abs(p.x - 20) <= 0.01 + 1e-9 && Math.abs(p.y - 5) < 1e-9, JSON.stringify(p));
  assert.ok(terrainHeightAt(t, p.x, p.y, 0) !== null);
  assert.equal(nearestOnTerrain(t, 100, 100, 0), null, 'no floor within reach');
});
