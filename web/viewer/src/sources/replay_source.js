// Replay data source: plays a recording with a timeline (play, pause, seek, speed). The timeline UI
// (ui/timeline.js) drives it through play() / pause() / seek(t) / setSpeed(s) and reads time and
// duration. Frames come from a backend with two methods:
//   duration() → seconds, frameAt(t) → the crowd frame (sources/frame.js layout) at or before t;
// plus the world description. `MemoryReplayBackend` holds frames in memory (used with
// `?demo&replay`: a recorded stretch of the demo). A server-side replay (`throng serve FILE.sqlite`)
// needs no backend here: LiveSource itself drives the server's timeline (ReplayControl/ReplayStatus).
import { Emitter } from './emitter.js';

export class MemoryReplayBackend {
  constructor(world, frames) {
    this.world = world;
    this.frames = frames;  // [{time [s], frame}] ascending
  }
  duration() { return this.frames.length ? this.frames[this.frames.length - 1].time : 0; }
  frameAt(t) {
    const f = this.frames;
    let lo = 0, hi = f.length - 1;
    if (hi < 0) return null;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (f[mid].time <= t) lo = mid; else hi = mid - 1;
    }
    return f[lo].frame;
  }
}

export class ReplaySource extends Emitter {
  constructor(backend) {
    super();
    this.kind = 'replay';
    this.backend = backend;
    this.time = 0;
    this.speed = 1;
    this.playing = false;
    this.bytesReceived = 0;
    this.participants = 0;
    this.lastFrame = null;
    this.timer = null;
  }

  get duration() { return this.backend.duration(); }

  start() {
    this.emit('status', { state: 'open', text: 'replay' });
    this.emit('world', this.backend.world);
    this.emitFrame(true);
    this.timer = setInterval(() => this.tick(), 50);
    this.last = performance.now();
    this.play();
  }

  stop() { clearInterval(this.timer); this.timer = null; }

  play() { if (this.time >= this.duration) this.time = 0; this.playing = true; this.emit('timeline', this.state()); }
  pause() { this.playing = false; this.emit('timeline', this.state()); }
  seek(t) { this.time = Math.min(Math.max(t, 0), this.duration); this.emitFrame(true); this.emit('timeline', this.state()); }
  setSpeed(s) { this.speed = Math.min(Math.max(s, 0.1), 16); this.emit('timeline', this.state()); }
  state() { return { time: this.time, duration: this.duration, playing: this.playing, speed: this.speed }; }

  tick() {
    const now = performance.now();
    const dt = (now - this.last) / 1000;
    this.last = now;
    if (!this.playing) return;
    this.time = Math.min(this.time + dt * this.speed, this.duration);
    if (this.time >= this.duration) this.playing = false;
    this.emitFrame(false);
    this.emit('timeline', this.state());
  }

  emitFrame(force) {
    const f = this.backend.frameAt(this.time);
    if (f && (force || f !== this.lastFrame)) { this.lastFrame = f; this.emit('frame', f); }
  }

  // A replay has no participants.
  join() {}
  leave() {}
  sendMove() {}
  guide() {}
  release() {}
}
