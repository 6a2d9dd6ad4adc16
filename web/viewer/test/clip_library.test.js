// Baking BVH clips (src/crowd/clip_library.js bakeBvh) with three's BVHLoader, as the viewer loads
// the bundled scenarios/motions: the root position is the file's hip position (0.95 m up), not that
// plus the root's OFFSET (which three's loader adds, and which floated every near body ~1 m up).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { BVHLoader } from 'three/examples/jsm/loaders/BVHLoader.js';
import { bakeBvh } from '../src/crowd/clip_library.js';

const motions = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../../scenarios/motions');

test('a baked clip keeps the hips at the height its file gives them', () => {
  const text = fs.readFileSync(path.join(motions, 'idle.bvh'), 'utf8');
  const parsed = new BVHLoader().parse(text);
  const names = parsed.skeleton.bones.map((b) => b.name);
  // The file's first frame: the root's position channels (Xposition Yposition Zposition first).
  const first = text.split('MOTION')[1].trim().split('\n')[2].trim().split(/\s+/).slice(0, 3).map(Number);
  const clip = bakeBvh(parsed, names, 'idle', true);
  assert.ok(clip.frames > 1);
  for (let k = 0; k < 3; ++k) assert.ok(Math.abs(clip.root[k] - first[k]) < 1e-5, `root[${k}] ${clip.root[k]} vs ${first[k]}`);
  assert.ok(clip.root[1] > 0.8 && clip.root[1] < 1.1, `hips ${clip.root[1]} m up`);
});

test('a result without a root track or skeleton leaves the root at the origin', () => {
  const clip = bakeBvh({ clip: { tracks: [] } }, ['root'], 'empty', false);
  assert.deepEqual([...clip.root], [0, 0, 0]);
  assert.deepEqual([...clip.quats], [0, 0, 0, 1]);
});
