// Trajectory trails: where each agent walked in the last `seconds` of simulated time, as a line
// fading from its colour (now) into the floor's (`seconds` ago). TrailBuffer (pure) keeps, per
// agent id, positions sampled from the crowd frames at least kTrailStep apart in simulated time,
// drops what is older than the window and agents not seen for as long, and starts afresh when time
// runs backwards (a replay seeked back); a jump longer than kTrailJump (a teleport, a floor
// change the frames skipped) breaks the line. Trails (three.js) draws them as one LineSegments
// with vertex colours, rebuilt after a received frame added a sample (at most every kTrailStep of
// simulated time: between samples nothing moves), into buffers reused while they are large enough.
// Scene coordinates: (x, z, −y).
import * as THREE from 'three';

export const kTrailSeconds = 10;  // [s] of simulated time shown
export const kTrailStep = 0.2;    // [s] between samples
export const kTrailJump = 5;      // [m] longer steps are not joined
export const kMaxTrailSegments = 100000;  // more would be drawn: every k-th sample joined instead

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
  constructor(scene, floorColour = 0xd8d4cc) {
    this.buffer = new TrailBuffer();
    this.floor = new THREE.Color(floorColour);
    this.geometry = new THREE.BufferGeometry();
    this.lines = new THREE.LineSegments(this.geometry, new THREE.LineBasicMaterial({ vertexColors: true }));
    this.lines.frustumCulled = false;
    this.lines.visible = false;
    this.lines.renderOrder = 1;
    scene.add(this.lines);
    this.segments = 0;
    this.tmp = new THREE.Color();
  }

  get enabled() { return this.lines.visible; }
  set enabled(on) { this.lines.visible = on; if (!on) this.buffer.clear(); }

  /** Each crowd frame (while enabled): `frame` as sources/frame.js, `t` its simulated time [s].
   * Returns whether the lines need a rebuild. */
  record(frame, t) {
    return this.enabled && this.buffer.record(frame.ids, frame.x, frame.y, frame.z, frame.count, t);
  }

  /** Rebuilds the lines; `colourOf(id)`: the agent's THREE.Color now. */
  rebuild(colourOf) {
    if (!this.enabled) return;
    let bound = 0;
    for (const a of this.buffer.agents.values()) bound += Math.max(a.len - 1, 0);
    bound = Math.min(bound, kMaxTrailSegments + this.buffer.agents.size);  // forEachSegment's cap
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
    });
    this.geometry.setDrawRange(0, this.segments * 2);
    for (const name of ['position', 'color']) {
      const attribute = this.geometry.attributes[name];
      attribute.clearUpdateRanges();
      attribute.addUpdateRange(0, o);  // only what is drawn goes to the GPU
      attribute.needsUpdate = true;
    }
  }
}
