// The avatar's looks (src/crowd/avatar_looks.js): distinct from one another and from the colours
// that mean something else on screen, each joint's solids coloured as the right body part, per-vertex
// colours of a body in a look, and the choice remembered (or not) in the browser's storage.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { kAvatarLooks, lookAt, lookPartOf, lookVertexColours, rgbOf, loadLookChoice, saveLookChoice }
  from '../src/crowd/avatar_looks.js';
import { kHanimSkeleton } from '../src/crowd/procedural_clips.js';

const distance = (a, b) => Math.hypot(...rgbOf(a).map((v, i) => v - rgbOf(b)[i]));

test('at least four looks, each shirt told apart from every other and from the marks', () => {
  assert.ok(kAvatarLooks.length >= 4, `${kAvatarLooks.length} looks`);
  for (const [i, a] of kAvatarLooks.entries()) {
    for (const b of kAvatarLooks.slice(i + 1)) assert.ok(distance(a.shirt, b.shirt) > 0.3, `${a.name} vs ${b.name}`);
    // the selected agent (yellow), the picked group (lime), other participants (magenta)
    for (const mark of [0xffe040, 0xb4f000, 0xd02090]) assert.ok(distance(a.shirt, mark) > 0.3, `${a.name} vs ${mark.toString(16)}`);
    assert.ok(a.height >= 0.9 && a.height <= 1.1, `${a.name}: height ${a.height}`);
  }
  assert.ok(new Set(kAvatarLooks.map((l) => l.height)).size > 1, 'some looks are taller or shorter');
});

test('an index out of range or not a number gives the first look', () => {
  assert.equal(lookAt(2), kAvatarLooks[2]);
  assert.equal(lookAt('3'), kAvatarLooks[3]);
  for (const bad of [-1, kAvatarLooks.length, 1.5, 'x', null, undefined]) assert.equal(lookAt(bad), kAvatarLooks[0], String(bad));
});

test('joints of H-Anim and of common BVH skeletons map to their body parts', () => {
  const parts = Object.fromEntries(kHanimSkeleton.map((j) => [j.name, lookPartOf(j.name)]));
  assert.deepEqual([parts.skullbase, parts.l_wrist, parts.r_ankle, parts.l_knee, parts.r_hip, parts.sacroiliac],
    ['skin', 'skin', 'shoes', 'trousers', 'trousers', 'trousers']);
  assert.deepEqual([parts.vl5, parts.l_shoulder, parts.r_elbow, parts.HumanoidRoot], ['shirt', 'shirt', 'shirt', 'shirt']);
  assert.deepEqual(['Head', 'LeftHand', 'RightFoot', 'LeftUpLeg', 'Spine1', 'LeftForeArm'].map(lookPartOf),
    ['skin', 'skin', 'shoes', 'trousers', 'shirt', 'shirt']);
});

test('each vertex takes the colour of its bone\'s part', () => {
  const look = kAvatarLooks[2];
  const skull = kHanimSkeleton.findIndex((j) => j.name === 'skullbase');
  const knee = kHanimSkeleton.findIndex((j) => j.name === 'l_knee');
  const spine = kHanimSkeleton.findIndex((j) => j.name === 'vl5');
  const skinIndex = Uint16Array.of(skull, 0, 0, 0, knee, 0, 0, 0, spine, 0, 0, 0);
  const c = lookVertexColours(skinIndex, kHanimSkeleton, look);
  assert.equal(c.length, 9);
  assert.deepEqual([...c.slice(0, 3)], rgbOf(look.skin).map(Math.fround));
  assert.deepEqual([...c.slice(3, 6)], rgbOf(look.trousers).map(Math.fround));
  assert.deepEqual([...c.slice(6, 9)], rgbOf(look.shirt).map(Math.fround));
  const doubled = lookVertexColours(skinIndex, kHanimSkeleton, look, (hex) => rgbOf(hex).map((v) => v / 2));
  assert.equal(doubled[6], Math.fround(rgbOf(look.shirt)[0] / 2), 'the converter given is used');
});

test('the choice is remembered, and a storage that refuses or holds nonsense gives the first look', () => {
  const store = new Map();
  const storage = { getItem: (k) => (store.has(k) ? store.get(k) : null), setItem: (k, v) => store.set(k, v) };
  assert.equal(loadLookChoice(storage), 0);
  saveLookChoice(storage, 3);
  assert.equal(loadLookChoice(storage), 3);
  store.set([...store.keys()][0], '99');
  assert.equal(loadLookChoice(storage), 0);
  const refusing = { getItem: () => { throw new Error('denied'); }, setItem: () => { throw new Error('denied'); } };
  assert.equal(loadLookChoice(refusing), 0);
  assert.doesNotThrow(() => saveLookChoice(refusing, 2));
  assert.equal(loadLookChoice(undefined), 0);
});
