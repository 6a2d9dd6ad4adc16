// Trajectory trails: where each agent walked in the last `seconds` of simulated time, as a line
// fading from its colour (now) into the floor's (`seconds` ago). TrailBuffer (pure) keeps, per
// agent id, positions sampled from the crowd frames at least kTrailStep apart in simulated time,
// drops what is older than the window and agents not seen for as long, and starts afresh when time
// runs backwards (a replay seeked back); a jump longer than kTrailJump (a teleport, a floor
// change the frames skipped) breaks the line. Trails (three.js) draws them as one LineSegments
// with vertex colours, rebuilt after a received frame added a sample (at most every kTrailStep of
// simulated time: between samples nothing moves), into buffers reused while they are large enough.
// A crowd whose trails would take more than kLineBudget segments in a flat world is drawn into
// a raster on the floor instead (trail_map.js: each sample adds one segment per agent; drawing costs
// the same whatever the crowd), the software renderer's cost being per line segment.
// Scene coordinates: (x, z, −y).
import * as THREE from 'three';
import { TrailMap, kMapSlots, stampOf } from './trail_map.js';

export const kTrailSeconds = 10;  // [s] of simulated time shown
export const kTrailStep = 0.2;    // [s] between samples
export const kTrailJump = 5;      // [m] longer steps are not joined
export const kMaxTrailSegments = 100000;  // more would be drawn: every k-th sample joined instead
export const kLineBudget = 20000;  // more segments (a window's worth) in a flat world: the raster map

export class TrailBuffer {
  constructor(seconds = kTrailSeconds, step = kTrailStep) {
    this.seconds = seconds;
    this.step = step;
    this.cap = Math.ceil(seconds / step) + 2;
    this.agents = new Map();  // id → {t: Float64Array, p: Float32Array (x, y, z), head, len, last}
    this.time = -Infinity;
  }

  clear() { this.agents.clear(); this.time = -Infinity; }

  /** One crowd frame at simulated time `t` [s]: ids, x, y, z (world metres) of `count` agents.
   * Returns whether it changed what forEachSegment gives (a sample added or dropped, time back). */
  record(ids, x, y, z, count, t) {
    let changed = t < this.time || this.agents.size === 0;
    if (t < this.time) this.clear();
    this.time = t;
    for (let i = 0; i < count; ++i) {
      let a = this.agents.get(ids[i]);
      if (!a) { a = { t: new Float64Array(this.cap), p: new Float32Array(this.cap * 3), head: 0, len: 0, last: -Infinity }; this.agents.set(ids[i], a); }
      if (t - a.last < this.step * 0.999 && a.len) continue;
      changed = true;
      a.last = t;
      a.t[a.head] = t;
      a.p[a.head * 3] = x[i]; a.p[a.head * 3 + 1] = y[i]; a.p[a.head * 3 + 2] = z[i];
      a.head = (a.head + 1) % this.cap;
      a.len = Math.min(a.len + 1, this.cap);
    }
    for (const [id, a] of this.agents) if (t - a.last > this.seconds) { this.agents.delete(id); changed = true; }
    return changed;
  }

  /** Calls fn(id, ax, ay, az, bx, by, bz, ageA, ageB) for each segment within the window, oldest
   * first per agent (ages [s] before the latest time, ≥ 0). Returns the number of segments. With
   * more than `maxSegments` (a huge crowd), every stride-th sample is joined instead, stride the
   * least that keeps them under it, the newest always included: the same trails, coarser. */
  forEachSegment(fn, maxSegments = kMaxTrailSegments) {
    let n = 0, total = 0;
    for (const a of this.agents.values()) total += Math.max(a.len - 1, 0);
    const stride = Math.max(1, Math.ceil(total / maxSegments));
    for (const [id, a] of this.agents) {
      let prev = -1;
      for (let k = a.len - 1; k >= 0; --k) {
        if (k % stride !== 0) continue;
        const j = (a.head - 1 - k + this.cap * 2) % this.cap;
        const age = this.time - a.t[j];
        if (age > this.seconds) continue;
        if (prev >= 0) {
          const p = a.p;
          const ax = p[prev * 3], ay = p[prev * 3 + 1], az = p[prev * 3 + 2], bx = p[j * 3], by = p[j * 3 + 1], bz = p[j * 3 + 2];
          if (Math.hypot(bx - ax, by - ay, bz - az) <= kTrailJump) { fn(id, ax, ay, az, bx, by, bz, this.time - a.t[prev], age); n++; }
        }
        prev = j;
      }
    }
    return n;
  }
}

export class Trails {
  /** `bounds`: worldBounds of the world (its floor carries the raster map when flat); none: lines only. */
  constructor(scene, floorColour = 0xd8d4cc, bounds = null) {
    this.scene = scene;
    this.bounds = bounds;
    this.map = null;       // the raster map (TrailMap) once the crowd needs it
    this.useMap = false;   // drawing into the map now (until the trails are turned off)
    this.slot = -Infinity; // the map's newest slot: ⌊time / slot length⌋
    this.mapSegments = 0;  // segments drawn into the map
    this.colourOf = null;  // the last rebuild's colours, for the segments the map draws as frames come
    this.buffer = new TrailBuffer();
    this.floor = new THREE.Color(floorColour);
    this.geometry = new THREE.BufferGeometry();
    this.lines = new THREE.LineSegments(this.geometry, new THREE.LineBasicMaterial({ vertexColors: true }));
    this.lines.frustumCulled = false;
    this.lines.visible = false;
    this.lines.renderOrder = 1;
    scene.add(this.lines);
    this.segments = 0;
    this.maxSegments = kMaxTrailSegments;
    this.tmp = new THREE.Color();
  }

  get enabled() { return this.lines.visible; }
  set enabled(on) {
    this.lines.visible = on;
    if (on) return;
    this.buffer.clear();
    this.useMap = false;
    this.slot = -Infinity;
    if (this.map) this.map.visible = false;
  }

  /** 'map' (rasters on the floor) or 'lines'. */
  get mode() { return this.useMap ? 'map' : 'lines'; }

  /** Each crowd frame (while enabled): `frame` as sources/frame.js, `t` its simulated time [s].
   * Returns whether the lines (or the map's textures) need a rebuild. */
  record(frame, t) {
    if (!this.enabled) return false;
    const changed = this.buffer.record(frame.ids, frame.x, frame.y, frame.z, frame.count, t);
    if (!this.useMap && this.wantsMap()) this.startMap();
    else if (this.useMap && changed) this.drawNewSegments();
    return changed;
  }

  /** A flat world and more than kLineBudget segments in a window's worth of samples. */
  wantsMap() {
    const b = this.bounds;
    return !!b && b.minZ === b.maxZ && this.buffer.agents.size * (this.buffer.cap - 1) > kLineBudget;
  }

  get slotSeconds() { return this.buffer.seconds / kMapSlots; }

  /** Moves the map's newest slot to the buffer's time: time gone back, or a stamp about to come
   * round, clears the raster; every 100 slots pixels too old to show are swept. */
  advanceSlot() {
    const now = Math.floor(this.buffer.time / this.slotSeconds);
    if (now === this.slot) return;
    if (now < this.slot || now - this.slot >= 255 - kMapSlots) this.map.clear();
    else if (now % 100 === 0) this.map.raster.sweep(stampOf(now));
    this.slot = now;
  }

  /** Switches to the map, drawing the trails so far stamped with the slots of their times. */
  startMap() {
    if (!this.map) this.map = new TrailMap(this.scene, this.bounds);
    this.useMap = true;
    this.map.clear();
    this.slot = -Infinity;
    this.advanceSlot();
    this.map.visible = true;
    this.geometry.setDrawRange(0, 0);
    this.segments = 0;
    const P = this.slotSeconds, colour = this.colourFn();
    this.mapSegments = 0;
    this.buffer.forEachSegment((id, ax, ay, az, bx, by, bz, ageA, ageB) => {
      const k = Math.floor((this.buffer.time - ageB) / P);
      if (this.slot - k >= kMapSlots) return;
      this.map.segment(ax, ay, bx, by, colour(id), stampOf(k));
      this.mapSegments++;
    }, Infinity);
  }

  colourFn() {
    return this.colourOf || (() => this.tmp.setRGB(0.6, 0.6, 0.6));
  }

  /** The segments the latest frame's samples added, stamped with the newest slot. */
  drawNewSegments() {
    this.advanceSlot();
    const b = this.buffer, t = b.time, cap = b.cap, colour = this.colourFn(), stamp = stampOf(this.slot);
    for (const [id, a] of b.agents) {
      if (a.last !== t || a.len < 2) continue;
      const j = (a.head - 1 + cap) % cap, i = (a.head - 2 + cap) % cap, p = a.p;
      if (Math.hypot(p[j * 3] - p[i * 3], p[j * 3 + 1] - p[i * 3 + 1], p[j * 3 + 2] - p[i * 3 + 2]) > kTrailJump) continue;
      this.map.segment(p[i * 3], p[i * 3 + 1], p[j * 3], p[j * 3 + 1], colour(id), stamp);
      this.mapSegments++;
    }
  }

  /** Rebuilds the lines, or uploads the map's rasters; `colourOf(id)`: the agent's THREE.Color now. */
  rebuild(colourOf) {
    if (!this.enabled) return;
    this.colourOf = colourOf;
    if (this.useMap) {
      this.map.update(stampOf(this.slot));
      return;
    }
    let bound = 0;
    for (const a of this.buffer.agents.values()) bound += Math.max(a.len - 1, 0);
    bound = Math.min(bound, this.maxSegments + this.buffer.agents.size);  // forEachSegment's cap
    if (!this.pos || this.pos.length < bound * 6) {
      this.pos = new Float32Array(Math.ceil(bound * 1.5) * 6 + 6);
      this.col = new Float32Array(this.pos.length);
      this.geometry.setAttribute('position', new THREE.BufferAttribute(this.pos, 3));
      this.geometry.setAttribute('color', new THREE.BufferAttribute(this.col, 3));
    }
    const pos = this.pos, col = this.col;
    const s = this.buffer.seconds, c = this.tmp;
    let o = 0;
    this.segments = this.buffer.forEachSegment((id, ax, ay, az, bx, by, bz, ageA, ageB) => {
      pos[o] = ax; pos[o + 1] = az + 0.08; pos[o + 2] = -ay; pos[o + 3] = bx; pos[o + 4] = bz + 0.08; pos[o + 5] = -by;
      const base = colourOf(id);
      c.copy(base).lerp(this.floor, Math.min(ageA / s, 1) * 0.85);
      col[o] = c.r; col[o + 1] = c.g; col[o + 2] = c.b;
      c.copy(base).lerp(this.floor, Math.min(ageB / s, 1) * 0.85);
      col[o + 3] = c.r; col[o + 4] = c.g; col[o + 5] = c.b;
      o += 6;
    }, this.maxSegments);
    this.geometry.setDrawRange(0, this.segments * 2);
    for (const name of ['position', 'color']) {
      const attribute = this.geometry.attributes[name];
      attribute.clearUpdateRanges();
      attribute.addUpdateRange(0, o);  // only what is drawn goes to the GPU
      attribute.needsUpdate = true;
    }
  }
}
