// Far level of detail: instanced billboards with angular level of detail. At start-up the 3D
// skinned body (near_bodies.js) is rendered into a texture atlas from kAngles directions around it
// (columns) × kWalkFrames walk-cycle frames plus one standing frame (rows), with an orthographic
// camera into an offscreen render target — images generated from the 3D body, not drawn. Each far
// agent is one quad (4 vertices of one shared dynamic geometry, not GPU instances) that turns about the vertical to face the camera; the shader picks
// the column from the angle between the agent's facing and the direction to the camera, and the
// row from its walk phase. One draw call for all far agents.
import * as THREE from 'three';
import { createSkinnedBody } from './near_bodies.js';
import { sampleClip } from './pose_math.js';

export const kAngles = 16;
export const kWalkFrames = 4;
const kRows = kWalkFrames + 1;
const kCellW = 48, kCellH = 96;
const kQuadW = 0.95, kQuadH = 1.9;  // [m] world size of a cell

/** Renders the atlas; returns the render target (texture: rt.texture). */
export function renderAtlas(renderer, joints, geometry, clips) {
  const rt = new THREE.WebGLRenderTarget(kAngles * kCellW, kRows * kCellH, {
    minFilter: THREE.LinearFilter, magFilter: THREE.LinearFilter, generateMipmaps: false,
  });
  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x888888, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.2);
  sun.position.set(2, 5, 3);
  scene.add(sun);
  const body = createSkinnedBody(joints, geometry, new THREE.MeshLambertMaterial({ color: 0xffffff }));
  scene.add(body);
  const cam = new THREE.OrthographicCamera(-kQuadW / 2, kQuadW / 2, kQuadH, 0, 0.1, 20);
  const quats = new Float32Array(joints.length * 4), root = new Float32Array(3);
  const walk = clips.get(clips.walkClipId()), idle = clips.get(clips.idleClipId());
  const prevTarget = renderer.getRenderTarget();
  const prevColor = renderer.getClearColor(new THREE.Color()), prevAlpha = renderer.getClearAlpha();
  renderer.setRenderTarget(rt);
  renderer.setClearColor(0x000000, 0);
  renderer.clear();
  rt.scissorTest = true;
  for (let row = 0; row < kRows; ++row) {
    const clip = row < kWalkFrames ? walk : idle;
    sampleClip(clip, row < kWalkFrames ? row / kWalkFrames : 0, quats, root);
    body.skeleton.bones.forEach((b, j) => b.quaternion.fromArray(quats, j * 4));
    body.skeleton.bones[0].position.fromArray(root);
    for (let col = 0; col < kAngles; ++col) {
      const rel = (col / kAngles) * Math.PI * 2;  // camera direction in the body's frame (0 = in front)
      cam.position.set(Math.sin(rel) * 8, 0, Math.cos(rel) * 8);
      cam.lookAt(0, 0, 0);
      cam.updateMatrixWorld();
      rt.viewport.set(col * kCellW, row * kCellH, kCellW, kCellH);
      rt.scissor.set(col * kCellW, row * kCellH, kCellW, kCellH);
      renderer.setRenderTarget(rt);
      renderer.render(scene, cam);
    }
  }
  rt.scissorTest = false;
  renderer.setRenderTarget(prevTarget);
  renderer.setClearColor(prevColor, prevAlpha);
  body.geometry = new THREE.BufferGeometry();  // the shared geometry stays with its owner
  return rt;
}

const vertexShader = `
attribute vec3 iPos;
attribute vec3 iColor;
attribute vec2 iAnim; // (scene yaw [rad], atlas row)
varying vec2 vUv;
varying vec3 vColor;
void main() {
  vec3 toCam = cameraPosition - iPos;
  vec2 d = normalize(toCam.xz + vec2(1e-5, 0.0));
  vec3 right = vec3(d.y, 0.0, -d.x);
  vec3 p = iPos + right * (position.x * ${kQuadW.toFixed(3)}) + vec3(0.0, position.y * ${kQuadH.toFixed(3)}, 0.0);
  float rel = atan(d.x, d.y) - iAnim.x;
  float col = mod(floor(rel / 6.2831853 * ${kAngles.toFixed(1)} + 0.5), ${kAngles.toFixed(1)});
  vUv = vec2((col + position.x + 0.5) / ${kAngles.toFixed(1)}, (iAnim.y + position.y) / ${kRows.toFixed(1)});
  vColor = iColor;
  gl_Position = projectionMatrix * viewMatrix * vec4(p, 1.0);
}`;

const fragmentShader = `
uniform sampler2D atlas;
varying vec2 vUv;
varying vec3 vColor;
void main() {
  vec4 c = texture2D(atlas, vUv);
  if (c.a < 0.5) discard;
  gl_FragColor = vec4(c.rgb * vColor, 1.0);
  #include <colorspace_fragment>
}`;

export class Billboards {
  constructor(scene, atlasTexture) {
    this.scene = scene;
    this.material = new THREE.ShaderMaterial({ uniforms: { atlas: { value: atlasTexture } }, vertexShader, fragmentShader });
    this.capacity = 0;
    this.count = 0;
    this.mesh = null;
  }

  // Not GPU-instanced: SwiftShader (and some weak GPUs) pay a fixed cost per instance, so each
  // agent's quad is written out as 4 vertices of one plain geometry (still one draw call).
  ensure(n) {
    if (n <= this.capacity) return;
    const cap = Math.max(256, Math.ceil(n * 1.5));
    const g = new THREE.BufferGeometry();
    const corner = new Float32Array(cap * 12), index = new Uint32Array(cap * 6);
    const kCorner = [-0.5, 0, 0, 0.5, 0, 0, 0.5, 1, 0, -0.5, 1, 0];
    for (let i = 0; i < cap; ++i) {
      corner.set(kCorner, i * 12);
      const v = i * 4;
      index.set([v, v + 1, v + 2, v, v + 2, v + 3], i * 6);
    }
    g.setAttribute('position', new THREE.BufferAttribute(corner, 3));
    g.setIndex(new THREE.BufferAttribute(index, 1));
    this.pos = new THREE.BufferAttribute(new Float32Array(cap * 12), 3).setUsage(THREE.DynamicDrawUsage);
    this.color = new THREE.BufferAttribute(new Float32Array(cap * 12), 3).setUsage(THREE.DynamicDrawUsage);
    this.anim = new THREE.BufferAttribute(new Float32Array(cap * 8), 2).setUsage(THREE.DynamicDrawUsage);
    g.setAttribute('iPos', this.pos);
    g.setAttribute('iColor', this.color);
    g.setAttribute('iAnim', this.anim);
    if (this.mesh) { this.scene.remove(this.mesh); this.mesh.geometry.dispose(); }
    this.mesh = new THREE.Mesh(g, this.material);
    this.mesh.frustumCulled = false;
    this.scene.add(this.mesh);
    this.capacity = cap;
  }

  begin(maxCount) { this.ensure(Math.max(maxCount, 1)); this.count = 0; }

  /** Scene yaw [rad]; row: 0…kWalkFrames−1 walk frames, kWalkFrames standing. */
  add(sx, sy, sz, sceneYaw, row, color) {
    const i = this.count++;
    const p = this.pos.array, c = this.color.array, a = this.anim.array;
    const r = color.r, gr = color.g, b = color.b;
    for (let k = 0, o = i * 12; k < 4; ++k, o += 3) {
      p[o] = sx; p[o + 1] = sy; p[o + 2] = sz;
      c[o] = r; c[o + 1] = gr; c[o + 2] = b;
    }
    for (let k = 0, o = i * 8; k < 4; ++k, o += 2) { a[o] = sceneYaw; a[o + 1] = row; }
  }

  end() {
    this.mesh.geometry.setDrawRange(0, this.count * 6);
    for (const [attr, w] of [[this.pos, 12], [this.color, 12], [this.anim, 8]]) {
      attr.clearUpdateRanges();
      attr.addUpdateRange(0, this.count * w);
      attr.needsUpdate = true;
    }
    this.mesh.visible = this.count > 0;
  }
}
