// Pose math (src/crowd/pose_math.js): BVH Euler order and clip sampling, checked against three.js.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import * as THREE from 'three';
import { quatFromZXY, sampleClip } from '../src/crowd/pose_math.js';
import { makeWalkClip } from '../src/crowd/procedural_clips.js';

test('quatFromZXY equals three.js Euler order ZXY (BVH Zrotation Xrotation Yrotation)', () => {
  const q = new Float32Array(4);
  for (const [x, y, z] of [[0.3, -0.7, 1.1], [1.5, 0.2, -2.0], [0, 0, 0.5]]) {
    quatFromZXY(x, y, z, q);
    const t = new THREE.Quaternion().setFromEuler(new THREE.Euler(x, y, z, 'ZXY'));
    for (const [a, b] of [[q[0], t.x], [q[1], t.y], [q[2], t.z], [q[3], t.w]]) assert.ok(Math.abs(a - b) < 1e-6);
  }
});

test('sampling a looping clip wraps and interpolates between frames', () => {
  const clip = makeWalkClip();
  const J = clip.jointCount;
  const a = new Float32Array(J * 4), b = new Float32Array(J * 4), r = new Float32Array(3);
  sampleClip(clip, 0, a, r);
  sampleClip(clip, 1, b, r);  // phase 1 ≡ 0
  assert.deepEqual([...a], [...b]);
  sampleClip(clip, 0.5 / clip.frames, b, r);  // halfway to frame 1: unit quaternions
  for (let j = 0; j < J; ++j) assert.ok(Math.abs(Math.hypot(b[j * 4], b[j * 4 + 1], b[j * 4 + 2], b[j * 4 + 3]) - 1) < 1e-5);
  assert.ok(r[1] > 0.8 && r[1] < 1.0);  // pelvis height
});
