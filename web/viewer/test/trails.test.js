// Trails (src/crowd/trails.js TrailBuffer): only the last `seconds` of simulated time, samples at
// least `step` apart, a jump breaks the line, agents long gone are dropped, time running backwards
// (a replay seeked back) starts afresh.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { TrailBuffer, kTrailJump } from '../src/crowd/trails.js';

const one = (buf, id, x, y, t) => buf.record(Uint32Array.of(id), Float32Array.of(x), Float32Array.of(y), Float32Array.of(0), 1, t);
function segments(buf) {
  const out = [];
  buf.forEachSegment((id, ax, ay, az, bx, by, bz, ageA, ageB) => out.push({ id, ax, bx, ageA, ageB }));
  return out;
}

test('a walker leaves a trail of the last seconds only', () => {
  const b = new TrailBuffer(2, 0.2);
  for (let k = 0; k <= 50; ++k) one(b, 7, k * 0.1, 0, k * 0.1);  // 1 m/s for 5 s, frames every 0.1 s
  const s = segments(b);
  assert.ok(s.length >= 8 && s.length <= 11, `about 2 s of 0.2 s steps: ${s.length}`);
  assert.ok(s.every((g) => g.ageA <= 2 + 1e-9 && g.ageB <= g.ageA), 'ages within the window, oldest first');
  assert.ok(Math.abs(s.at(-1).bx - 5) < 1e-6 && s.at(-1).ageB < 1e-9, 'it ends where the agent is now');
  assert.ok(s[0].ax >= 3 - 1e-6, `it starts about 2 s back (x ${s[0].ax})`);
});

test('a jump breaks the line; agents long gone are dropped; time going back clears', () => {
  const b = new TrailBuffer(2, 0.2);
  one(b, 1, 0, 0, 0); one(b, 1, 0.3, 0, 0.2); one(b, 1, 0.3 + kTrailJump + 1, 0, 0.4); one(b, 1, 6.5, 0, 0.6);
  assert.equal(segments(b).length, 2, 'the jump is not drawn');
  one(b, 2, 0, 0, 3);
  assert.ok(!b.agents.has(1), 'agent 1, unseen for more than the window, is dropped');
  one(b, 2, 0.2, 0, 3.2);
  assert.equal(segments(b).length, 1);
  one(b, 2, 0, 0, 1);
  assert.equal(segments(b).length, 0, 'seeked back: afresh');
});

test('record says when the trails changed: a sample added, an agent dropped, time going back', () => {
  const b = new TrailBuffer(10, 0.2);
  const ids = Uint32Array.from([1]), z = Float32Array.from([0]);
  assert.equal(b.record(ids, Float32Array.from([0]), Float32Array.from([0]), z, 1, 0), true);
  assert.equal(b.record(ids, Float32Array.from([0.1]), Float32Array.from([0]), z, 1, 0.1), false, 'within a step: nothing new');
  assert.equal(b.record(ids, Float32Array.from([0.3]), Float32Array.from([0]), z, 1, 0.2), true);
  assert.equal(b.record(ids, Float32Array.from([0.3]), Float32Array.from([0]), z, 1, 0.25), false);
  assert.equal(b.record(ids, Float32Array.from([0]), Float32Array.from([0]), z, 1, 0.05), true, 'time back: afresh');
  assert.equal(b.record(new Uint32Array(0), new Float32Array(0), new Float32Array(0), new Float32Array(0), 0, 20), true, 'agent 1 gone');
});

test('a huge crowd gets coarser trails under the segment cap, each still ending at its newest sample', () => {
  const b = new TrailBuffer(10, 0.2);
  const n = 10, ids = Uint32Array.from({ length: n }, (_, i) => i), z = new Float32Array(n);
  for (let s = 0; s < 20; ++s) {
    const x = Float32Array.from({ length: n }, (_, i) => s * 0.25), y = Float32Array.from({ length: n }, (_, i) => i);
    b.record(ids, x, y, z, n, s * 0.2);
  }
  const full = b.forEachSegment(() => {});
  assert.equal(full, n * 19);
  const ends = new Map();
  const capped = b.forEachSegment((id, ax, ay, az, bx, by, bz, ageA, ageB) => {
    assert.ok(Math.abs(bx - ax - 4 * 0.25) < 1e-6, 'every 4th sample joined');
    if (!ends.has(id) || ageB < ends.get(id).age) ends.set(id, { age: ageB, x: bx });
  }, 50);
  assert.equal(capped, n * 4);
  for (const e of ends.values()) { assert.ok(Math.abs(e.age) < 1e-9); assert.ok(Math.abs(e.x - 19 * 0.25) < 1e-6); }
});
