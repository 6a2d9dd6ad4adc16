// The crowd in plan view (an orthographic camera straight down): every agent one disc of a body's
// width — in its colour, with a dark rim and a white wedge towards its heading — never smaller than
// kMinDiscPx, so a zoomed-out world still shows each person. On a multi-level world the rim of
// those on an upper floor (kUpperFloor above the lowest floor) is white: the plan flattens the floors. One point sprite per agent in one
// plain geometry, one draw call (as dots.js); the bodies, billboards and dots are not drawn then.
import * as THREE from 'three';

export const kDiscDiameter = 0.5;  // [m] a body's width seen from above (shoulders)
export const kMinDiscPx = 6;       // [px] of the drawing buffer
export const kUpperFloor = 1.2;    // [m] above the lowest floor: on an upper floor (a step is at most 0.35 m)

const vertexShader = `
attribute vec3 iColor;
attribute float iYaw;
attribute float iUpper;   // 1: on an upper floor (a white rim)
uniform float pxPerMetre; // drawing-buffer pixels per world metre
uniform float diameter;   // [m]
uniform float minPx;
varying vec3 vColor;
varying vec2 vDir;
varying float vUpper;
void main() {
  vUpper = iUpper;
  gl_PointSize = max(minPx, diameter * pxPerMetre);
  vColor = iColor;
  vDir = vec2(cos(iYaw), -sin(iYaw)); // gl_PointCoord's y grows downwards; screen up is world +y
  gl_Position = projectionMatrix * viewMatrix * vec4(position, 1.0);
}`;

const fragmentShader = `
varying vec3 vColor;
varying vec2 vDir;
varying float vUpper;
void main() {
  vec2 p = (gl_PointCoord - vec2(0.5)) * 2.0;
  float r2 = dot(p, p);
  if (r2 > 1.0) discard;
  float ahead = dot(p, vDir);
  float side = abs(p.x * vDir.y - p.y * vDir.x);
  vec3 rim = vUpper > 0.5 ? vec3(1.0) : vColor * 0.55;  // white: on an upper floor
  vec3 c = r2 > 0.62 ? rim : vColor;                     // rim
  if (ahead > 0.2 && side < (0.95 - ahead) * 0.45) c = mix(c, vec3(1.0), 0.85); // heading wedge
  gl_FragColor = vec4(c, 1.0);
  #include <colorspace_fragment>
}`;

export class PlanDiscs {
  constructor(scene) {
    this.scene = scene;
    this.material = new THREE.ShaderMaterial({
      uniforms: { pxPerMetre: { value: 10 }, diameter: { value: kDiscDiameter }, minPx: { value: kMinDiscPx } },
      vertexShader, fragmentShader,
    });
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
    this.yaw = new THREE.BufferAttribute(new Float32Array(cap), 1).setUsage(THREE.DynamicDrawUsage);
    this.upper = new THREE.BufferAttribute(new Float32Array(cap), 1).setUsage(THREE.DynamicDrawUsage);
    g.setAttribute('position', this.pos);
    g.setAttribute('iUpper', this.upper);
    g.setAttribute('iColor', this.color);
    g.setAttribute('iYaw', this.yaw);
    if (this.points) { this.scene.remove(this.points); this.points.geometry.dispose(); }
    this.points = new THREE.Points(g, this.material);
    this.points.frustumCulled = false;
    this.points.renderOrder = 2;
    this.scene.add(this.points);
    this.capacity = cap;
  }

  /** `pxPerMetre`: drawing-buffer pixels per world metre at the plan camera's zoom. */
  begin(maxCount, pxPerMetre) {
    this.ensure(Math.max(maxCount, 1));
    this.count = 0;
    this.upperCount = 0;
    this.material.uniforms.pxPerMetre.value = pxPerMetre;
  }

  /** Scene coordinates [m] of the agent's feet; `yaw` [rad] world heading (0 = +x, counter-clockwise);
   * `upper`: on an upper floor of a multi-level world (drawn with a white rim). */
  add(sx, sy, sz, yaw, color, upper = false) {
    const i = this.count++, o = i * 3;
    const p = this.pos.array, c = this.color.array;
    p[o] = sx; p[o + 1] = sy + 0.15; p[o + 2] = sz;
    c[o] = color.r; c[o + 1] = color.g; c[o + 2] = color.b;
    this.yaw.array[i] = yaw;
    this.upper.array[i] = upper ? 1 : 0;
    if (upper) this.upperCount++;
  }

  end() {
    if (!this.points) this.ensure(1);
    this.points.geometry.setDrawRange(0, this.count);
    for (const a of [this.pos, this.color, this.yaw, this.upper]) {
      a.clearUpdateRanges(); a.addUpdateRange(0, this.count * a.itemSize); a.needsUpdate = true;
    }
    this.points.visible = this.count > 0;
  }
}
