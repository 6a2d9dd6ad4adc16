// Camera modes. Orbit: three's OrbitControls around the world (drag rotate, wheel zoom, right-drag
// pan). Walk: the camera follows behind the local avatar, which W/S or ↑/↓ move forward/back,
// A/D or ←/→ turn, Q/E strafe (Shift runs); dragging the mouse turns. The avatar is the viewer's
// own walking position (world x, y [m], yaw [rad]); once joined, main.js sends it as Move.
// In a multi-level world (`terrain`, the scenario's triangles) the avatar also has a height z [m]:
// it follows the walkable surface (floors, ramps, stairs; world/terrain.js stepOnTerrain), and
// both cameras take the heights into account (orbit: frames bounds.minZ … maxZ; walk: above z).
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { terrainHeightAt, stepOnTerrain } from '../world/terrain.js';

export class Cameras {
  /** `bounds`: worldBounds(scenario); `terrain`: scenario.terrain, or null in a flat world. */
  constructor(camera, dom, bounds, terrain = null) {
    this.camera = camera;
    this.dom = dom;
    this.mode = 'orbit';
    this.orbit = new OrbitControls(camera, dom);
    this.orbit.enableDamping = true;
    this.orbit.maxPolarAngle = Math.PI * 0.49;
    const cx = (bounds.minX + bounds.maxX) / 2, cy = (bounds.minY + bounds.maxY) / 2;
    const minZ = bounds.minZ ?? 0, maxZ = bounds.maxZ ?? 0;
    const span = Math.max(bounds.maxX - bounds.minX, bounds.maxY - bounds.minY, maxZ - minZ, 10);
    const cz = (minZ + maxZ) / 2;
    this.bounds = bounds;
    this.terrain = terrain && Array.isArray(terrain.vertices) && Array.isArray(terrain.walkable) ? terrain : null;
    this.orbit.target.set(cx, cz, -cy);
    camera.position.set(cx, cz + span * 0.45 + (maxZ - minZ) / 2, -cy + span * 0.6);
    this.orbit.update();
    this.avatar = { x: cx, y: cy, z: 0, yaw: Math.PI / 2, moving: false, speed: 0, onTerrain: false };
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

  /** Places the avatar (e.g. where the camera looks) before walking; in a multi-level world on the
   * walkable surface under (x, y) nearest height `nearZ` [m] (at nearZ when there is none). */
  placeAvatar(x, y, yaw, nearZ = 0) {
    const z = this.terrain ? terrainHeightAt(this.terrain, x, y, nearZ) : null;
    Object.assign(this.avatar, { x, y, yaw, z: z ?? (this.terrain ? nearZ : 0), onTerrain: z !== null });
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
    this.moveAvatar(Math.min(Math.max(a.x + dx * v * dt, this.bounds.minX), this.bounds.maxX),
      Math.min(Math.max(a.y + dy * v * dt, this.bounds.minY), this.bounds.maxY));
    const az = a.z || 0;
    const back = 3.6, height = 2.3;
    const cam = this.camera;
    const tx = a.x - Math.cos(a.yaw) * back, ty = a.y - Math.sin(a.yaw) * back;
    cam.position.lerp(new THREE.Vector3(tx, az + height, -ty), Math.min(1, dt * 8));
    cam.lookAt(a.x + Math.cos(a.yaw) * 3, az + 1.2, -(a.y + Math.sin(a.yaw) * 3));
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
