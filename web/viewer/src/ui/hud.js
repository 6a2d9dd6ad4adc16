// Heads-up display (top left), for people first: the scenario's name, the simulated time (the
// latest crowd frame's tick × the world's dt; of the recording's length when replaying, else of the
// scenario's duration when it has one), how
// many agents are in the world now and how many have gone (seen in an earlier frame, not in the
// latest one: they left the world — or, for a participant, walked out of the area the server
// sends it), participants, and frames per second. The engineering figures — kbit/s received,
// agents drawn at each level of detail (or as plan discs), the adaptive caps and resolution, the
// round-trip time, why a recording's glTF materials are not drawn (modelMissing) — are in a debug
// part folded away by default (click "debug" to open it). Also
// publishes the numbers as window.__throngStats for scripts (bench/fps.mjs, the e2e tests).

/** m:ss (or h:mm:ss) of `s` seconds. */
export function clock(s) {
  const t = Math.max(0, Math.floor(s));
  const h = Math.floor(t / 3600), m = Math.floor((t % 3600) / 60), sec = String(t % 60).padStart(2, '0');
  return h ? `${h}:${String(m).padStart(2, '0')}:${sec}` : `${m}:${sec}`;
}

/** The HUD's clock: "1:05 of 5:00"; past the scenario's duration (a live world runs on) it says
 * so instead of "5:31 of 5:00". */
export function timeWords(t, duration) {
  if (!duration) return clock(t);
  return t > duration + 0.5 ? `${clock(t)} (its ${clock(duration)} are over; it runs on)` : `${clock(t)} of ${clock(duration)}`;
}

/** "  (12 gone)", "  (12 gone since 0:15)" after a replay's jump, or nothing. */
export function goneWords(attendance, dt) {
  if (!attendance.gone) return '';
  return attendance.since > 0 ? `  (${attendance.gone} gone since ${clock(attendance.since * (dt || 0))})` : `  (${attendance.gone} gone)`;
}

/** Agents present and gone: remembers every id seen; `ids` the latest frame's. A replay's jump —
 * a frame of an earlier tick, or more than `jumpTicks` later — starts the count afresh and
 * remembers where (`since`, the tick; 0 when counted from the start): those who came and went
 * in the part jumped over were never seen, so "gone" counts from there. */
export class Attendance {
  constructor() { this.seen = new Set(); this.present = 0; this.tick = -Infinity; this.since = 0; }
  frame(ids, count, tick = 0, jumpTicks = Infinity) {
    if (tick < this.tick || (Number.isFinite(this.tick) && tick - this.tick > jumpTicks)) {
      this.seen.clear();
      this.since = tick;
    }
    this.tick = tick;
    for (let i = 0; i < count; ++i) this.seen.add(ids[i]);
    this.present = count;
  }
  get gone() { return Math.max(0, this.seen.size - this.present); }
}

/** What the HUD shows of a world description: its name, dt and the duration the clock counts
 * towards — a recording's own length when replaying (the scenario's may be longer: the run ended
 * early, or everyone left), else the scenario's, 0 when it has none. */
export function hudWorld(w) {
  const sc = w.scenario || {};
  const length = Number(w.replay?.duration) > 0 ? Number(w.replay.duration) : Number(sc.duration);
  return { name: w.name || sc.name || '', dt: Number(w.dt) > 0 ? Number(w.dt) : 1 / (w.tickRate || 10),
    duration: length > 0 ? length : 0, about: typeof sc.description === 'string' ? sc.description : '' };
}

export class Hud {
  constructor(el) {
    this.el = el;
    el.innerHTML = '<div class="hud-main"></div><div class="hud-about hidden"></div>'
      + '<button class="hud-debug-toggle" title="engineering figures">debug ▸</button><div class="hud-debug hidden"></div>';
    this.main = el.querySelector('.hud-main');
    this.about = el.querySelector('.hud-about');
    // Two lines at first (it must not hide the world on a small screen); a click shows it all.
    this.about.title = 'what this world is: click to read it all';
    this.about.onclick = () => this.about.classList.toggle('open');
    this.debug = el.querySelector('.hud-debug');
    this.toggle = el.querySelector('.hud-debug-toggle');
    this.toggle.onclick = () => this.showDebug(this.debug.classList.contains('hidden'));
    this.frames = 0;
    this.windowStart = performance.now();
    this.fps = 0;
    this.kbps = 0;
    this.lastBytes = 0;
    this.totalFrames = 0;
    this.world = { name: '', dt: 0.1, duration: 0, about: '' };
    this.modelMissing = '';  // set by main.js from GET /api/world/model's `missing`
    this.simTick = 0;
    this.attendance = new Attendance();
  }

  showDebug(on) {
    this.debug.classList.toggle('hidden', !on);
    this.toggle.textContent = on ? 'debug ▾' : 'debug ▸';
  }

  /** The world description: {name, dt, scenario: {name, duration}, replay?: {duration}}. */
  setWorld(w) {
    this.world = hudWorld(w);
    // The scenario's "description": what the world is and what to watch, for someone new to it.
    this.about.textContent = this.world.about;
    this.about.classList.toggle('hidden', !this.world.about);
  }

  /** Each crowd frame received. */
  frame(f) {
    this.simTick = f.simTick || 0;
    this.attendance.frame(f.ids, f.count, this.simTick, this.world.dt > 0 ? 2 / this.world.dt : Infinity);  // 2 s: a seek
  }

  /** Simulated time [s] of the latest frame. */
  get simTime() { return this.simTick * this.world.dt; }

  /** Once per rendered frame. */
  tick(source, counts, agents, lod) {
    this.frames++;
    this.totalFrames++;
    const now = performance.now();
    const dt = now - this.windowStart;
    if (dt >= 1000) {
      this.fps = (this.frames * 1000) / dt;
      this.kbps = ((source.bytesReceived - this.lastBytes) * 8) / dt;  // bits per ms = kbit/s
      this.lastBytes = source.bytesReceived;
      this.frames = 0;
      this.windowStart = now;
      this.draw(source, counts, agents, lod);
    }
    globalThis.__throngStats = {
      fps: this.fps, agents, frames: this.totalFrames, kbps: this.kbps,
      lod: { near: counts.near, middle: counts.middle, far: counts.far, dot: counts.dot || 0, plan: counts.plan || 0, hidden: counts.hidden,
        renderScale: lod.adaptive ? lod.renderScale : 1 },
      adaptive: lod.adaptive, participants: source.participants,
      simTime: this.simTime, gone: this.attendance.gone, scenario: this.world.name,
    };
  }

  draw(source, counts, agents, lod) {
    const w = this.world;
    this.main.textContent = [
      w.name || 'throng',
      `time         ${timeWords(this.simTime, w.duration)}`,
      `agents       ${agents}${goneWords(this.attendance, w.dt)}`,
      `participants ${source.participants}`,
      `fps          ${this.fps.toFixed(0)}`,
    ].join('\n');
    const cap = lod.adaptive ? `caps ${lod.maxNear}/${lod.maxMiddle} res ${Math.round(lod.renderScale * 100)}%` : 'LOD off';
    this.debug.textContent = [
      `kbit/s       ${this.kbps.toFixed(1)}`,
      counts.plan ? `plan discs   ${counts.plan}` : null,
      `near         ${counts.near}`,
      `middle       ${counts.middle}`,
      `far          ${counts.far}`,
      `dots         ${counts.dot || 0}`,
      `off screen   ${counts.hidden}`,
      `${cap}`,
      source.rttMs ? `rtt          ${source.rttMs.toFixed(0)} ms` : `source       ${source.kind}`,
      this.modelMissing ? `materials    not drawn: ${this.modelMissing}` : null,
    ].filter((l) => l !== null).join('\n');
  }

  /** The text shown (for tests). */
  text() { return `${this.main.textContent}\n${this.debug.classList.contains('hidden') ? '' : this.debug.textContent}`; }
}
