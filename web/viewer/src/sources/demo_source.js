// Demo data source (`?demo&agents=N`): a fabricated world, no server and no fetch. A square hall
// (side grows with N, about 4 m² per agent) with a few pillars, interest/action points and an
// exit; N agents in groups walking in circles around the centre at 0.9–1.5 m/s (one in ten stands
// idle), emitted as crowd frames at 10 Hz like the server's, middle tier, with the walk phase
// advancing with distance walked (1.5 m per cycle). Joining works locally: Guide makes a group
// walk after the avatar. This is what the fps benchmark (bench/fps.mjs) loads.
import { Emitter } from './emitter.js';
import { makeFrame } from './frame.js';
import { kHanimSkeleton } from '../crowd/procedural_clips.js';

const kTickRate = 10;
const kStride = 1.5;  // [m] per walk cycle

function rng(seed) {
  let s = seed >>> 0;
  return () => { s = (s * 1664525 + 1013904223) >>> 0; return s / 4294967296; };
}

export function demoDescription(n) {
  const side = Math.max(30, Math.ceil(Math.sqrt(n * 4)) + 12);
  const c = side / 2;
  const p = (x, y) => [x, y];
  const groupSize = 4;
  const groups = [];
  for (let g = 0; g * groupSize < n; ++g) {
    const members = [];
    for (let k = g * groupSize; k < Math.min(n, (g + 1) * groupSize); ++k) members.push(k);
    groups.push({ id: g, population: g % 5 === 0 ? 'tourists' : 'visitors', members });
  }
  return {
    description: 1, name: `demo (${n} agents)`, dt: 1 / kTickRate, tickRate: kTickRate,
    scenario: {
      format: 'throng/1', name: 'demo',
      walkable: [[p(0, 0), p(side, 0), p(side, side), p(0, side)], [p(side, c - 2), p(side + 3, c - 2), p(side + 3, c + 2), p(side, c + 2)]],
      obstacles: [
        [p(c - 1, c - 1), p(c + 1, c - 1), p(c + 1, c + 1), p(c - 1, c + 1)],
        [p(4, 4), p(5, 4), p(5, 5), p(4, 5)], [p(side - 5, 4), p(side - 4, 4), p(side - 4, 5), p(side - 5, 5)],
        [p(4, side - 5), p(5, side - 5), p(5, side - 4), p(4, side - 4)],
        [p(side - 5, side - 5), p(side - 4, side - 5), p(side - 4, side - 4), p(side - 5, side - 4)],
      ],
      points: [
        { id: 'fountain', kind: 'interest', position: [c, c + 4], radius: 1.5 },
        { id: 'statue', kind: 'action', position: [c + 6, c], radius: 1, orientation: [1, 0], action: 'look', duration: 8 },
        { id: 'painting', kind: 'action', position: [c, 2], radius: 1, orientation: [0, -1], action: 'look', duration: 8 },
        { id: 'exit', kind: 'exit', polygon: [p(side + 2, c - 2), p(side + 3, c - 2), p(side + 3, c + 2), p(side + 2, c + 2)] },
      ],
      populations: [],
    },
    skeleton: { joints: kHanimSkeleton.map((j) => ({ ...j, offset: [...j.offset] })) },
    clips: [
      { id: 0, name: 'idle', duration: 2, loops: true, url: null },
      { id: 1, name: 'walk', duration: 1.12, loops: true, url: null },
    ],
    groups,
  };
}

export class DemoSource extends Emitter {
  constructor(n = 200) {
    super();
    this.kind = 'demo';
    this.n = n;
    this.bytesReceived = 0;
    this.participants = 0;
    this.timer = null;
    this.guided = new Set();
    this.avatar = null;
  }

  start() {
    const n = this.n;
    this.world = demoDescription(n);
    const side = this.world.scenario.walkable[0][1][0];
    this.centre = side / 2;
    const r = rng(42);
    this.radius = new Float32Array(n); this.angle = new Float32Array(n); this.speed = new Float32Array(n);
    this.dir = new Int8Array(n); this.idle = new Uint8Array(n); this.phase = new Float32Array(n);
    this.px = new Float32Array(n); this.py = new Float32Array(n); this.yaw = new Float32Array(n);
    const maxR = side / 2 - 2;
    for (let g = 0; g < this.world.groups.length; ++g) {
      const rad = 2.5 + (maxR - 2.5) * Math.sqrt(r());
      const ang = r() * Math.PI * 2;
      const sp = 0.9 + r() * 0.6;
      const dir = r() < 0.5 ? 1 : -1;
      const idle = r() < 0.1 ? 1 : 0;
      for (const a of this.world.groups[g].members) {
        this.radius[a] = rad + (r() - 0.5) * 1.2;
        this.angle[a] = ang + (r() - 0.5) * (1.2 / rad);
        this.speed[a] = sp; this.dir[a] = dir; this.idle[a] = idle; this.phase[a] = r();
      }
    }
    this.tick = 0;
    this.emit('status', { state: 'open', text: 'demo world (no server)' });
    this.emit('world', this.world);
    this.step(0);
    this.timer = setInterval(() => this.step(1 / kTickRate), 1000 / kTickRate);
  }

  stop() { clearInterval(this.timer); this.timer = null; }

  step(dt) {
    const n = this.n;
    const f = makeFrame(n);
    f.simTick = this.tick++;
    const c = this.centre;
    for (let i = 0; i < n; ++i) {
      f.ids[i] = i; f.tier[i] = 1;
      const guidedBy = this.avatar && this.guided.has(Math.floor(i / 4));
      if (guidedBy) {
        const tx = this.avatar.x - Math.cos(this.avatar.yaw) * 1.5 + ((i % 4) - 1.5) * 0.7;
        const ty = this.avatar.y - Math.sin(this.avatar.yaw) * 1.5;
        const dx = tx - this.px[i], dy = ty - this.py[i];
        const d = Math.hypot(dx, dy);
        const v = Math.min(d / Math.max(dt, 1e-3), 1.6);
        if (d > 0.2) {
          this.px[i] += (dx / d) * v * dt; this.py[i] += (dy / d) * v * dt; this.yaw[i] = Math.atan2(dy, dx);
          this.phase[i] = (this.phase[i] + (v * dt) / kStride) % 1;
        }
        f.clip[i] = d > 0.2 ? 1 : 0;
        // Keep the circle parameters in step so a released agent continues from here.
        this.radius[i] = Math.max(2.5, Math.hypot(this.px[i] - c, this.py[i] - c));
        this.angle[i] = Math.atan2(this.py[i] - c, this.px[i] - c);
      } else if (this.idle[i]) {
        this.px[i] = c + this.radius[i] * Math.cos(this.angle[i]);
        this.py[i] = c + this.radius[i] * Math.sin(this.angle[i]);
        this.yaw[i] = this.angle[i] + Math.PI;
        this.phase[i] = (this.phase[i] + dt / 2) % 1;
        f.clip[i] = 0;
      } else {
        this.angle[i] += (this.dir[i] * this.speed[i] * dt) / this.radius[i];
        this.px[i] = c + this.radius[i] * Math.cos(this.angle[i]);
        this.py[i] = c + this.radius[i] * Math.sin(this.angle[i]);
        this.yaw[i] = this.angle[i] + (this.dir[i] * Math.PI) / 2;
        this.phase[i] = (this.phase[i] + (this.speed[i] * dt) / kStride) % 1;
        f.clip[i] = 1;
      }
      f.x[i] = this.px[i]; f.y[i] = this.py[i]; f.z[i] = 0; f.yaw[i] = this.yaw[i]; f.phase[i] = this.phase[i];
    }
    this.bytesReceived += 40 + n * 6;  // what a compressed middle-tier frame would weigh, roughly
    this.emit('frame', f);
  }

  join(name) {
    this.avatar = { x: this.centre + 3, y: this.centre - 3, yaw: 0 };
    this.participants = 1;
    setTimeout(() => this.emit('joined', { participantId: 1, token: 1n, name }), 50);
  }

  leave() { this.avatar = null; this.guided.clear(); this.participants = 0; }

  sendMove(x, y, z, yaw) { if (this.avatar) Object.assign(this.avatar, { x, y, yaw }); }

  guide(groupId) {
    this.guided.add(groupId);
    this.emit('guide', { groupId, guiding: true, ok: true, reason: 0 });
  }

  release(groupId) {
    const ok = this.guided.delete(groupId);
    this.emit('guide', { groupId, guiding: false, ok, reason: ok ? 0 : 12 });
  }
}
