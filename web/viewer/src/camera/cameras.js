// Camera modes. Plan: an orthographic camera straight down, north (world +y) up (left- or right-drag
// pans, the wheel zooms at the pointer); the default for a single-level world wider than
// kPlanDefaultSpan, where an oblique camera leaves most bodies a few pixels high. Orbit: three's
// OrbitControls around the world (drag rotate, wheel zoom, right-drag pan). fit() frames the whole
// world in the plan or orbit camera, in the part of the viewport the panels leave free (framing.js);
// until the person moves that camera, refit() frames it again when the panels or the window change;
// follow(fn) keeps the plan or orbit camera centred on what fn
// returns each frame (a selected agent, a group's centre) until it returns null. Walk: the camera follows behind the local avatar, which W/S or ↑/↓ move forward/back,
// A/D or ←/→ turn, Q/E strafe (Shift runs); dragging the mouse turns. The avatar is the viewer's
// own walking position (world x, y [m], yaw [rad]); once joined, main.js sends it as Move.
// In a multi-level world (`terrain`, the scenario's triangles) the avatar also has a height z [m]:
// it follows the walkable surface (floors, ramps, stairs; world/terrain.js stepOnTerrain), and
// both cameras take the heights into account (orbit: frames bounds.minZ … maxZ; walk: above z).
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { stepOnTerrain, nearestOnTerrain } from '../world/terrain.js';
import { freeRect, planFrame } from './framing.js';

export const kPlanDefaultSpan = 40;  // [m] a flat world wider or deeper than this opens in plan view
export const kModes = ['plan', 'orbit', 'walk'];

/** The camera a world opens with: plan for a single-level world wider than kPlanDefaultSpan,
 * orbit otherwise (small worlds read better in 3D; a plan view hides a lower floor). */
export function defaultMode(bounds, terrain) {
  const span = Math.max(bounds.maxX - bounds.minX, bounds.maxY - bounds.minY);
  return !terrain && span > kPlanDefaultSpan ? 'plan' : 'orbit';
}

/** Height [m] above the highest floor that the orbit fit keeps in view (bodies, walls, blocks). */
export const kFitHeadroom = 2;
const kFitMargin = 0.06;  // of the free rectangle, on each side

export class Cameras {
  /** `camera`: the perspective camera (orbit, walk); `bounds`: worldBounds(scenario); `terrain`:
   * scenario.terrain, or null in a flat world; `mode`: the first mode (defaultMode when omitted);
   * `panels`: returns the screen rectangles [px] ({left, top, right, bottom}) of the panels over
   * the canvas, which fit() keeps the world clear of. */
  constructor(camera, dom, bounds, terrain = null, mode = null, panels = () => []) {
    this.perspective = camera;
    this.dom = dom;
    this.orbit = new OrbitControls(camera, dom);
    this.orbit.enableDamping = true;
    this.orbit.maxPolarAngle = Math.PI * 0.49;
    this.ortho = new THREE.OrthographicCamera(-10, 10, 10, -10, 0.1, 5000);
    this.ortho.up.set(0, 0, -1);  // screen up = world +y (north)
    this.plan = new OrbitControls(this.ortho, dom);
    Object.assign(this.plan, { enableRotate: false, screenSpacePanning: true, zoomToCursor: true, minZoom: 0.2, maxZoom: 60 });
    this.plan.mouseButtons = { LEFT: THREE.MOUSE.PAN, MIDDLE: THREE.MOUSE.DOLLY, RIGHT: THREE.MOUSE.PAN };
    this.plan.touches = { ONE: THREE.TOUCH.PAN, TWO: THREE.TOUCH.DOLLY_PAN };
    const cx = (bounds.minX + bounds.maxX) / 2, cy = (bounds.minY + bounds.maxY) / 2;
    this.bounds = bounds;
    this.terrain = terrain && Array.isArray(terrain.vertices) && Array.isArray(terrain.walkable) ? terrain : null;
    this.following = null;
    this.panels = panels;
    // Which cameras show the world as fit() framed it (until the person moves them): refit() reframes those.
    this.fitted = { plan: false, orbit: false };
    this.plan.addEventListener('start', () => { this.fitted.plan = false; });
    this.orbit.addEventListener('start', () => { this.fitted.orbit = false; });
    this.fit('plan');
    this.fit('orbit');
    this.avatar = { x: cx, y: cy, z: 0, yaw: Math.PI / 2, moving: false, speed: 0, onTerrain: false };
    this.setMode(mode || defaultMode(bounds, this.terrain));
    this.keys = new Set();
    this.dragging = false;
    addEventListener('keydown', (e) => { if (!isTyping(e)) this.keys.add(e.code); });
    addEventListener('keyup', (e) => this.keys.delete(e.code));
    addEventListener('blur', () => this.keys.clear());
    dom.addEventListener('pointerdown', (e) => { if (this.mode === 'walk') { this.dragging = true; this.lastX = e.clientX; } });
    addEventListener('pointerup', () => { this.dragging = false; });
    addEventListener('pointermove', (e) => {
      if (this.mode === 'walk' && this.dragging) { this.avatar.yaw -= (e.clientX - this.lastX) * 0.005; this.lastX = e.clientX; }
    });
  }

  /** The camera of the current mode: orthographic in plan view, perspective otherwise. */
  get camera() { return this.mode === 'plan' ? this.ortho : this.perspective; }

  setMode(mode) {
    this.mode = mode;
    this.orbit.enabled = mode === 'orbit';
    this.plan.enabled = mode === 'plan';
  }

  /** The next mode after the current one (plan → orbit → walk → plan). */
  nextMode() { return kModes[(kModes.indexOf(this.mode) + 1) % kModes.length]; }

  /** Viewport size [px]. */
  viewport() {
    return this.dom.clientWidth && this.dom.clientHeight ? { w: this.dom.clientWidth, h: this.dom.clientHeight } : { w: innerWidth, h: innerHeight };
  }

  /** Frames the whole world in the plan camera ('plan') or the orbit camera ('orbit'); the current
   * mode's camera when `which` is omitted (walk: none). The world is drawn as large as fits in the
   * part of the viewport the panels leave free (framing.js freeRect), centred there, with 6 % of
   * that rectangle's size free on each side. */
  fit(which = this.mode) {
    const b = this.bounds;
    const cx = (b.minX + b.maxX) / 2, cy = (b.minY + b.maxY) / 2;
    const minZ = b.minZ ?? 0, maxZ = b.maxZ ?? 0;
    const { w, h } = this.viewport();
    if (which === 'plan') {
      const spanX = b.maxX - b.minX, spanY = b.maxY - b.minY;
      const rect = freeRect(w, h, this.panels(), Math.max(spanX, 4) / Math.max(spanY, 4));
      const f = planFrame(spanX, spanY, w, h, rect, kFitMargin);
      Object.assign(this.ortho, { left: -f.halfW, right: f.halfW, top: f.halfH, bottom: -f.halfH, zoom: 1 });
      this.ortho.position.set(cx + f.dx, maxZ + 200, -(cy + f.dy));
      this.plan.target.set(cx + f.dx, minZ, -(cy + f.dy));
      this.ortho.updateProjectionMatrix();
      this.plan.update();
      this.fitted.plan = true;
    } else if (which === 'orbit') {
      this.fitOrbit(w, h);
      this.fitted.orbit = true;
    }
  }

  /** The world's bounding box (up to kFitHeadroom above its highest floor) in the orbit camera:
   * from the south, 50° above the horizon, as large as fits in the free rectangle and centred in
   * it. A perspective picture's size is not linear in the distance, so the distance and the
   * sideways shift are found by iteration: project the box's corners, scale the distance by how
   * much too large or small their screen box is, shift by how far off centre it is. */
  fitOrbit(w, h) {
    const b = this.bounds;
    const minZ = b.minZ ?? 0, maxZ = (b.maxZ ?? 0) + kFitHeadroom;
    const cam = this.perspective;
    cam.aspect = w / h;
    cam.updateProjectionMatrix();
    const corners = [];
    for (const x of [b.minX, b.maxX]) for (const y of [b.minY, b.maxY]) for (const z of [minZ, maxZ]) corners.push(new THREE.Vector3(x, z, -y));
    const el = THREE.MathUtils.degToRad(50);
    const dir = new THREE.Vector3(0, Math.sin(el), Math.cos(el));
    const target = new THREE.Vector3((b.minX + b.maxX) / 2, (minZ + maxZ) / 2, -(b.minY + b.maxY) / 2);
    const r = Math.max(Math.hypot(b.maxX - b.minX, b.maxY - b.minY, maxZ - minZ) / 2, 5);
    const fov = THREE.MathUtils.degToRad(cam.fov);
    let d = r / Math.sin(Math.min(fov, 2 * Math.atan(Math.tan(fov / 2) * cam.aspect)) / 2);
    const v = new THREE.Vector3();
    const place = () => { cam.position.copy(target).addScaledVector(dir, d); cam.lookAt(target); cam.updateMatrixWorld(); };
    const screenBox = () => {
      let l = Infinity, t = Infinity, rr = -Infinity, bb = -Infinity;
      for (const c of corners) {
        v.copy(c).applyMatrix4(cam.matrixWorldInverse);
        if (v.z > -cam.near) return null;  // behind the camera
        v.applyMatrix4(cam.projectionMatrix);
        const x = (v.x + 1) / 2 * w, y = (1 - v.y) / 2 * h;
        l = Math.min(l, x); rr = Math.max(rr, x); t = Math.min(t, y); bb = Math.max(bb, y);
      }
      return { left: l, top: t, right: rr, bottom: bb };
    };
    place();
    const first = screenBox();
    const rect = freeRect(w, h, this.panels(), first ? (first.right - first.left) / Math.max(first.bottom - first.top, 1) : 1);
    const mx = (rect.right - rect.left) * kFitMargin, my = (rect.bottom - rect.top) * kFitMargin;
    const inner = { left: rect.left + mx, top: rect.top + my, right: rect.right - mx, bottom: rect.bottom - my };
    const right = new THREE.Vector3(), up = new THREE.Vector3();
    for (let k = 0; k < 60; ++k) {
      const s = screenBox();
      if (!s) { d *= 1.5; place(); continue; }
      const grow = Math.max((s.right - s.left) / (inner.right - inner.left), (s.bottom - s.top) / (inner.bottom - inner.top));
      const dx = (s.left + s.right - inner.left - inner.right) / 2, dy = (s.top + s.bottom - inner.top - inner.bottom) / 2;
      if (Math.abs(grow - 1) < 0.002 && Math.abs(dx) < 0.5 && Math.abs(dy) < 0.5) break;
      const mpp = 2 * d * Math.tan(fov / 2) / h;  // metres per pixel at the target's distance
      right.setFromMatrixColumn(cam.matrixWorld, 0);
      up.setFromMatrixColumn(cam.matrixWorld, 1);
      target.addScaledVector(right, dx * mpp).addScaledVector(up, -dy * mpp);
      d *= 1 + (grow - 1) * 0.8;
      place();
    }
    // Never larger than the rectangle: the last steps may leave it a pixel over.
    for (let k = 0; k < 50; ++k) {
      const s = screenBox();
      if (s && s.left >= rect.left && s.right <= rect.right && s.top >= rect.top && s.bottom <= rect.bottom) break;
      d *= 1.02;
      place();
    }
    this.orbit.target.copy(target);
    this.orbit.update();
  }

  /** Frames again each camera that still shows the world as fit() left it (the panels or the
   * window changed: the free part of the viewport moved). */
  refit() {
    for (const which of ['plan', 'orbit']) if (this.fitted[which]) this.fit(which);
  }

  /** Viewport resized: the plan camera keeps its height in metres and widens or narrows; a camera
   * still as fit() framed it is framed again. */
  resize(aspect) {
    const halfH = this.ortho.top;
    Object.assign(this.ortho, { left: -halfH * aspect, right: halfH * aspect });
    this.ortho.updateProjectionMatrix();
    this.refit();
  }

  /** Keeps the plan or orbit camera centred on `fn()` (world {x, y, z} [m]) each frame until it
   * returns null; follow(null) stops. */
  follow(fn) {
    this.following = fn;
    if (fn) this.fitted.plan = this.fitted.orbit = false;
  }

  /** Brings the plan or orbit camera within `metres` of what it looks at (the plan view `metres`
   * high, the orbit camera `metres` from its target) when it is farther: following someone from a
   * view of the whole world would show nothing move. */
  closeIn(metres = 24) {
    if (this.mode === 'plan') {
      const high = (this.ortho.top - this.ortho.bottom) / this.ortho.zoom;
      if (high > metres) {
        this.ortho.zoom = (this.ortho.top - this.ortho.bottom) / metres;
        this.ortho.updateProjectionMatrix();
        this.plan.update();
      }
    } else if (this.mode === 'orbit') {
      const c = this.perspective.position, t = this.orbit.target;
      const d = c.distanceTo(t);
      if (d > metres) { c.sub(t).multiplyScalar(metres / d).add(t); this.orbit.update(); }
    }
  }

  /** Moves the current controls' target (and the camera with it) onto the followed point. */
  applyFollow() {
    if (!this.following || this.mode === 'walk') return;
    const p = this.following();
    if (!p) { this.following = null; if (this.onFollowEnd) this.onFollowEnd(); return; }  // it left
    const controls = this.mode === 'plan' ? this.plan : this.orbit;
    const cam = this.camera;
    const dx = p.x - controls.target.x, dz = -p.y - controls.target.z;
    const dy = this.mode === 'plan' ? 0 : (p.z || 0) + 0.9 - controls.target.y;
    controls.target.x += dx; controls.target.y += dy; controls.target.z += dz;
    cam.position.x += dx; cam.position.y += dy; cam.position.z += dz;
  }

  /** Metres per screen pixel at the plan camera's zoom (for pick tolerances and marker sizes). */
  planMetresPerPixel(viewportHeight) {
    return (this.ortho.top - this.ortho.bottom) / this.ortho.zoom / viewportHeight;
  }

  /** Places the avatar (e.g. where the camera looks) before walking; in a multi-level world on the
   * walkable surface under (x, y) nearest height `nearZ` [m] (at nearZ when there is none). */
  placeAvatar(x, y, yaw, nearZ = 0) {
    // On a multi-level world, on the floor nearest the point asked for (the view's centre may lie
    // over a stairwell or outside the building).
    const p = this.terrain ? nearestOnTerrain(this.terrain, x, y, nearZ) : null;
    if (p) { Object.assign(this.avatar, { x: p.x, y: p.y, yaw, z: p.z, onTerrain: true }); return; }
    Object.assign(this.avatar, { x, y, yaw, z: this.terrain ? nearZ : 0, onTerrain: false });
  }

  /** Moves the avatar to ground point (nx, ny): freely on a flat world; over the terrain by
   * stepOnTerrain, sliding along one axis when the whole move is refused (an edge, a drop). */
  moveAvatar(nx, ny) {
    const a = this.avatar;
    if (!this.terrain) { a.x = nx; a.y = ny; return; }
    const s = stepOnTerrain(this.terrain, a.x, a.y, a.z, nx, ny, a.onTerrain)
      || stepOnTerrain(this.terrain, a.x, a.y, a.z, nx, a.y, a.onTerrain)
      || stepOnTerrain(this.terrain, a.x, a.y, a.z, a.x, ny, a.onTerrain);
    if (s) Object.assign(a, s);
  }

  /** Per frame: moves the avatar from the keys (walk mode) and the camera. */
  update(dt) {
    this.applyFollow();
    if (this.mode === 'orbit') { this.orbit.update(); this.avatar.moving = false; return; }
    if (this.mode === 'plan') { this.plan.update(); this.avatar.moving = false; return; }
    this.fitted.orbit = false;  // the walk camera moves the perspective camera the orbit view shares
    const k = this.keys;
    const run = k.has('ShiftLeft') || k.has('ShiftRight') ? 2.2 : 1;
    const fwd = (k.has('KeyW') || k.has('ArrowUp') ? 1 : 0) - (k.has('KeyS') || k.has('ArrowDown') ? 1 : 0);
    const turn = (k.has('KeyA') || k.has('ArrowLeft') ? 1 : 0) - (k.has('KeyD') || k.has('ArrowRight') ? 1 : 0);
    const strafe = (k.has('KeyE') ? 1 : 0) - (k.has('KeyQ') ? 1 : 0);
    const a = this.avatar;
    a.yaw += turn * 1.8 * dt;
    const v = 1.4 * run;
    const dx = Math.cos(a.yaw) * fwd + Math.sin(a.yaw) * strafe;
    const dy = Math.sin(a.yaw) * fwd - Math.cos(a.yaw) * strafe;
    a.moving = fwd !== 0 || strafe !== 0;
    a.speed = a.moving ? v : 0;
    this.moveAvatar(Math.min(Math.max(a.x + dx * v * dt, this.bounds.minX), this.bounds.maxX),
      Math.min(Math.max(a.y + dy * v * dt, this.bounds.minY), this.bounds.maxY));
    const az = a.z || 0;
    const back = 3.6, height = 2.3;
    const cam = this.perspective;
    const tx = a.x - Math.cos(a.yaw) * back, ty = a.y - Math.sin(a.yaw) * back;
    cam.position.lerp(new THREE.Vector3(tx, az + height, -ty), Math.min(1, dt * 8));
    cam.lookAt(a.x + Math.cos(a.yaw) * 3, az + 1.2, -(a.y + Math.sin(a.yaw) * 3));
  }

  /** Plan view centred on world (x, y), `metresHigh` [m] of the world from the top of the
   * viewport to the bottom. */
  planAt(x, y, metresHigh) {
    this.setMode('plan');
    this.fitted.plan = false;
    this.ortho.zoom = (this.ortho.top - this.ortho.bottom) / metresHigh;
    this.ortho.updateProjectionMatrix();
    this.plan.target.set(x, this.plan.target.y, -y);
    this.ortho.position.set(x, this.ortho.position.y, -y);
    this.plan.update();
  }

  /** Looks at world (x, y) from a given distance (used by the benchmark's screenshots). */
  lookAt(x, y, distance, height) {
    this.setMode('orbit');
    this.fitted.orbit = false;
    this.orbit.target.set(x, 1, -y);
    this.perspective.position.set(x + distance * 0.6, height, -y + distance * 0.8);
    this.orbit.update();
  }
}

function isTyping(e) {
  const t = e.target;
  return t && (t.tagName === 'INPUT' || t.tagName === 'TEXTAREA');
}
