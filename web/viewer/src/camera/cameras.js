// Camera modes. Orbit: three's OrbitControls around the world (drag rotate, wheel zoom, right-drag
// pan). Walk: the camera follows behind the local avatar, which W/S or ↑/↓ move forward/back,
// A/D or ←/→ turn, Q/E strafe (Shift runs); dragging the mouse turns. The avatar is the viewer's
// own walking position (world x, y [m], yaw [rad]); once joined, main.js sends it as Move.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

export class Cameras {
  constructor(camera, dom, bounds) {
    this.camera = camera;
    this.dom = dom;
    this.mode = 'orbit';
    this.orbit = new OrbitControls(camera, dom);
    this.orbit.enableDamping = true;
    this.orbit.maxPolarAngle = Math.PI * 0.49;
    const cx = (bounds.minX + bounds.maxX) / 2, cy = (bounds.minY + bounds.maxY) / 2;
    const span = Math.max(bounds.maxX - bounds.minX, bounds.maxY - bounds.minY, 10);
    this.bounds = bounds;
    this.orbit.target.set(cx, 0, -cy);
    camera.position.set(cx, span * 0.45, -cy + span * 0.6);
    this.orbit.update();
    this.avatar = { x: cx, y: cy, yaw: Math.PI / 2, moving: false, speed: 0 };
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

  setMode(mode) {
    this.mode = mode;
    this.orbit.enabled = mode === 'orbit';
  }

  /** Places the avatar (e.g. where the camera looks) before walking. */
  placeAvatar(x, y, yaw) { Object.assign(this.avatar, { x, y, yaw }); }

  /** Per frame: moves the avatar from the keys (walk mode) and the camera. */
  update(dt) {
    if (this.mode === 'orbit') { this.orbit.update(); this.avatar.moving = false; return; }
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
    a.x = Math.min(Math.max(a.x + dx * v * dt, this.bounds.minX), this.bounds.maxX);
    a.y = Math.min(Math.max(a.y + dy * v * dt, this.bounds.minY), this.bounds.maxY);
    const back = 3.6, height = 2.3;
    const cam = this.camera;
    const tx = a.x - Math.cos(a.yaw) * back, ty = a.y - Math.sin(a.yaw) * back;
    cam.position.lerp(new THREE.Vector3(tx, height, -ty), Math.min(1, dt * 8));
    cam.lookAt(a.x + Math.cos(a.yaw) * 3, 1.2, -(a.y + Math.sin(a.yaw) * 3));
  }

  /** Looks at world (x, y) from a given distance (used by the benchmark's screenshots). */
  lookAt(x, y, distance, height) {
    this.setMode('orbit');
    this.orbit.target.set(x, 1, -y);
    this.camera.position.set(x + distance * 0.6, height, -y + distance * 0.8);
    this.orbit.update();
  }
}

function isTyping(e) {
  const t = e.target;
  return t && (t.tagName === 'INPUT' || t.tagName === 'TEXTAREA');
}
