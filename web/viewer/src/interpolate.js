// Frame interpolation — pure, no three.js. Reads crowd frames as they arrive (10–25 Hz, whole
// crowd the client sees: ids, positions, yaw, clip, phase, tier, near joints) and writes, for any
// display time, smooth per-agent positions, yaw (shortest arc) and animation phase:
//   position/yaw: from where the agent was displayed when the frame arrived to the frame's value,
//     over one measured frame interval (one frame of latency, no jumps);
//   phase: advanced locally at a rate estimated from successive received phases (the server sends
//     clip and phase only every X frames: the animation granularity factor), nudged towards each
//     received phase, snapped when the clip changes or the error is large.
// Frame layout (what every source emits, see sources/frame.js): {count, ids, tier, x, y, z, yaw,
// clip, phase, joints: Map id → Float32Array (near agents only)}.

const kTwoPi = Math.PI * 2;
const kTeleport = 5;  // [m] farther than this between frames: snap instead of gliding
const kJumpSeconds = 2;  // [s] of simulated time between two frames: a replay's seek, not walking
export const kStrideCycle = 1.4;  // [m] ground covered by one walk cycle (two steps) of the bundled walk

/** Signed smallest difference b − a of two angles [rad], in [−π, π). */
export function angleDelta(a, b) {
  let d = (b - a) % kTwoPi;
  if (d < -Math.PI) d += kTwoPi;
  if (d >= Math.PI) d -= kTwoPi;
  return d;
}

/** Forward distance from phase a to phase b on the unit loop, in [0, 1). */
export function phaseForward(a, b) {
  let d = (b - a) % 1;
  if (d < 0) d += 1;
  return d;
}

function signedPhase(a, b) {
  const d = phaseForward(a, b);
  return d >= 0.5 ? d - 1 : d;
}

export class CrowdState {
  /** `clips`: [{duration [s], loops}] indexed by clip id (world description); `interval`: the
   * expected frame interval [s] until it is measured. */
  constructor(clips = [], interval = 0.1) {
    this.clips = clips;
    this.interval = interval;
    this.count = 0;
    this.index = new Map();  // id → slot
    this.lastFrameAt = -1;
    this.lastAdvance = 0;
    this.frames = 0;
    this.dt = 0;  // simulated seconds a tick (the world description's dt; 0: unknown, speeds by wall time)
    this.alloc(0);
  }

  setClips(clips) { this.clips = clips; }

  alloc(n) {
    this.ids = new Uint32Array(n);
    this.tier = new Uint8Array(n);
    this.clip = new Uint16Array(n);
    this.fromX = new Float32Array(n); this.fromY = new Float32Array(n); this.fromZ = new Float32Array(n);
    this.fromYaw = new Float32Array(n);
    this.toX = new Float32Array(n); this.toY = new Float32Array(n); this.toZ = new Float32Array(n);
    this.toYaw = new Float32Array(n);
    this.x = new Float32Array(n); this.y = new Float32Array(n); this.z = new Float32Array(n);
    this.yaw = new Float32Array(n);
    this.phase = new Float32Array(n);
    this.rate = new Float32Array(n);       // phase units per second
    this.recvPhase = new Float32Array(n);  // last received phase
    this.recvAt = new Float64Array(n);     // when it changed last [s]
    this.speed = new Float32Array(n);      // ground speed estimate [m/s]
    this.joints = new Map();
  }

  clipInfo(c) {
    const info = this.clips[c];
    return { duration: info && info.duration > 0 ? info.duration : 1, loops: info ? info.loops !== false : true };
  }

  /** Takes a new frame received at local time `now` [s]. A frame of the same simulated tick as the
   * one before (a paused replay sends the same moment again) keeps every agent's speed estimate:
   * no simulated time passed, so standing still says nothing about how fast anyone walks. */
  applyFrame(frame, now) {
    this.advance(now);
    const sameMoment = this.frames > 0 && frame.simTick === this.lastSimTick;
    // Simulated seconds since the last frame, when the world's dt is known (a replay played faster
    // or slower, or frames late, then still give walking speeds); a replay's jump (back, or more than
    // kJumpSeconds on) says nothing about anyone's speed: they start again from 0.
    const simGap = this.frames > 0 && this.dt > 0 && Number.isFinite(frame.simTick) && Number.isFinite(this.lastSimTick)
      ? (frame.simTick - this.lastSimTick) * this.dt : NaN;
    const jumped = simGap < 0 || simGap > kJumpSeconds;
    this.lastSimTick = frame.simTick;
    if (this.lastFrameAt >= 0) {
      const gap = now - this.lastFrameAt;
      if (gap > 0.005 && gap < 2) this.interval = this.frames < 2 ? gap : this.interval * 0.8 + gap * 0.2;
    }
    this.lastFrameAt = now;
    this.frames++;
    const old = {
      index: this.index, x: this.x, y: this.y, z: this.z, yaw: this.yaw, phase: this.phase, rate: this.rate,
      clip: this.clip, recvPhase: this.recvPhase, recvAt: this.recvAt, speed: this.speed, toX: this.toX, toY: this.toY,
    };
    const n = frame.count;
    this.alloc(n);
    this.count = n;
    this.index = new Map();
    for (let i = 0; i < n; ++i) {
      const id = frame.ids[i];
      this.index.set(id, i);
      this.ids[i] = id;
      this.tier[i] = frame.tier[i];
      const c = frame.clip[i];
      this.clip[i] = c;
      const nx = frame.x[i], ny = frame.y[i], nz = frame.z[i], nyaw = frame.yaw[i], np = frame.phase[i];
      this.toX[i] = nx; this.toY[i] = ny; this.toZ[i] = nz; this.toYaw[i] = nyaw;
      const j = old.index.get(id);
      const { duration } = this.clipInfo(c);
      if (j === undefined || Math.hypot(nx - old.x[j], ny - old.y[j]) > kTeleport) {
        this.speed[i] = j === undefined || jumped ? 0 : old.speed[j];  // a newcomer: not the speed of whoever had this slot
        this.fromX[i] = nx; this.fromY[i] = ny; this.fromZ[i] = nz; this.fromYaw[i] = nyaw;
        this.phase[i] = np; this.rate[i] = 1 / duration; this.recvPhase[i] = np; this.recvAt[i] = now;
      } else {
        this.fromX[i] = old.x[j]; this.fromY[i] = old.y[j]; this.fromZ[i] = old.z[j]; this.fromYaw[i] = old.yaw[j];
        this.speed[i] = sameMoment ? old.speed[j] : jumped ? 0
          : old.speed[j] * 0.7 + 0.3 * (Math.hypot(nx - old.toX[j], ny - old.toY[j]) / (simGap > 0 ? simGap : this.interval));
        if (old.clip[j] !== c) {
          this.phase[i] = np; this.rate[i] = 1 / duration; this.recvPhase[i] = np; this.recvAt[i] = now;
        } else if (np !== old.recvPhase[j]) {
          const gap = now - old.recvAt[j];
          const est = gap > 0 ? phaseForward(old.recvPhase[j], np) / gap : 1 / duration;
          const rate = Math.min(Math.max(est, 0), 3 / duration);
          this.rate[i] = old.rate[j] * 0.5 + rate * 0.5;
          const err = signedPhase(old.phase[j], np);
          this.phase[i] = Math.abs(err) > 0.25 ? np : wrap01(old.phase[j] + err * 0.5);
          this.recvPhase[i] = np; this.recvAt[i] = now;
        } else {
          this.phase[i] = old.phase[j]; this.rate[i] = old.rate[j];
          this.recvPhase[i] = old.recvPhase[j]; this.recvAt[i] = old.recvAt[j];
        }
      }
      this.x[i] = this.fromX[i]; this.y[i] = this.fromY[i]; this.z[i] = this.fromZ[i]; this.yaw[i] = this.fromYaw[i];
    }
    // Far-tier agents carry no clip or phase (protocol): they walk at the rate their ground speed
    // gives (one walk cycle per kStrideCycle metres), so distant walkers still step.
    for (let i = 0; i < n; ++i) if (this.tier[i] === 2) this.rate[i] = this.speed[i] / kStrideCycle;
    if (frame.joints) for (const [id, j] of frame.joints) this.joints.set(id, j);
  }

  /** Display state at local time `now` [s]: fills x, y, z, yaw, phase for every agent. */
  advance(now) {
    const dt = Math.min(Math.max(now - this.lastAdvance, 0), 0.5);
    this.lastAdvance = now;
    if (this.count === 0) return;
    const a = this.lastFrameAt < 0 ? 1 : Math.min(Math.max((now - this.lastFrameAt) / this.interval, 0), 1);
    for (let i = 0; i < this.count; ++i) {
      this.x[i] = this.fromX[i] + (this.toX[i] - this.fromX[i]) * a;
      this.y[i] = this.fromY[i] + (this.toY[i] - this.fromY[i]) * a;
      this.z[i] = this.fromZ[i] + (this.toZ[i] - this.fromZ[i]) * a;
      this.yaw[i] = this.fromYaw[i] + angleDelta(this.fromYaw[i], this.toYaw[i]) * a;
      const { loops } = this.clipInfo(this.clip[i]);
      const p = this.phase[i] + this.rate[i] * dt;
      this.phase[i] = loops ? wrap01(p) : Math.min(p, 0.999);
    }
  }
}

function wrap01(p) {
  const w = p % 1;
  return w < 0 ? w + 1 : w;
}
