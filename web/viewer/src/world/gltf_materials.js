// glTF materials: a live world read from a glTF file (throng serve WORLD.gltf) is drawn from that
// file's own meshes, with their base colours and textures, where the file has materials — instead
// of the flat floor and obstacle colours of the scenario's polygons (world_view.js). The server
// hands the file out at GET /api/world/model ({"url": …, or null}; docs/server.md); three's
// GLTFLoader reads it. Pure: a node's role by throng's naming rules (docs/world-files.md) and what
// a file's materials cover (materialSummary); with three: loadWorldModel (the meshes, those without
// a material in the viewer's colours for their role) and showWorldModel (the model or the flat
// world drawn). glTF is Y-up in metres, the viewer's scene too: world (x, y, z) → scene (x, z, −y)
// is glTF's own frame, so the meshes go in unchanged.
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

export const kFloorColour = 0xd8d4cc;     // world_view.js's walkable floor
export const kObstacleColour = 0xb9a98f;  // world_view.js's obstacles

/** A node's role as throng reads it: 'walkable', 'obstacle', or null (points, crowds, decoration). */
export function gltfRole(node) {
  const name = String(node?.name || '').toLowerCase();
  const extras = node?.extras?.throng || {};
  if (name.startsWith('walkable') || extras.walkable === true) return 'walkable';
  if (name.startsWith('obstacle') || extras.obstacle === true) return 'obstacle';
  return null;
}

/** A material's base colour as drawn: a texture, a colour other than white, or neither. */
function baseColourOf(material) {
  const pbr = material?.pbrMetallicRoughness || {};
  if (pbr.baseColorTexture) return 'texture';
  const f = pbr.baseColorFactor;
  if (Array.isArray(f) && f.slice(0, 3).some((v) => v !== 1)) return 'colour';
  return null;
}

/** What a glTF document's materials cover: {textured, coloured, plain} counts of the mesh
 * primitives of nodes with a mesh, by their material's base colour; `any`: some base colour to draw. */
export function materialSummary(json) {
  const out = { textured: 0, coloured: 0, plain: 0, any: false };
  for (const node of json?.nodes || []) {
    const mesh = json.meshes?.[node.mesh];
    if (!mesh) continue;
    for (const p of mesh.primitives || []) {
      const kind = p.material === undefined ? null : baseColourOf(json.materials?.[p.material]);
      if (kind === 'texture') out.textured++;
      else if (kind === 'colour') out.coloured++;
      else out.plain++;
    }
  }
  out.any = out.textured + out.coloured > 0;
  return out;
}

/** The glTF node an object of GLTFLoader's scene came from (itself or its nearest ancestor). */
function nodeOf(parser, object) {
  for (let o = object; o; o = o.parent) {
    const a = parser.associations.get(o);
    if (a && a.nodes !== undefined) return parser.json.nodes[a.nodes];
  }
  return null;
}

/** Meshes whose primitive has no material get the viewer's colour for their node's role. */
function colourPlainMeshes(gltf) {
  const { parser } = gltf;
  const floor = new THREE.MeshLambertMaterial({ color: kFloorColour, side: THREE.DoubleSide });
  const solid = new THREE.MeshLambertMaterial({ color: kObstacleColour });
  gltf.scene.traverse((o) => {
    if (!o.isMesh) return;
    const a = parser.associations.get(o);
    const primitive = a && parser.json.meshes[a.meshes]?.primitives[a.primitives];
    if (primitive && primitive.material !== undefined) return;
    o.material = gltfRole(nodeOf(parser, o)) === 'walkable' ? floor : solid;
  });
}

/** Loads the world model at `url` (the server's /api/world/model answer): a Group named
 * 'world-model' with the file's default scene, or null when its materials give no base colour
 * (the flat world is as good) or it cannot be loaded. */
export async function loadWorldModel(url, loader = new GLTFLoader()) {
  const gltf = await loader.loadAsync(url);
  const summary = materialSummary(gltf.parser.json);
  if (!summary.any) return null;
  colourPlainMeshes(gltf);
  const group = new THREE.Group();
  group.name = 'world-model';
  group.add(gltf.scene);
  group.userData.summary = summary;
  return group;
}

/** Draws the model (`on`) or the flat floors and obstacles it stands for, in the world `root`
 * (world_view.js marks those with userData.flat). */
export function showWorldModel(root, model, on) {
  model.visible = on;
  root.traverse((o) => { if (o.userData.flat) o.visible = !on; });
}
