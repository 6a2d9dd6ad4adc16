// The global level-of-detail function (src/lod.js): levels by projected size, caps (largest on
// screen win), hysteresis at the thresholds, and the frame-time budget's adaptation.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Level, assignLevels, projectedHeight, LodBudget, nearestVisible, defaultLodParams } from '../src/lod.js';

// alwaysNear 0: the rules of size, caps and hysteresis alone (the pinned nearest are tested below).
const params = { nearPx: 100, middlePx: 20, maxNear: 10, maxMiddle: 100, hysteresis: 0.2, alwaysNear: 0, adaptive: true };

test('projected height falls with distance and grows with screen height', () => {
  const fov = Math.PI / 3;
  const h10 = projectedHeight(10, fov, 1000, 1.75);
  assert.ok(Math.abs(h10 - (1.75 * 1000) / (2 * 10 * Math.tan(fov / 2))) < 1e-9);
  assert.ok(Math.abs(projectedHeight(20, fov, 1000) - h10 / 2) < 1e-9);
  assert.ok(Math.abs(projectedHeight(10, fov, 2000) - h10 * 2) < 1e-9);
});

test('levels by projected size; off screen is hidden', () => {
  const sizes = Float32Array.from([500, 150, 50, 25, 10, 1, -1]);
  const out = new Uint8Array(sizes.length);
  const c = assignLevels(sizes, sizes.length, null, out, params);
  assert.deepEqual([...out], [Level.Near, Level.Near, Level.Middle, Level.Middle, Level.Far, Level.Dot, Level.Hidden]);
  assert.deepEqual([c.near, c.middle, c.far, c.dot, c.hidden], [2, 2, 1, 1, 1]);
});

test('caps keep the largest on screen; the rest drop one level', () => {
  const n = 50;
  const sizes = Float32Array.from({ length: n }, (_, i) => 200 + i * 10);  // all large enough for near
  const out = new Uint8Array(n);
  const c = assignLevels(sizes, n, null, out, { ...params, maxNear: 10 });
  assert.equal(c.near, 10);
  assert.equal(c.nearDemand, 50);
  for (let i = 0; i < n; ++i) assert.equal(out[i], i >= 40 ? Level.Near : Level.Middle, `agent ${i}`);
  const c2 = assignLevels(sizes, n, null, out, { ...params, maxNear: 10, maxMiddle: 5 });
  assert.equal(c2.middle, 5);
  assert.equal(c2.far, 35);
});

test('caps are exact even when every size falls in one histogram bucket', () => {
  const n = 30;
  const sizes = new Float32Array(n).fill(300);
  const out = new Uint8Array(n);
  const prev = new Uint8Array(n).fill(Level.Middle);
  for (const i of [5, 17, 29]) prev[i] = Level.Near;
  const c = assignLevels(sizes, n, prev, out, { ...params, maxNear: 3 });
  assert.equal(c.near, 3);
  // Previous holders keep their level (no flicker among equals).
  for (const i of [5, 17, 29]) assert.equal(out[i], Level.Near);
});

test('hysteresis: a near agent stays near until clearly below the threshold', () => {
  const out = new Uint8Array(1);
  const near = Uint8Array.from([Level.Near]), far = Uint8Array.from([Level.Far]), mid = Uint8Array.from([Level.Middle]);
  assignLevels(Float32Array.from([90]), 1, near, out, params);  // 90 ≥ 100 × (1 − 0.2)
  assert.equal(out[0], Level.Near);
  assignLevels(Float32Array.from([90]), 1, far, out, params);   // not near when coming from far
  assert.equal(out[0], Level.Middle);
  assignLevels(Float32Array.from([79]), 1, near, out, params);
  assert.equal(out[0], Level.Middle);
  assignLevels(Float32Array.from([17]), 1, mid, out, params);   // 17 ≥ 20 × 0.8: stays middle
  assert.equal(out[0], Level.Middle);
  assignLevels(Float32Array.from([17]), 1, far, out, params);
  assert.equal(out[0], Level.Far);
});

test('display off: every visible agent gets the full body', () => {
  const sizes = Float32Array.from([500, 1, -1]);
  const out = new Uint8Array(3);
  assignLevels(sizes, 3, null, out, { ...params, adaptive: false });
  assert.deepEqual([...out], [Level.Near, Level.Near, Level.Hidden]);
});

test('budget: over budget shrinks caps and raises thresholds; under budget grows back', () => {
  const b = new LodBudget({ targetFrameMs: 20, maxNear: 40, maxMiddle: 1000, periodS: 0.5 });
  const demand = { nearDemand: 1000, middleDemand: 10000 };
  for (let k = 0; k < 60; ++k) b.update(50, demand);  // 3 s at 20 fps against a 50 fps target
  const p = b.params();
  assert.ok(p.maxNear < 40 && p.maxMiddle < 1000, JSON.stringify(p));
  assert.ok(p.nearPx > 150 && p.middlePx > 30);
  assert.ok(p.maxNear >= 2 && p.maxMiddle >= 50);
  for (let k = 0; k < 4000; ++k) b.update(5, demand);  // 20 s at 200 fps
  const q = b.params();
  assert.equal(q.maxNear, 40);
  assert.equal(q.maxMiddle, 1000);
  assert.equal(q.nearPx, 150);
});

test('budget: inside the dead band nothing changes (no oscillation)', () => {
  const b = new LodBudget({ targetFrameMs: 20, maxNear: 40, maxMiddle: 1000 });
  for (let k = 0; k < 60; ++k) b.update(50, { nearDemand: 1000, middleDemand: 10000 });
  for (let k = 0; k < 30; ++k) b.update(20, { nearDemand: 1000, middleDemand: 10000 });  // smoothing settles
  const before = b.params();
  for (let k = 0; k < 600; ++k) b.update([20, 22, 17][k % 3], { nearDemand: 1000, middleDemand: 10000 });  // in the band
  assert.deepEqual(b.params(), before);
});

test('budget: caps do not grow when nobody needs them', () => {
  const b = new LodBudget({ targetFrameMs: 20, maxNear: 40, maxMiddle: 1000 });
  for (let k = 0; k < 60; ++k) b.update(50, { nearDemand: 1000, middleDemand: 10000 });
  const shrunk = b.params();
  for (let k = 0; k < 1000; ++k) b.update(5, { nearDemand: 0, middleDemand: 0 });
  assert.equal(b.params().maxNear, shrunk.maxNear);
  assert.equal(b.params().maxMiddle, shrunk.maxMiddle);
});

test('dots: far agents below dotPx become dots, with hysteresis both ways', () => {
  const p = { ...params, dotPx: 6 };  // hysteresis 0.2: 4.8 px
  const out = new Uint8Array(1);
  const far = Uint8Array.from([Level.Far]), dot = Uint8Array.from([Level.Dot]);
  assignLevels(Float32Array.from([5.5]), 1, far, out, p);  // 5.5 ≥ 4.8: a billboard stays one
  assert.equal(out[0], Level.Far);
  assignLevels(Float32Array.from([4.5]), 1, far, out, p);
  assert.equal(out[0], Level.Dot);
  assignLevels(Float32Array.from([5.5]), 1, dot, out, p);  // a dot stays one until ≥ 6 px
  assert.equal(out[0], Level.Dot);
  assignLevels(Float32Array.from([6.5]), 1, dot, out, p);
  assert.equal(out[0], Level.Far);
  assignLevels(Float32Array.from([5.5]), 1, null, out, p);  // no history counts as Far
  assert.equal(out[0], Level.Far);
  // Dots never replace larger levels, nor show off-screen agents; display off has no dots.
  const o3 = new Uint8Array(3);
  assignLevels(Float32Array.from([2, 2, -1]), 3, null, o3, { ...p, middlePx: 1, maxMiddle: 1 });
  assert.deepEqual([...o3], [Level.Middle, Level.Dot, Level.Hidden]);
  assignLevels(Float32Array.from([2]), 1, null, out, { ...p, adaptive: false });
  assert.equal(out[0], Level.Near);
});

test('budget: dynamic resolution drops when over budget, faster when far over, and comes back', () => {
  const b = new LodBudget({ targetFrameMs: 20, periodS: 0.5, minRenderScale: 0.5 });
  assert.equal(b.params().renderScale, 1);
  for (let k = 0; k < 20; ++k) b.update(25, null);  // 1.25× the target: over budget (> 1.15×)
  const mild = b.params().renderScale;
  assert.ok(mild < 1 && mild >= 0.5, String(mild));
  const c = new LodBudget({ targetFrameMs: 20, periodS: 0.5, minRenderScale: 0.5 });
  for (let k = 0; k < 20; ++k) c.update(40, null);  // same number of periods, 2× the target
  assert.ok(c.params().renderScale < mild);
  for (let k = 0; k < 200; ++k) c.update(100, null);
  assert.equal(c.params().renderScale, 0.5);  // never below the floor
  for (let k = 0; k < 4000; ++k) c.update(5, null);  // 20 s at 200 fps: full resolution again
  assert.equal(c.params().renderScale, 1);
  // Dot threshold follows the size-threshold scale.
  assert.equal(c.params().dotPx, 6);
});

test('nearestVisible: the k largest on screen at or above the floor, largest first', () => {
  const sizes = Float32Array.from([30, -1, 500, 90, 20, 500, 700, 10]);
  assert.deepEqual(nearestVisible(sizes, sizes.length, 3, 24), [6, 2, 5]);
  assert.deepEqual(nearestVisible(sizes, sizes.length, 10, 24), [6, 2, 5, 3, 0]);
  assert.deepEqual(nearestVisible(sizes, sizes.length, 0, 24), []);
  assert.deepEqual(nearestVisible(Float32Array.from([-1, 5]), 2, 4, 24), []);
});

test('the selected agent and the nearest few stay full bodies when the budget squeezes the rest', () => {
  // A budget long over its target: caps at their floor, thresholds scaled up 4×.
  const budget = new LodBudget({ targetFrameMs: 10 });
  let p = budget.params();
  for (let k = 0; k < 200; ++k) p = budget.update(100, { nearDemand: 1000, middleDemand: 1000 });
  assert.equal(p.maxNear, 2);
  assert.ok(p.nearPx >= 4 * defaultLodParams.nearPx - 1e-9);
  // 1000 agents 100–300 px high (under the squeezed near threshold), the four nearest 400–460 px,
  // the selected one far away (40 px), one off screen.
  const n = 1006;
  const sizes = new Float32Array(n);
  for (let i = 0; i < 1000; ++i) sizes[i] = 100 + (i % 200);
  sizes[1000] = 400; sizes[1001] = 420; sizes[1002] = 440; sizes[1003] = 460;
  sizes[1004] = 40;   // selected
  sizes[1005] = -1;   // off screen
  const out = new Uint8Array(n);
  const c = assignLevels(sizes, n, null, out, p, null, [1004, 1005]);
  for (const i of [1000, 1001, 1002, 1003, 1004]) assert.equal(out[i], Level.Near, `agent ${i}`);
  assert.equal(out[1005], Level.Hidden);
  assert.equal(c.pinned, defaultLodParams.alwaysNear + 1);
  assert.equal(c.near, c.pinned, 'nobody else qualifies for a skinned body under the squeezed budget');
  assert.equal(c.nearDemand, 0, 'pinned bodies do not make the budget grow the cap');
  // Without the rule they would all have been middle bodies at best.
  const plain = new Uint8Array(n);
  assignLevels(sizes, n, null, plain, { ...p, alwaysNear: 0 });
  for (const i of [1000, 1001, 1002, 1003, 1004]) assert.notEqual(plain[i], Level.Near, `agent ${i}`);
});

test('the nearest few are pinned only within a looking distance; the cap still holds for the rest', () => {
  const sizes = Float32Array.from([20, 15, 10, 5]);  // all under alwaysNearMinPx
  const out = new Uint8Array(4);
  const c = assignLevels(sizes, 4, null, out, { ...params, maxNear: 0, alwaysNear: 4, alwaysNearMinPx: 24 });
  assert.equal(c.near, 0);
  assert.equal(c.pinned, 0);
  // Large agents over the cap: the nearest alwaysNear pinned, then maxNear more from the rest.
  const big = Float32Array.from({ length: 20 }, (_, i) => 200 + i);
  const o2 = new Uint8Array(20);
  const c2 = assignLevels(big, 20, null, o2, { ...params, maxNear: 3, alwaysNear: 2 });
  assert.equal(c2.pinned, 2);
  assert.equal(c2.near, 5);
  assert.equal(o2[19], Level.Near);
  assert.equal(o2[18], Level.Near);
});
