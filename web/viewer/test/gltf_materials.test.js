// glTF materials (src/world/gltf_materials.js): a node's role by throng's naming rules
// (docs/world-files.md), and what a world file's materials give to draw — the bundled
// scenarios/tiled_hall.gltf (a textured floor, coloured carpet and obstacles) against
// scenarios/gallery.gltf (no materials: the viewer keeps its flat floor).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { gltfRole, materialSummary } from '../src/world/gltf_materials.js';

const scenarios = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../../scenarios');
const read = (name) => JSON.parse(fs.readFileSync(path.join(scenarios, name), 'utf8'));

test('roles: walkable and obstacle by name (any case) or extras, nothing else', () => {
  assert.equal(gltfRole({ name: 'walkable_hall' }), 'walkable');
  assert.equal(gltfRole({ name: 'WalkableStairs' }), 'walkable');
  assert.equal(gltfRole({ name: 'slab', extras: { throng: { walkable: true } } }), 'walkable');
  assert.equal(gltfRole({ name: 'Obstacle_wall' }), 'obstacle');
  assert.equal(gltfRole({ name: 'kiosk', extras: { throng: { obstacle: true } } }), 'obstacle');
  for (const name of ['interest:statue', 'crowd:visitors', 'Lamp', 'floor_walkable', '']) assert.equal(gltfRole({ name }), null, name);
  assert.equal(gltfRole(null), null);
});

test('the tiled hall has a texture and base colours; the gallery has nothing to draw', () => {
  assert.deepEqual(materialSummary(read('tiled_hall.gltf')), { textured: 1, coloured: 4, plain: 0, any: true });
  const gallery = materialSummary(read('gallery.gltf'));
  assert.equal(gallery.any, false);
  assert.ok(gallery.plain >= 5, JSON.stringify(gallery));
  assert.equal(materialSummary(read('two_floors.gltf')).any, false);
});

test('a white base colour, a material without a base colour and a missing material draw nothing new', () => {
  const json = {
    nodes: [{ mesh: 0 }, { mesh: 1 }, { mesh: 2 }, { name: 'no mesh' }],
    meshes: [{ primitives: [{ material: 0 }] }, { primitives: [{ material: 1 }, {}] }, { primitives: [{ material: 7 }] }],
    materials: [{ pbrMetallicRoughness: { baseColorFactor: [1, 1, 1, 0.5] } }, { name: 'emissive only', emissiveFactor: [1, 0, 0] }],
  };
  assert.deepEqual(materialSummary(json), { textured: 0, coloured: 0, plain: 4, any: false });
  json.materials[1].pbrMetallicRoughness = { baseColorFactor: [0.2, 0.4, 0.6, 1] };
  assert.deepEqual(materialSummary(json), { textured: 0, coloured: 1, plain: 3, any: true });
  assert.deepEqual(materialSummary({}), { textured: 0, coloured: 0, plain: 0, any: false });
});
