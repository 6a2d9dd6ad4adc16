// Picking (src/camera/pick.js): a ray hits an agent's upright capsule from the side, from straight
// above (a plan view: the old side-of-a-cylinder test missed every such click) and obliquely;
// it misses beside it, behind the camera and above the head; of two agents, the one under the
// pointer wins. Scene coordinates: world (x, y, z) → scene (x, z, −y).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { rayToUprightSegment, pickAgent } from '../src/camera/pick.js';

const v = (x, y, z) => ({ x, y, z });
const norm = (p) => { const l = Math.hypot(p.x, p.y, p.z); return v(p.x / l, p.y / l, p.z / l); };
/** A crowd state of agents at world (x, y, z). */
function crowd(...agents) {
  return { count: agents.length, x: agents.map((a) => a[0]), y: agents.map((a) => a[1]), z: agents.map((a) => a[2] || 0) };
}
/** Ray from scene point `from` towards the world point (x, y, z). */
function rayTo(from, [x, y, z]) {
  return { origin: from, direction: norm(v(x - from.x, z - from.y, -y - from.z)) };
}

test('a ray from straight above hits the agent below it (plan view)', () => {
  const s = crowd([3, 4]);
  assert.equal(pickAgent({ origin: v(3, 100, -4), direction: v(0, -1, 0) }, s), 0);
  assert.equal(pickAgent({ origin: v(3.3, 100, -4), direction: v(0, -1, 0) }, s), 0, '0.3 m off the axis: still on the body');
  assert.equal(pickAgent({ origin: v(3.6, 100, -4), direction: v(0, -1, 0) }, s), -1, '0.6 m off: a miss');
  assert.equal(pickAgent({ origin: v(3.6, 100, -4), direction: v(0, -1, 0) }, s, 0.7), 0, 'a wider pick radius (a zoomed-out plan)');
});

test('a ray from the side and obliquely hits the body, not the air above it', () => {
  const s = crowd([0, 0]);
  assert.equal(pickAgent({ origin: v(-10, 1, 0), direction: v(1, 0, 0) }, s), 0, 'side, chest high');
  assert.equal(pickAgent({ origin: v(-10, 2.6, 0), direction: v(1, 0, 0) }, s), -1, 'side, over the head');
  assert.equal(pickAgent(rayTo(v(-6, 8, 6), [0, 0, 1]), s), 0, 'oblique at the waist');
  assert.equal(pickAgent(rayTo(v(-6, 8, 6), [0, 0, 0]), s), 0, 'oblique at the feet');
  assert.equal(pickAgent({ origin: v(10, 1, 0), direction: v(1, 0, 0) }, s), -1, 'the agent is behind the camera');
});

test('of two neighbours, the one under the pointer wins', () => {
  const s = crowd([0, 0], [0.6, 0]);
  assert.equal(pickAgent({ origin: v(0.05, 50, 0), direction: v(0, -1, 0) }, s), 0);
  assert.equal(pickAgent({ origin: v(0.55, 50, 0), direction: v(0, -1, 0) }, s), 1);
});

test('an agent on an upper floor is hit at its height', () => {
  const s = crowd([0, 0, 0], [5, 0, 3]);
  assert.equal(pickAgent(rayTo(v(5, 12, 8), [5, 0, 4]), s), 1);
  const up = rayToUprightSegment(v(5, 12, 0), v(0, -1, 0), 5, 3, 0, 1.8);
  assert.ok(up.dist < 1e-9 && Math.abs(up.t - (12 - 4.8)) < 1e-9, `meets the top of the capsule: ${JSON.stringify(up)}`);
});
