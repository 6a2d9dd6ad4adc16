// Near level of detail: skinned bodies. A pool of SkinnedMesh objects sharing one procedural
// geometry (body_geometry.js), each with its own bones (the description's skeleton), posed every
// frame from the agent's clip sampled at its phase, or from the joint angles the server sent for
// near-tier agents (3 per joint, X Y Z [rad], applied in BVH order Z, X, Y). The avatar of the
// local participant and other participants' avatars use the same bodies; an avatar drawn in a look
// (avatar_looks.js: shirt, trousers, skin, shoes, height) gets a copy of the geometry coloured per
// vertex, one per look.
import * as THREE from 'three';
import { skinnedBodyGeometry } from './body_geometry.js';
import { lookVertexColours } from './avatar_looks.js';
import { sampleClip, quatFromZXY } from './pose_math.js';
import { sceneYaw } from '../coords.js';

export function createSkinnedBody(joints, geometry, material) {
  const bones = joints.map((j) => {
    const b = new THREE.Bone();
    b.name = j.name;
    b.position.set(...j.offset);
    return b;
  });
  joints.forEach((j, i) => { if (j.parent >= 0) bones[j.parent].add(bones[i]); });
  const mesh = new THREE.SkinnedMesh(geometry, material);
  mesh.add(bones[0]);
  mesh.bind(new THREE.Skeleton(bones));
  mesh.frustumCulled = false;
  mesh.castShadow = false;
  return mesh;
}

export class NearBodies {
  constructor(scene, joints, clips) {
    this.scene = scene;
    this.joints = joints;
    this.clips = clips;
    this.geometry = skinnedBodyGeometry(joints);
    this.materials = new Map();
    this.lookGeometries = new Map();  // look → its vertex-coloured copy of the geometry
    this.lookMaterial = new THREE.MeshLambertMaterial({ vertexColors: true });
    this.pool = [];
    this.used = 0;
    this.quats = new Float32Array(joints.length * 4);
    this.root = new Float32Array(3);
  }

  material(color) {
    let m = this.materials.get(color);
    if (!m) { m = new THREE.MeshLambertMaterial({ color }); this.materials.set(color, m); }
    return m;
  }

  /** The geometry coloured in `look`, made on first use. */
  lookGeometry(look) {
    let g = this.lookGeometries.get(look);
    if (!g) {
      g = this.geometry.clone();
      const toRgb = (hex) => new THREE.Color(hex).toArray();  // sRGB hex → the renderer's linear values
      g.setAttribute('color', new THREE.Float32BufferAttribute(
        lookVertexColours(g.attributes.skinIndex.array, this.joints, look, toRgb), 3));
      this.lookGeometries.set(look, g);
    }
    return g;
  }

  begin() { this.used = 0; }

  /** Places the next pooled body at world (x, y, z) with yaw, posed by clip/phase or joints;
   * `color`: 0xRRGGBB for the whole body, or a look (avatar_looks.js). */
  add(x, y, z, yaw, clipId, phase, color, jointAngles = null) {
    let mesh = this.pool[this.used];
    if (!mesh) {
      mesh = createSkinnedBody(this.joints, this.geometry, this.material(0x808080));
      this.pool.push(mesh);
      this.scene.add(mesh);
    }
    this.used++;
    mesh.visible = true;
    const look = typeof color === 'object' ? color : null;
    mesh.geometry = look ? this.lookGeometry(look) : this.geometry;
    mesh.material = look ? this.lookMaterial : this.material(color);
    mesh.scale.setScalar(look ? look.height : 1);
    this.pose(mesh, x, y, z, yaw, clipId, phase, jointAngles);
    return mesh;
  }

  pose(mesh, x, y, z, yaw, clipId, phase, jointAngles) {
    const bones = mesh.skeleton.bones;
    sampleClip(this.clips.get(clipId), phase, this.quats, this.root);
    if (jointAngles && jointAngles.length >= bones.length * 3) {
      for (let j = 0; j < bones.length; ++j) {
        quatFromZXY(jointAngles[j * 3], jointAngles[j * 3 + 1], jointAngles[j * 3 + 2], this.quats, j * 4);
      }
    }
    for (let j = 0; j < bones.length; ++j) bones[j].quaternion.fromArray(this.quats, j * 4);
    bones[0].position.set(this.root[0], this.root[1], this.root[2]);
    mesh.position.set(x, z, -y);
    mesh.rotation.set(0, sceneYaw(yaw), 0);
  }

  end() {
    for (let i = this.used; i < this.pool.length; ++i) this.pool[i].visible = false;
  }
}
