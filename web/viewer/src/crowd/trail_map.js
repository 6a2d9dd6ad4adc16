// Trails of a large crowd drawn into a raster on the floor instead of as line segments: the
// software renderer spends about 0.4 µs per line segment per frame (docs/viewer.md, frame-rate
// table), so 10,000 agents' ten seconds of trails (50,000–100,000 segments) cost it 20–40 ms a
// frame, whatever the view. Here each new sample adds one short segment per agent to the raster, and
// drawing it is one textured plane whatever the crowd. The window is cut into kMapSlots slots of
// equal time; each pixel keeps its colour (RGB, sRGB) and, in alpha, the stamp of the slot it was
// last drawn in (1–255, the slot number modulo 255, plus one; 0: never drawn). The plane's shader
// shows a pixel by its age in slots — opaque in the newest, fainter in older ones, as the line
// trails fade into the floor, gone after kMapSlots — so what shows is the last `seconds` to within
// one slot, and nothing has to be erased as time passes (sweep() clears pixels old enough for their
// stamp to come round again). Flat worlds only (the plane lies at floor height). TrailRaster (pure):
// the raster, stamps and ages; TrailMap: its texture and plane.
// Ground (x, y) → raster column (x − minX)·ppm, row (y − minY)·ppm; scene (x, z, −y).
import * as THREE from 'three';

export const kMapSlots = 5;          // slots the window is cut into
export const kMapPxPerMetre = 10;    // finest raster resolution [px/m]
export const kMapMaxPx = 1024;       // largest raster side [px]

/** The raster layout for world `bounds` {minX, minY, maxX, maxY}: {nx, ny, ppm (px/m), minX, minY}. */
export function rasterLayout(bounds, maxPx = kMapMaxPx, finest = kMapPxPerMetre) {
  const w = Math.max(bounds.maxX - bounds.minX, 1), h = Math.max(bounds.maxY - bounds.minY, 1);
  const ppm = Math.min(finest, maxPx / Math.max(w, h));
  return { nx: Math.max(1, Math.ceil(w * ppm)), ny: Math.max(1, Math.ceil(h * ppm)), ppm, minX: bounds.minX, minY: bounds.minY };
}

/** The stamp (1–255) of slot number `slot` (⌊time / slot length⌋, any integer). */
export function stampOf(slot) {
  return (((slot % 255) + 255) % 255) + 1;
}

/** Age in slots of a pixel stamped `stamp` when the newest slot's stamp is `now` (0: the newest). */
export function stampAge(stamp, now) {
  return (((now - stamp) % 255) + 255) % 255;
}

/** Opacity of a pixel `age` slots old: from 1 (the newest) down to 0.15, none from `slots` on. */
export function slotOpacity(age, slots = kMapSlots) {
  return age >= slots ? 0 : 1 - (0.85 * age) / slots;
}

export class TrailRaster {
  constructor(bounds, maxPx = kMapMaxPx) {
    Object.assign(this, rasterLayout(bounds, maxPx));
    this.data = new Uint8Array(this.nx * this.ny * 4);
  }

  clear() { this.data.fill(0); }

  /** Draws the ground segment (ax, ay) → (bx, by) [m] in colour [r, g, b] (0–255, sRGB) stamped
   * `stamp`, two pixels wide (it stays visible when the plane is drawn smaller); clipped. */
  segment(ax, ay, bx, by, r, g, b, stamp) {
    const d = this.data, { nx, ny, ppm } = this;
    const x0 = (ax - this.minX) * ppm, y0 = (ay - this.minY) * ppm, x1 = (bx - this.minX) * ppm, y1 = (by - this.minY) * ppm;
    const steps = Math.max(1, Math.ceil(Math.max(Math.abs(x1 - x0), Math.abs(y1 - y0))));
    for (let s = 0; s <= steps; ++s) {
      const x = Math.floor(x0 + ((x1 - x0) * s) / steps), y = Math.floor(y0 + ((y1 - y0) * s) / steps);
      for (let k = 0; k < 3; ++k) {
        const px = x + (k === 1 ? 1 : 0), py = y + (k === 2 ? 1 : 0);
        if (px < 0 || py < 0 || px >= nx || py >= ny) continue;
        const o = (py * nx + px) * 4;
        d[o] = r; d[o + 1] = g; d[o + 2] = b; d[o + 3] = stamp;
      }
    }
  }

  /** Clears every pixel `slots` or more old at stamp `now` (before its stamp can come round). */
  sweep(now, slots = kMapSlots) {
    const d = this.data;
    for (let o = 3; o < d.length; o += 4) if (d[o] && stampAge(d[o], now) >= slots) d[o] = 0;
  }
}

const kVertex = `varying vec2 vUv;
void main() { vUv = uv; gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0); }`;
const kFragment = `uniform sampler2D map;
uniform float now;
uniform float slots;
varying vec2 vUv;
void main() {
  vec4 t = texture2D(map, vUv);
  float stamp = floor(t.a * 255.0 + 0.5);
  if (stamp < 0.5) discard;
  float age = mod(now - stamp + 255.0, 255.0);
  if (age >= slots) discard;
  gl_FragColor = vec4(t.rgb, 1.0 - 0.85 * age / slots);
}`;

/** The raster as a textured plane over the floor of a flat world (lifted as the line trails). */
export class TrailMap {
  constructor(scene, bounds, lift = 0.08) {
    this.raster = new TrailRaster(bounds);
    const { nx, ny, ppm } = this.raster;
    const w = nx / ppm, h = ny / ppm;
    this.texture = new THREE.DataTexture(this.raster.data, nx, ny, THREE.RGBAFormat);
    this.texture.magFilter = THREE.NearestFilter;  // stamps must not be blended
    this.texture.minFilter = THREE.NearestFilter;
    const plane = new THREE.PlaneGeometry(w, h);
    plane.rotateX(-Math.PI / 2);  // (u, v) = (0, 0) at world (minX, minY)
    plane.translate(bounds.minX + w / 2, (bounds.minZ || 0) + lift, -(bounds.minY + h / 2));
    this.material = new THREE.ShaderMaterial({
      uniforms: { map: { value: this.texture }, now: { value: 1 }, slots: { value: kMapSlots } },
      vertexShader: kVertex, fragmentShader: kFragment, transparent: true, depthWrite: false,
    });
    this.mesh = new THREE.Mesh(plane, this.material);
    this.mesh.name = 'trail-map';
    this.mesh.renderOrder = 1;
    this.mesh.visible = false;
    this.tmp = new THREE.Color();
    this.dirty = false;
    scene.add(this.mesh);
  }

  get visible() { return this.mesh.visible; }
  set visible(on) { this.mesh.visible = on; }

  clear() { this.raster.clear(); this.dirty = true; }

  /** A segment in `colour` (a THREE.Color, the renderer's linear values) stamped `stamp`. */
  segment(ax, ay, bx, by, colour, stamp) {
    const c = colour.getRGB(this.tmp, THREE.SRGBColorSpace);  // the shader writes what it reads
    this.raster.segment(ax, ay, bx, by, Math.round(c.r * 255), Math.round(c.g * 255), Math.round(c.b * 255), stamp);
    this.dirty = true;
  }

  /** The newest slot's stamp, for the shader; the raster uploaded when drawn into. */
  update(now) {
    this.material.uniforms.now.value = now;
    if (this.dirty) this.texture.needsUpdate = true;
    this.dirty = false;
  }
}
