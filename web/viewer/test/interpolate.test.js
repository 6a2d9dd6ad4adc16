// Frame interpolation (src/interpolate.js): positions glide from the displayed pose to the new
// frame over one frame interval, yaw takes the short way round, new agents appear in place,
// departed agents vanish, phases advance between frames at the rate the frames show.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { CrowdState, angleDelta, phaseForward, kStrideCycle } from '../src/interpolate.js';
import { frameFromAgents } from '../src/sources/frame.js';

const near = (a, b, eps = 1e-4) => assert.ok(Math.abs(a - b) < eps, `${a} ≉ ${b}`);
const clips = [{ duration: 2, loops: true }, { duration: 1, loops: true }, { duration: 1, loops: false }];

test('angle and phase helpers', () => {
  near(angleDelta(3, -3), 2 * Math.PI - 6);
  near(angleDelta(-3, 3), 6 - 2 * Math.PI);
  near(angleDelta(0, 1), 1);
  near(phaseForward(0.9, 0.1), 0.2);
  near(phaseForward(0.1, 0.3), 0.2);
});

test('positions interpolate over one frame interval', () => {
  const s = new CrowdState(clips, 0.1);
  s.applyFrame(frameFromAgents([{ id: 1, x: 0, y: 0, yaw: 0, clip: 1 }]), 0);
  s.applyFrame(frameFromAgents([{ id: 1, x: 1, y: 2, yaw: 0, clip: 1 }]), 0.1);
  s.advance(0.15);
  near(s.x[0], 0.5); near(s.y[0], 1);
  s.advance(0.2);
  near(s.x[0], 1); near(s.y[0], 2);
  s.advance(0.5);  // no extrapolation past the last frame
  near(s.x[0], 1);
});

test('a frame arriving mid-glide starts from the displayed position (no jump)', () => {
  const s = new CrowdState(clips, 0.1);
  s.applyFrame(frameFromAgents([{ id: 1, x: 0, y: 0, clip: 1 }]), 0);
  s.applyFrame(frameFromAgents([{ id: 1, x: 1, y: 0, clip: 1 }]), 0.1);
  s.advance(0.15);
  const shown = s.x[0];
  s.applyFrame(frameFromAgents([{ id: 1, x: 2, y: 0, clip: 1 }]), 0.15);
  near(s.x[0], shown);
});

test('yaw turns the short way across ±π', () => {
  const s = new CrowdState(clips, 0.1);
  s.applyFrame(frameFromAgents([{ id: 3, x: 0, y: 0, yaw: 3.0, clip: 1 }]), 0);
  s.applyFrame(frameFromAgents([{ id: 3, x: 0, y: 0, yaw: -3.0, clip: 1 }]), 0.1);
  s.advance(0.15);
  near(s.yaw[0], 3.0 + (2 * Math.PI - 6) / 2);
});

test('agents come and go; teleports snap', () => {
  const s = new CrowdState(clips, 0.1);
  s.applyFrame(frameFromAgents([{ id: 1, x: 0, y: 0 }, { id: 2, x: 5, y: 5 }]), 0);
  s.applyFrame(frameFromAgents([{ id: 2, x: 50, y: 5 }, { id: 7, x: 9, y: 9 }]), 0.1);
  assert.equal(s.count, 2);
  assert.deepEqual([...s.ids], [2, 7]);
  s.advance(0.1);
  near(s.x[0], 50);  // 45 m in one frame: snapped, not glided
  near(s.x[1], 9);   // new agent: in place at once
  assert.equal(s.index.get(1), undefined);
});

test('phase advances between frames at the rate the frames show', () => {
  const s = new CrowdState(clips, 0.1);
  s.applyFrame(frameFromAgents([{ id: 1, x: 0, y: 0, clip: 1, phase: 0.0 }]), 0);
  s.applyFrame(frameFromAgents([{ id: 1, x: 0, y: 0, clip: 1, phase: 0.2 }]), 0.1);  // 2 cycles/s seen
  s.applyFrame(frameFromAgents([{ id: 1, x: 0, y: 0, clip: 1, phase: 0.4 }]), 0.2);
  const p0 = s.phase[0];
  s.advance(0.25);
  const rate = phaseForward(p0, s.phase[0]) / 0.05;
  assert.ok(rate > 1.2 && rate < 2.6, `rate ${rate}`);
});

test('phase holds when the server skips animation (granularity X > 1) and snaps on a clip change', () => {
  const s = new CrowdState(clips, 0.1);
  s.applyFrame(frameFromAgents([{ id: 1, x: 0, y: 0, clip: 0, phase: 0.5 }]), 0);
  s.applyFrame(frameFromAgents([{ id: 1, x: 0, y: 0, clip: 0, phase: 0.5 }]), 0.1);  // same phase: not refreshed
  s.advance(0.2);
  near(s.phase[0], 0.5 + 0.2 / 2);  // kept advancing at 1/duration
  s.applyFrame(frameFromAgents([{ id: 1, x: 0, y: 0, clip: 2, phase: 0.1 }]), 0.2);
  near(s.phase[0], 0.1);
  for (let t = 0.4; t < 5; t += 0.2) s.advance(t);  // a non-looping clip holds its end
  assert.ok(s.phase[0] <= 0.9991 && s.phase[0] > 0.99, `${s.phase[0]}`);
});

test('far-tier agents (no clip or phase on the wire) step at the rate their speed gives', () => {
  const s = new CrowdState(clips, 0.1);
  for (let k = 0; k <= 20; ++k) s.applyFrame(frameFromAgents([{ id: 7, tier: 2, x: 0.12 * k, y: 0 }], k), 0.1 * k);
  near(s.speed[0], 1.2, 1e-3);  // 0.12 m per 0.1 s
  near(s.rate[0], 1.2 / kStrideCycle, 1e-3);
  const before = s.phase[0];
  s.advance(2.0 + 0.5);
  near(phaseForward(before, s.phase[0]), (0.5 * 1.2) / kStrideCycle, 1e-3);
  // Standing: the rate falls to zero.
  for (let k = 21; k <= 60; ++k) s.applyFrame(frameFromAgents([{ id: 7, tier: 2, x: 2.4, y: 0 }], k), 0.1 * k);
  assert.ok(s.rate[0] < 0.01, `rate ${s.rate[0]}`);
});

test('a paused replay (the same simulated tick again) keeps the speeds; time moving on updates them', () => {
  const s = new CrowdState(clips, 0.1);
  for (let k = 0; k <= 20; ++k) s.applyFrame(frameFromAgents([{ id: 7, x: 0.12 * k, y: 0, clip: 1 }], k), 0.1 * k);
  near(s.speed[0], 1.2, 1e-3);
  // Paused at tick 20: the server keeps sending that moment; the walker still reads 1.2 m/s.
  for (let k = 21; k <= 60; ++k) s.applyFrame(frameFromAgents([{ id: 7, x: 2.4, y: 0, clip: 1 }], 20), 0.1 * k);
  near(s.speed[0], 1.2, 1e-3);
  // Playing on while it stands: the estimate falls.
  for (let k = 61; k <= 80; ++k) s.applyFrame(frameFromAgents([{ id: 7, x: 2.4, y: 0, clip: 1 }], k - 40), 0.1 * k);
  assert.ok(s.speed[0] < 0.01, `speed ${s.speed[0]}`);
});

test('speeds come from simulated time: a replay at 4x reads the walking speed, a seek reads nobody as fast', () => {
  const s = new CrowdState(clips, 0.1);
  s.dt = 0.05;
  // Played at 4x: each frame, 0.1 s apart on the wall clock, is 8 ticks (0.4 s) on, the walker 0.48 m on.
  for (let k = 0; k <= 20; ++k) s.applyFrame(frameFromAgents([{ id: 7, x: 0.48 * k, y: 0, clip: 1 }], 8 * k), 0.1 * k);
  near(s.speed[0], 1.2, 1e-3);
  // A seek back to the start: a standing agent 3 m from where the walker was is not read at 30 m/s.
  s.applyFrame(frameFromAgents([{ id: 7, x: 6.6, y: 0, clip: 1 }], 0), 2.2);
  assert.equal(s.speed[0], 0, 'after the jump its speed starts again from 0');
  s.applyFrame(frameFromAgents([{ id: 7, x: 6.6, y: 0, clip: 1 }], 2), 2.3);
  assert.equal(s.speed[0], 0, 'standing: 0');
});
