// Unit tests of web/editor/src/geometry.js: lengths, area and centroid, the simplicity check
// (crossing, touching and folding edges, repeated points), point-in-polygon, and snapping to
// vertices, right angles, axes and the grid, in that order of priority.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  bounds, centroid, cleanPolygon, distanceToSegment, isSimplePolygon, pointInPolygon, polygonArea, polygonProblem,
  polylineLength, rectangle, roundTo, signedArea, snapPoint,
} from '../src/geometry.js';

const square = [[0, 0], [4, 0], [4, 4], [0, 4]];

test('lengths, areas and centroids', () => {
  assert.equal(polylineLength([[0, 0], [3, 4], [3, 10]]), 11);
  assert.equal(polylineLength(square, true), 16);
  assert.equal(polygonArea(square), 16);
  assert.equal(signedArea(square), 16);
  assert.equal(signedArea([...square].reverse()), -16);
  assert.deepEqual(centroid(square), [2, 2]);
  // An L shape: its centroid is not the vertex mean.
  const l = [[0, 0], [4, 0], [4, 1], [1, 1], [1, 4], [0, 4]];
  assert.equal(polygonArea(l), 7);
  const [cx, cy] = centroid(l);
  assert.ok(Math.abs(cx - 9.5 / 7) < 1e-9 && Math.abs(cy - 9.5 / 7) < 1e-9, `${cx}, ${cy}`);  // (4·2 + 3·0.5) / 7
});

test('simple polygons and the problems the validator refuses', () => {
  assert.ok(isSimplePolygon(square));
  assert.equal(polygonProblem([[0, 0], [4, 4], [4, 0], [0, 5]]), 'edges 0 and 2 cross');  // a bow tie
  assert.equal(polygonProblem([[0, 0], [1, 0]]), 'fewer than 3 distinct points');
  assert.equal(polygonProblem([[0, 0], [1, 0], [2, 0]]), 'zero area');
  assert.match(polygonProblem([[0, 0], [4, 0], [2, 0], [2, 3]]), /fold back/);  // a spike back along an edge
  // A closing repeat and repeated points are dropped, as the loader drops them.
  assert.deepEqual(cleanPolygon([[0, 0], [0, 0], [4, 0], [4, 4], [0, 0]]), [[0, 0], [4, 0], [4, 4]]);
  assert.ok(isSimplePolygon([[0, 0], [0, 0], [4, 0], [4, 4], [0, 4], [0, 0]]));
  // A vertex touching a non-adjacent edge is not simple.
  assert.ok(!isSimplePolygon([[0, 0], [4, 0], [4, 4], [2, 0], [0, 4]]));
});

test('point in polygon, distance to a segment, rectangles, bounds', () => {
  assert.ok(pointInPolygon([1, 1], square));
  assert.ok(!pointInPolygon([5, 1], square));
  assert.equal(distanceToSegment([2, 3], [0, 0], [4, 0]), 3);
  assert.equal(distanceToSegment([7, 4], [0, 0], [4, 0]), 5);
  assert.deepEqual(rectangle([3, 5], [1, 2]), [[1, 2], [3, 2], [3, 5], [1, 5]]);
  assert.deepEqual(bounds([[1, 2], [-1, 5]]), { x0: -1, y0: 2, x1: 1, y1: 5 });
  assert.equal(bounds([]), null);
  assert.equal(roundTo(0.1 + 0.2, 0.1), 0.3);
});

test('snapping: vertex first, then a right angle or an axis, then the grid', () => {
  const vertices = [[2, 2]];
  assert.deepEqual(snapPoint([2.1, 1.95], { grid: 0.5, vertices, tolerance: 0.2 }), { point: [2, 2], kind: 'vertex' });
  assert.deepEqual(snapPoint([1.3, 0.8], { grid: 0.5, vertices, tolerance: 0.2 }), { point: [1.5, 1], kind: 'grid' });
  assert.deepEqual(snapPoint([1.3, 0.8], { grid: 0, tolerance: 0.2 }), { point: [1.3, 0.8], kind: 'none' });
  // Along the x axis from the anchor, then to the grid along it.
  assert.deepEqual(snapPoint([3.12, 0.1], { grid: 0.5, anchor: [0, 0], tolerance: 0.2 }), { point: [3, 0], kind: 'axis' });
  // At a right angle to a slanted segment before -> anchor.
  const before = [0, 0], anchor = [3, 3];
  const s = snapPoint([4.05, 1.9], { grid: 0, anchor, before, tolerance: 0.2 });
  assert.equal(s.kind, 'right-angle');
  const d1 = [anchor[0] - before[0], anchor[1] - before[1]], d2 = [s.point[0] - anchor[0], s.point[1] - anchor[1]];
  assert.ok(Math.abs(d1[0] * d2[0] + d1[1] * d2[1]) < 1e-6, `not perpendicular: ${s.point}`);
  // Out of reach of every line: the grid.
  assert.equal(snapPoint([4.6, 4.4], { grid: 0.5, anchor: [0, 0], tolerance: 0.1 }).kind, 'grid');
});
