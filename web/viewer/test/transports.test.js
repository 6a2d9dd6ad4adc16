// Lifts and escalators in the viewer (src/world/world_view.js): their stops as world points, and the
// belt and the shaft buildWorld draws between them.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import * as THREE from 'three';
import { buildWorld, transportShapes } from '../src/world/world_view.js';

const square = (x0, y0, x1, y1) => [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
function atrium() {
  return {
    walkable: [square(0, 0, 30, 20)],
    points: [
      { id: 'foot', kind: 'interest', polygon: square(10, 2, 12, 4), height: 0 },
      { id: 'head', kind: 'interest', polygon: square(22, 2, 24, 4), height: 4.5 },
      { id: 'lift-0', kind: 'interest', polygon: square(2, 15, 4, 17), height: 0 },
      { id: 'lift-1', kind: 'interest', position: [3, 16], height: 4.5 },
      { id: 'lift-2', kind: 'interest', position: [3, 16, 9] },
    ],
    transports: [
      { id: 'up', kind: 'escalator', stops: ['foot', 'head'] },
      { id: 'lift', kind: 'elevator', stops: ['lift-0', 'lift-1', 'lift-2'] },
      { id: 'broken', kind: 'escalator', stops: ['foot', 'nowhere'] },
    ],
  };
}

test('transportShapes places every stop at its point and height, and skips what names no point', () => {
  const shapes = transportShapes(atrium());
  assert.deepEqual(shapes, [
    { id: 'up', kind: 'escalator', stops: [[11, 3, 0], [23, 3, 4.5]] },
    { id: 'lift', kind: 'elevator', stops: [[3, 16, 0], [3, 16, 4.5], [3, 16, 9]] },
  ]);
  assert.deepEqual(transportShapes({ points: [] }), []);
});

test('buildWorld draws the escalator from foot to head and the lift shaft over every floor', () => {
  const world = buildWorld(atrium());
  world.updateMatrixWorld(true);
  const belt = world.getObjectByName('transport-escalator');
  assert.ok(belt, 'escalator drawn');
  assert.equal(belt.userData.transport, 'up');
  const box = new THREE.Box3().setFromObject(belt);
  // Scene (x, z, −y): the belt runs from x 11 to 23 and climbs from 0 to 4.5 (the handrails 0.9 above).
  assert.ok(Math.abs(box.min.x - 11) < 0.5 && Math.abs(box.max.x - 23) < 0.5, `x ${box.min.x}..${box.max.x}`);  // rails lean with the belt
  assert.ok(box.min.y < 0 && box.min.y > -0.6 && box.max.y > 4.5 && box.max.y < 4.5 + 1.2, `y ${box.min.y}..${box.max.y}`);
  assert.ok(box.min.z > -3.8 && box.max.z < -2.2, `z ${box.min.z}..${box.max.z}`);
  const shaft = world.getObjectByName('transport-lift');
  assert.ok(shaft, 'lift drawn');
  const s = new THREE.Box3().setFromObject(shaft);
  assert.ok(Math.abs(s.min.y) < 1e-6 && s.max.y > 9 + 2, `shaft ${s.min.y}..${s.max.y}`);
  assert.ok(Math.abs((s.min.x + s.max.x) / 2 - 3) < 1e-6 && Math.abs((s.min.z + s.max.z) / 2 + 16) < 1e-6);
  assert.equal(buildWorld({ walkable: [square(0, 0, 5, 5)] }).getObjectByName('transport-lift'), undefined);
});
