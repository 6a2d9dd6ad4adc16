// Lowest level of detail: a flat-coloured dot per agent a few pixels high (lod.js Level.Dot).
// One point sprite per agent in one plain (not instanced) geometry, one draw call: the point is
// the agent's projected height [px] high, its colour the group colour shaded like the billboards'
// average, and its footprint a narrow upright ellipse (about a body's width-to-height ratio).
import * as THREE from 'three';

const vertexShader = `
attribute vec3 iColor;
uniform float pxPerUnit; // screen height [px] / (2 tan(fovY/2))
varying vec3 vColor;
void main() {
  vec4 mv = viewMatrix * vec4(position + vec3(0.0, 0.9, 0.0), 1.0);
  gl_PointSize = max(1.5, 1.75 * pxPerUnit / max(-mv.z, 1e-3));
  vColor = iColor;
  gl_Position = projectionMatrix * mv;
}`;

const fragmentShader = `
varying vec3 vColor;
void main() {
  vec2 d = gl_PointCoord - vec2(0.5);
  if (d.x * d.x * 16.0 + d.y * d.y * 4.0 > 1.0) discard; // ellipse 0.25 wide × 1 high
  gl_FragColor = vec4(vColor * 0.8, 1.0);
  #include <colorspace_fragment>
}`;

export class Dots {
  constructor(scene) {
    this.scene = scene;
    this.material = new THREE.ShaderMaterial({ uniforms: { pxPerUnit: { value: 500 } }, vertexShader, fragmentShader });
    this.capacity = 0;
    this.count = 0;
    this.points = null;
  }

  ensure(n) {
    if (n <= this.capacity) return;
    const cap = Math.max(256, Math.ceil(n * 1.5));
    const g = new THREE.BufferGeometry();
    this.pos = new THREE.BufferAttribute(new Float32Array(cap * 3), 3).setUsage(THREE.DynamicDrawUsage);
    this.color = new THREE.BufferAttribute(new Float32Array(cap * 3), 3).setUsage(THREE.DynamicDrawUsage);
    g.setAttribute('position', this.pos);
    g.setAttribute('iColor', this.color);
    if (this.points) { this.scene.remove(this.points); this.points.geometry.dispose(); }
    this.points = new THREE.Points(g, this.material);
    this.points.frustumCulled = false;
    this.scene.add(this.points);
    this.capacity = cap;
  }

  /** `pxPerUnit`: drawing-buffer height [px] / (2 tan(fovY / 2)). */
  begin(maxCount, pxPerUnit) {
    this.ensure(Math.max(maxCount, 1));
    this.count = 0;
    this.material.uniforms.pxPerUnit.value = pxPerUnit;
  }

  /** Scene coordinates [m] of the agent's feet. */
  add(sx, sy, sz, color) {
    const i = this.count++, o = i * 3;
    const p = this.pos.array, c = this.color.array;
    p[o] = sx; p[o + 1] = sy; p[o + 2] = sz;
    c[o] = color.r; c[o + 1] = color.g; c[o + 2] = color.b;
  }

  end() {
    this.points.geometry.setDrawRange(0, this.count);
    for (const a of [this.pos, this.color]) { a.clearUpdateRanges(); a.addUpdateRange(0, this.count * 3); a.needsUpdate = true; }
    this.points.visible = this.count > 0;
  }
}
