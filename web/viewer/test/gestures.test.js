// Participants' gestures (src/crowd/gestures.js): joint angles sampled from a gesture clip, their
// Joints encoding (the C++ golden bytes, and through web/protocol's decoder back to the angles),
// the ~10 Hz sending while a gesture plays, and remote avatars' 1 s timeout back to idle.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { decodeAny } from '../../protocol/decode.js';
import * as enc from '../src/net/encode.js';
import { quatFromZXY, eulerZXYFromQuat } from '../src/crowd/pose_math.js';
import { kHanimSkeleton, makeGestureClip } from '../src/crowd/procedural_clips.js';
import { GesturePlayer, RemoteJoints, gestureClip, sampleJointAngles, kGestures, kJointsTimeoutMs } from '../src/crowd/gestures.js';

const golden = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../../tests/protocol/golden/joints.bin');
const kTurn16 = (2 * Math.PI) / 65536;
const wrap = (a) => Math.atan2(Math.sin(a), Math.cos(a));

test('eulerZXYFromQuat inverts quatFromZXY', () => {
  const q = new Float32Array(4), e = new Float32Array(3), q2 = new Float32Array(4);
  for (const [x, y, z] of [[0.3, -0.7, 1.1], [-1.2, 2.5, -2.0], [0, 0, 0.5], [1.5, 0.1, 0.2]]) {
    quatFromZXY(x, y, z, q);
    eulerZXYFromQuat(q, 0, e);
    assert.ok(Math.abs(e[0] - x) < 1e-5 && Math.abs(e[1] - y) < 1e-5 && Math.abs(e[2] - z) < 1e-5, `${[x, y, z]} → ${[...e]}`);
    quatFromZXY(e[0], e[1], e[2], q2);
    assert.ok(Math.abs(q[0] * q2[0] + q[1] * q2[1] + q[2] * q2[2] + q[3] * q2[3]) > 1 - 1e-6);
  }
});

test('Joints of the golden sample encode as the C++ bytes and decode back', () => {
  const bytes = enc.encodeJoints({ subject: { kind: 1, value: 7 }, seq: 300, angles: [0, 0.5, -0.5, 3.0, -3.0, 1.0] });
  assert.deepEqual([...bytes], [...fs.readFileSync(golden)]);
  const m = decodeAny(fs.readFileSync(golden));
  assert.equal(m.type, 'Joints');
  assert.equal(Number(m.seq), 300);
  assert.equal(m.angles.length, 6);
});

test('a gesture sampled, sent as Joints and decoded gives the clip\'s angles (within 1/65536 turn)', () => {
  const J = kHanimSkeleton.length;
  for (const g of kGestures) {
    const clip = makeGestureClip(g.name);
    const angles = sampleJointAngles(clip, 0.4);
    assert.equal(angles.length, J * 3);
    const bytes = enc.encodeJoints({ subject: { kind: 0, value: 0x1234n }, seq: 5, angles });
    assert.equal(bytes.length, 2 + 1 + 8 + 1 + 1 + J * 3 * 2);
    const m = decodeAny(bytes);
    assert.equal(m.angles.length, J * 3);
    for (let i = 0; i < J * 3; ++i) {
      const back = ((m.angles[i] << 16) >> 16) * kTurn16;
      assert.ok(Math.abs(wrap(back - angles[i])) < 2 * kTurn16, `${g.name} angle ${i}: ${angles[i]} → ${back}`);
    }
  }
  // The wave raises the right arm: its shoulder's Z angle is far from rest mid-gesture.
  const r = kHanimSkeleton.findIndex((j) => j.name === 'r_shoulder');
  assert.ok(Math.abs(sampleJointAngles(makeGestureClip('wave'), 0.4)[r * 3 + 2]) > 1.5);
});

test('gestureClip prefers the world\'s clip of that name', () => {
  const worldWave = { name: 'wave', duration: 3, loops: true, frames: 2, jointCount: J(), quats: new Float32Array(2 * J() * 4), root: new Float32Array(6) };
  const clips = { info: [{ id: 0, name: 'idle' }, { id: 4, name: 'Wave_hand' }], get: (id) => (id === 4 ? worldWave : null) };
  const c = gestureClip(clips, 'wave', kHanimSkeleton);
  assert.equal(c.duration, 3);
  assert.equal(c.loops, false);
  assert.equal(gestureClip(clips, 'nod', kHanimSkeleton).name, 'nod');  // none in the world: procedural
  function J() { return kHanimSkeleton.length; }
});

test('GesturePlayer: plays once, Joints due about every 100 ms', () => {
  const p = new GesturePlayer();
  assert.equal(p.sample(0), null);
  const clip = makeGestureClip('nod');
  p.start('nod', clip, 1000);
  let sends = 0, samples = 0;
  for (let t = 1000; t < 1000 + clip.duration * 1000; t += 16) {
    const s = p.sample(t);
    assert.ok(s && s.name === 'nod' && s.phase >= 0 && s.phase < 1);
    samples++;
    if (s.send) sends++;
  }
  assert.ok(sends >= 17 && sends <= 21, `${sends} Joints over ${clip.duration} s`);
  assert.equal(p.sample(1000 + clip.duration * 1000 + 1), null, 'over after one play');
  assert.ok(samples > 100);
});

test('RemoteJoints: the latest angles until none came for 1 s, then the idle pose', () => {
  const r = new RemoteJoints();
  const a = Float32Array.of(1, 2, 3), b = Float32Array.of(4, 5, 6);
  assert.equal(r.get(3, 0), null);
  r.set(3, a, 100);
  r.set(3, b, 200);
  assert.equal(r.get(3, 250), b);
  assert.equal(r.get(3, 200 + kJointsTimeoutMs), b);
  assert.equal(r.get(4, 250), null, 'per participant');
  assert.equal(r.get(3, 201 + kJointsTimeoutMs), null, 'timed out');
  assert.equal(r.get(3, 250), null, 'forgotten once timed out');
  r.set(3, a, 5000);
  r.delete(3);
  assert.equal(r.get(3, 5001), null);
  assert.equal(r.received, 3);
});
