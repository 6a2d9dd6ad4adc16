// Walls, railings and stair risers (src/world/walls.js): where the walkable area's boundary gets a
// wall, where a door leaves a gap, and where a staircase gets risers instead of walls.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { walkableWalls, terrainWalls, insidePolygon, wallRectangles } from '../src/world/walls.js';

const length = (segs) => segs.reduce((s, w) => s + Math.hypot(w.x1 - w.x0, w.y1 - w.y0), 0);
const near = (a, b, eps = 1e-6) => Math.abs(a - b) <= eps;

test('a single room is walled all round, whichever way its polygon turns', () => {
  const room = [[0, 0], [10, 0], [10, 5], [0, 5]];
  for (const poly of [room, [...room].reverse()]) {
    const walls = walkableWalls([poly]);
    assert.equal(walls.length, 4);
    assert.ok(near(length(walls), 30));
  }
});

test('a shop overlapping the corridor at its door: walls all round both but the 1.2 m door', () => {
  const corridor = [[0, 0], [20, 0], [20, 4], [0, 4]];
  // The shop (5 x 5 m) north of the corridor, its door a 1.2 m notch reaching 0.2 m into the corridor.
  const shop = [[5, 4.5], [7.4, 4.5], [7.4, 3.8], [8.6, 3.8], [8.6, 4.5], [10, 4.5], [10, 9.5], [5, 9.5]];
  const walls = walkableWalls([corridor, shop]);
  // Corridor: 48 m of perimeter less the door (1.2 m); the shop: its 20 m less the door's 1.2 m,
  // plus the notch's sides as far as they stand outside the corridor (2 x 0.5 m).
  assert.ok(Math.abs(length(walls) - (48 - 1.2 + 20 - 1.2 + 1.0)) < 0.25, `wall length ${length(walls)}`);
  // Nothing stands in the doorway (x 7.4 .. 8.6 at y = 4).
  for (const w of walls) {
    const onDoorLine = near(w.y0, 4) && near(w.y1, 4);
    if (onDoorLine) assert.ok(Math.max(w.x0, w.x1) <= 7.45 || Math.min(w.x0, w.x1) >= 8.55, `a wall across the door: ${JSON.stringify(w)}`);
  }
  // The door's notch inside the corridor has no walls (it is walkable on both sides).
  assert.ok(!walls.some((w) => w.y0 < 3.95 && w.y1 < 3.95 && w.y0 > 3.5), 'a wall inside the corridor');
});

test('two rooms sharing a whole wall become one hall: no wall between them', () => {
  const walls = walkableWalls([[[0, 0], [5, 0], [5, 5], [0, 5]], [[5, 0], [10, 0], [10, 5], [5, 5]]]);
  assert.ok(near(length(walls), 30, 1e-6));
  assert.ok(!walls.some((w) => near(w.x0, 5) && near(w.x1, 5)));
});

test('insidePolygon is the even-odd rule', () => {
  const sq = [[0, 0], [2, 0], [2, 2], [0, 2]];
  assert.equal(insidePolygon(1, 1, sq), true);
  assert.equal(insidePolygon(3, 1, sq), false);
});

/** A 10 x 6 m floor at z 0 and a gallery 10 x 6 m at z 0.9 east of it, joined by a 2 m wide
 * staircase of 3 steps (0.3 m high, 1 m deep) on x 10..13, y 2..4. */
function steppedWorld() {
  const vertices = [], walkable = [];
  const quad = (x0, y0, x1, y1, z) => {
    const i = vertices.length;
    vertices.push([x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]);
    walkable.push([i, i + 1, i + 2], [i, i + 2, i + 3]);
  };
  quad(0, 0, 10, 6, 0);
  for (let s = 0; s < 3; ++s) quad(10 + s, 2, 11 + s, 4, 0.3 * (s + 1));
  quad(13, 0, 23, 6, 0.9);
  return { vertices, walkable, obstacles: [] };
}

test('a staircase gets a riser at each step, railings along its sides and no wall across it', () => {
  const { walls, risers } = terrainWalls(steppedWorld());
  // Risers: the first step over the floor (0 → 0.3), the second and third over the one before.
  const fronts = risers.filter((r) => near(r.x0, r.x1) && Math.abs(r.y1 - r.y0) > 1.9);
  assert.deepEqual(fronts.map((r) => [r.x0, r.zLow, r.zHigh].map((v) => Math.round(v * 100) / 100)).sort((p, q) => p[0] - q[0]),
    [[10, 0, 0.3], [11, 0.3, 0.6], [12, 0.6, 0.9]]);
  // No wall stands across the way up: none on x = 10..13 spanning y 2..4 at the steps' fronts.
  for (const w of walls) {
    const across = near(w.x0, w.x1) && w.x0 >= 10 - 1e-6 && w.x0 <= 13 + 1e-6 && Math.min(w.y0, w.y1) < 3.9 && Math.max(w.y0, w.y1) > 2.1;
    assert.ok(!across, `a wall across the stairs: ${JSON.stringify(w)}`);
  }
  // The steps' sides: the first step (0.3 m over the floor beyond) gets side risers, the third
  // (0.9 m over the floor) railings.
  assert.ok(walls.some((w) => near(w.y0, w.y1) && (near(w.y0, 2) || near(w.y0, 4)) && w.x0 >= 12 - 1e-6 && near(w.z0, 0.9)));
  // The gallery's edge over the floor (x = 13 beside the stairs, 0.9 m drop) is a railing, and the
  // outer walls of both floors are walls: the floor's 32 m perimeter less the 2 m where the stairs start.
  const floorWalls = walls.filter((w) => near(w.z0, 0) && near(w.z1, 0));
  assert.ok(Math.abs(length(floorWalls) - 30) < 0.3, `floor walls ${length(floorWalls)}`);
  const galleryWest = walls.filter((w) => near(w.x0, 13) && near(w.x1, 13) && near(w.z0, 0.9));
  assert.ok(Math.abs(length(galleryWest) - 4) < 0.3, `gallery railing over the floor ${length(galleryWest)}`);
});

test('a flat world and an empty terrain have no terrain walls', () => {
  assert.deepEqual(terrainWalls(null), { walls: [], risers: [] });
  assert.deepEqual(terrainWalls({ vertices: [], walkable: [] }), { walls: [], risers: [] });
});

test('a scenario wall is drawn as the rectangles the engine cuts out: thickness wide, ends lengthened', () => {
  // An L: 4 m east, then 3 m north, 0.2 m thick (the default).
  const rects = wallRectangles({ line: [[0, 0], [4, 0], [4, 3]] });
  assert.equal(rects.length, 2);
  const xs = rects[0].map((p) => p[0]), ys = rects[0].map((p) => p[1]);
  assert.ok(near(Math.min(...xs), -0.1) && near(Math.max(...xs), 4.1), `x ${xs}`);
  assert.ok(near(Math.min(...ys), -0.1) && near(Math.max(...ys), 0.1), `y ${ys}`);
  // The corner (4, 0) is inside both rectangles: the joint is covered.
  assert.ok(insidePolygon(4.05, -0.05, rects[0]) && insidePolygon(4.05, -0.05, rects[1]));
  // A thickness of its own; zero-length segments and missing lines give nothing.
  const thick = wallRectangles({ line: [[0, 0], [0, 0], [0, 2]], thickness: 0.5 });
  assert.equal(thick.length, 1);
  assert.ok(near(Math.max(...thick[0].map((p) => p[0])), 0.25));
  assert.deepEqual(wallRectangles({}), []);
});

test('what visitors look at hangs on the wall they face; a look at nothing near gets no picture', async () => {
  const fs = await import('node:fs');
  const { exhibitsOnWalls, polygonEdges, walkableWalls, kExhibitReach } = await import('../src/world/walls.js');
  const museum = JSON.parse(fs.readFileSync(new URL('../../../scenarios/museum.json', import.meta.url), 'utf8'));
  const segments = [...walkableWalls(museum.walkable), ...polygonEdges(museum.obstacles)];
  const looks = museum.points.filter((p) => p.kind === 'action' && p.action === 'look');
  const exhibits = exhibitsOnWalls(museum.points, segments);
  assert.equal(exhibits.length, looks.length, 'every painting of the museum is on a wall');
  for (const e of exhibits) {
    const p = e.point, d = Math.hypot(e.x - p.position[0], e.y - p.position[1]);
    assert.ok(d > 0.5 && d <= kExhibitReach, `${p.id}: ${d.toFixed(2)} m in front`);
    const o = p.orientation, l = Math.hypot(o[0], o[1]);
    assert.ok(Math.abs(e.nx + o[0] / l) < 1e-9 && Math.abs(e.ny + o[1] / l) < 1e-9, `${p.id} faces its visitors`);
  }
  // A square with nothing to look at within reach, and a point that is not a look.
  const square = [[0, 0], [20, 0], [20, 20], [0, 20]];
  const points = [{ id: 'statue', kind: 'action', action: 'look', position: [10, 10], orientation: [1, 0] },
    { id: 'kiosk', kind: 'action', action: 'buy', position: [19, 10], orientation: [1, 0] },
    { id: 'notice', kind: 'action', action: 'look', position: [18.5, 10], orientation: [1, 0], radius: 1 }];
  const got = exhibitsOnWalls(points, walkableWalls([square]));
  assert.deepEqual(got.map((e) => e.point.id), ['notice']);
  assert.ok(Math.abs(got[0].x - 19.98) < 1e-9 && Math.abs(got[0].y - 10) < 1e-9 && got[0].width === 1.3);
});
