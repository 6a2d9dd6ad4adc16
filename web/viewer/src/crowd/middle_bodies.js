// Middle level of detail: low-polygon bodies, GPU-instanced (one InstancedMesh, one draw call).
// Per instance: matrix (position, yaw), colour, and `iAnim` = (walk phase, swing amplitude [rad]);
// the vertex shader swings legs and arms about the hip and shoulder pivots (body_geometry.js
// `part`/`pivot` attributes): left leg −A·cos 2πφ (forward at φ = 0, the left heel strike), right
// leg opposite, arms opposite to the legs. Standing agents get amplitude 0.
import * as THREE from 'three';
import { lowPolyBodyGeometry } from './body_geometry.js';
import { sceneYaw } from '../coords.js';

const kSwing = 0.45;  // [rad] leg swing amplitude while walking

export class MiddleBodies {
  constructor(scene, joints) {
    this.scene = scene;
    this.geometry = lowPolyBodyGeometry(joints);
    this.material = new THREE.MeshLambertMaterial({ color: 0xffffff });
    this.material.onBeforeCompile = (shader) => {
      shader.vertexShader = shader.vertexShader
        .replace('#include <common>', `#include <common>
attribute vec2 iAnim;
attribute float part;
attribute vec3 pivot;
vec3 swingAbout(vec3 v, vec3 p, float a) {
  vec3 d = v - p;
  float c = cos(a), s = sin(a);
  return p + vec3(d.x, d.y * c - d.z * s, d.y * s + d.z * c);
}
float swingAngle() {
  float s = iAnim.y * cos(6.2831853 * iAnim.x);
  if (part < 0.5) return 0.0;
  if (part < 1.5) return -s;
  if (part < 2.5) return s;
  if (part < 3.5) return 0.7 * s;
  return -0.7 * s;
}`)
        .replace('#include <beginnormal_vertex>', `#include <beginnormal_vertex>
{ float a = swingAngle(); float c = cos(a), s = sin(a);
  objectNormal = vec3(objectNormal.x, objectNormal.y * c - objectNormal.z * s, objectNormal.y * s + objectNormal.z * c); }`)
        .replace('#include <begin_vertex>', `#include <begin_vertex>
transformed = swingAbout(transformed, pivot, swingAngle());`);
    };
    this.capacity = 0;
    this.mesh = null;
    this.count = 0;
  }

  ensure(n) {
    if (n <= this.capacity) return;
    const cap = Math.max(256, Math.ceil(n * 1.5));
    if (this.mesh) { this.scene.remove(this.mesh); this.mesh.dispose(); }
    const mesh = new THREE.InstancedMesh(this.geometry, this.material, cap);
    mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    mesh.instanceColor = new THREE.InstancedBufferAttribute(new Float32Array(cap * 3), 3);
    mesh.instanceColor.setUsage(THREE.DynamicDrawUsage);
    this.anim = new THREE.InstancedBufferAttribute(new Float32Array(cap * 2), 2);
    this.anim.setUsage(THREE.DynamicDrawUsage);
    this.geometry.setAttribute('iAnim', this.anim);
    mesh.frustumCulled = false;
    mesh.count = 0;
    this.scene.add(mesh);
    this.mesh = mesh;
    this.capacity = cap;
  }

  begin(maxCount) { this.ensure(Math.max(maxCount, 1)); this.count = 0; }

  add(x, y, z, yaw, phase, walking, color) {
    const i = this.count++;
    const m = this.mesh.instanceMatrix.array;
    const r = sceneYaw(yaw), c = Math.cos(r), s = Math.sin(r);
    const o = i * 16;
    // Rotation about Y then translation (column-major).
    m[o] = c; m[o + 1] = 0; m[o + 2] = -s; m[o + 3] = 0;
    m[o + 4] = 0; m[o + 5] = 1; m[o + 6] = 0; m[o + 7] = 0;
    m[o + 8] = s; m[o + 9] = 0; m[o + 10] = c; m[o + 11] = 0;
    m[o + 12] = x; m[o + 13] = z; m[o + 14] = -y; m[o + 15] = 1;
    const col = this.mesh.instanceColor.array;
    col[i * 3] = color.r; col[i * 3 + 1] = color.g; col[i * 3 + 2] = color.b;
    this.anim.array[i * 2] = phase;
    this.anim.array[i * 2 + 1] = walking ? kSwing : 0;
  }

  end() {
    const mesh = this.mesh;
    mesh.count = this.count;
    mesh.instanceMatrix.needsUpdate = true;
    mesh.instanceColor.needsUpdate = true;
    this.anim.needsUpdate = true;
    mesh.visible = this.count > 0;
  }
}
