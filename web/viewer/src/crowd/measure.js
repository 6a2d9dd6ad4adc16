// Live measurements at the scenario's "measurements" (docs/scenario-format.md; issue 20's analysis
// overlays), from the crowd frames the page receives, with PedPy's definitions as `throng plot` and
// throng.analysis use them (docs/plot.md), over a sliding window of simulated time:
// - LineMeter: a measurement line's crossings — an agent whose straight step between two
//   successive frames crosses the segment — counted both ways; flow = crossings in the last
//   `seconds` / the window's length [1/s], specific flow = flow / the line's length [1/(m·s)].
// - AreaMeter: a measurement area's classic density (N inside / area, averaged over the window's
//   frames) [1/m²] and the mean speed of those inside (distance / time since their last frame)
//   [m/s]; once per simulated second a (density, speed) sample for the live fundamental diagram.
// - Measurements: one meter per entry of the scenario's list, fed each frame; rows() for the panel.
// Pure (no DOM, no three.js). A frame of an earlier time (a replay seeked back) starts afresh.
import { insidePolygon } from '../world/walls.js';

export const kMeasureSeconds = 10;  // [s] the sliding window
export const kFdSamples = 120;      // fundamental-diagram samples kept (one per simulated second)
const kJump = 5;                    // [m] a longer step between frames is a jump, not walking

function polygonArea(poly) {
  let a = 0;
  for (let i = 0, j = poly.length - 1; i < poly.length; j = i++) a += poly[j][0] * poly[i][1] - poly[i][0] * poly[j][1];
  return Math.abs(a) / 2;
}

/** Whether segments p0-p1 and q0-q1 properly intersect (touching at an end counts as crossing). */
export function segmentsCross(p0, p1, q0, q1) {
  const orient = (a, b, c) => (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  const d1 = orient(q0, q1, p0), d2 = orient(q0, q1, p1), d3 = orient(p0, p1, q0), d4 = orient(p0, p1, q1);
  return ((d1 > 0 && d2 <= 0) || (d1 < 0 && d2 >= 0) || (d1 === 0 && d2 !== 0)) &&
         ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0) || d3 === 0 || d4 === 0) && !(d1 === 0 && d2 === 0);
}

class Meter {
  constructor(seconds) { this.seconds = seconds; this.last = new Map(); this.t = -Infinity; }
  /** Returns false for the same frame again; clears on a frame of an earlier time. */
  advance(t) {
    if (t < this.t) this.reset();
    else if (t === this.t) return false;
    this.t = t;
    return true;
  }
  reset() { this.last.clear(); this.t = -Infinity; }
}

export class LineMeter extends Meter {
  /** line: [[x0, y0], [x1, y1]] [m]. */
  constructor(line, seconds = kMeasureSeconds) {
    super(seconds);
    this.line = line;
    this.length = Math.hypot(line[1][0] - line[0][0], line[1][1] - line[0][1]);
    this.times = [];  // simulated times of the crossings in the window, oldest first
    this.total = 0;   // since the start (or the last seek back)
    this.start = null;
  }
  reset() { super.reset(); this.times = []; this.total = 0; this.start = null; }
  /** One frame at simulated time t [s]: ids, x, y of its first `count` agents. */
  record(ids, x, y, count, t) {
    if (!this.advance(t)) return;
    if (this.start === null) this.start = t;
    const now = new Map();
    for (let i = 0; i < count; ++i) {
      const p = [x[i], y[i]];
      now.set(ids[i], p);
      const q = this.last.get(ids[i]);
      if (q && Math.hypot(p[0] - q[0], p[1] - q[1]) <= kJump && segmentsCross(q, p, this.line[0], this.line[1])) {
        this.times.push(t);
        this.total += 1;
      }
    }
    this.last = now;
    while (this.times.length && this.times[0] <= t - this.seconds) this.times.shift();
  }
  /** Crossings per second over the window (or over the time seen, when shorter) [1/s]. */
  flow() {
    const span = Math.min(this.seconds, this.t - (this.start ?? this.t));
    return span > 0 ? this.times.length / span : 0;
  }
  specificFlow() { return this.length > 0 ? this.flow() / this.length : 0; }
}

export class AreaMeter extends Meter {
  /** polygon: [[x, y], ...] [m]. */
  constructor(polygon, seconds = kMeasureSeconds) {
    super(seconds);
    this.polygon = polygon;
    this.area = polygonArea(polygon);
    this.frames = [];  // [{t, n, speedSum, speedCount}]
    this.fd = [];      // [{t, density, speed}], one per simulated second
  }
  reset() { super.reset(); this.frames = []; this.fd = []; }
  record(ids, x, y, count, t) {
    const previous = this.t;
    if (!this.advance(t)) return;
    const now = new Map();
    let n = 0, speedSum = 0, speedCount = 0;
    for (let i = 0; i < count; ++i) {
      if (!insidePolygon(x[i], y[i], this.polygon)) continue;
      n += 1;
      now.set(ids[i], [x[i], y[i]]);
      const q = this.last.get(ids[i]);
      if (!q || !(t > previous)) continue;
      const d = Math.hypot(x[i] - q[0], y[i] - q[1]);
      if (d <= kJump) { speedSum += d / (t - previous); speedCount += 1; }
    }
    this.last = now;
    this.frames.push({ t, n, speedSum, speedCount });
    while (this.frames.length > 1 && this.frames[0].t <= t - this.seconds) this.frames.shift();
    const lastSample = this.fd[this.fd.length - 1];
    if ((!lastSample || t - lastSample.t >= 1) && speedCount > 0) {
      this.fd.push({ t, density: n / this.area, speed: speedSum / speedCount });
      if (this.fd.length > kFdSamples) this.fd.shift();
    }
  }
  /** Classic density averaged over the window's frames [1/m²]. */
  density() {
    if (!this.frames.length || !(this.area > 0)) return 0;
    return this.frames.reduce((s, f) => s + f.n, 0) / (this.frames.length * this.area);
  }
  /** Mean speed of the agents inside over the window [m/s] (0 when nobody moved inside). */
  speed() {
    const c = this.frames.reduce((s, f) => s + f.speedCount, 0);
    return c ? this.frames.reduce((s, f) => s + f.speedSum, 0) / c : 0;
  }
}

export class Measurements {
  /** measurements: the scenario's list ({id, line} | {id, polygon}). */
  constructor(measurements = [], seconds = kMeasureSeconds) {
    this.meters = [];
    for (const m of measurements || []) {
      if (Array.isArray(m.line) && m.line.length === 2) this.meters.push({ id: m.id, kind: 'line', meter: new LineMeter(m.line, seconds) });
      else if (Array.isArray(m.polygon) && m.polygon.length >= 3) this.meters.push({ id: m.id, kind: 'area', meter: new AreaMeter(m.polygon, seconds) });
    }
  }
  get size() { return this.meters.length; }
  /** A crowd frame ({ids, x, y, count}) at simulated time t [s]. */
  record(f, t) { for (const m of this.meters) m.meter.record(f.ids, f.x, f.y, f.count, t); }
  /** [{id, kind, text}] for the panel. */
  rows() {
    return this.meters.map(({ id, kind, meter }) => ({
      id, kind, meter,
      text: kind === 'line'
        ? `${meter.flow().toFixed(2)} /s · ${meter.specificFlow().toFixed(2)} /(m·s) · ${meter.total} crossed`
        : `${meter.density().toFixed(2)} /m² · ${meter.speed().toFixed(2)} m/s`,
    }));
  }
}
