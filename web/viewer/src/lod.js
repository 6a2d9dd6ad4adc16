// Global level-of-detail function (Musse et al. §4, adaptive display) — pure, no three.js.
// Reads each agent's projected height on screen [px] and the measured frame time; writes each
// agent's level: Near (skinned body), Middle (instanced low-polygon body), Far (billboard), Dot (a
// flat-coloured point, for agents a few pixels high) or Hidden (off screen). Two parts:
//   assignLevels: thresholds on projected size, with hysteresis (an agent keeps its level until it
//     crosses the threshold by a margin) and caps (at most maxNear skinned and maxMiddle middle
//     bodies: the largest on screen win, found with a log-size histogram in O(n));
//   LodBudget: adapts caps and thresholds from the measured frame time so the frame rate holds as
//     the crowd grows (shrinks fast when over budget, grows slowly when under, a dead band between).
// Whatever the budget does, the selected agent (when on screen) and the alwaysNear agents nearest
// the camera (largest on screen, when at least alwaysNearMinPx high) stay full bodies: people the
// viewer looks at stay people (nearestVisible).

export const Level = Object.freeze({ Near: 0, Middle: 1, Far: 2, Hidden: 3, Dot: 4 });

/** Height on screen [px] of a body `bodyHeight` [m] at `distance` [m] seen with vertical field of
 * view `fovY` [rad] on a viewport `screenHeight` [px] high. */
export function projectedHeight(distance, fovY, screenHeight, bodyHeight = 1.75) {
  const d = Math.max(distance, 1e-3);
  return (bodyHeight * screenHeight) / (2 * d * Math.tan(fovY / 2));
}

export const defaultLodParams = Object.freeze({
  nearPx: 150,      // projected height from which an agent gets a skinned body [px]
  middlePx: 30,     // projected height from which an agent gets a middle body [px]
  maxNear: 48,      // cap on skinned bodies
  maxMiddle: 4000,  // cap on middle bodies
  dotPx: 6,         // below this projected height a Far agent is drawn as a dot [px]
  hysteresis: 0.15, // a level is kept until the size is this fraction below its threshold
  alwaysNear: 4,    // the agents nearest the camera that are Near whatever the thresholds and caps
  alwaysNearMinPx: 24, // … when at least this high on screen (about 55 m away at 720 px) [px]
  adaptive: true,   // false: every visible agent is Near (the "display off" baseline)
});

/**
 * Indices of the `k` largest visible agents (sizes ≥ minPx), largest first, ties by index: the
 * nearest to the camera, as every body has the same height. O(n·k) for the few k it is used with.
 */
export function nearestVisible(sizes, count, k, minPx) {
  const best = [];
  if (k <= 0) return best;
  for (let i = 0; i < count; ++i) {
    const s = sizes[i];
    if (!(s >= minPx) || s < 0) continue;
    if (best.length === k && s <= sizes[best[k - 1]]) continue;
    let at = best.length === k ? k - 1 : best.length;
    while (at > 0 && sizes[best[at - 1]] < s) { best[at] = best[at - 1]; --at; }
    best[at] = i;
    if (best.length > k) best.length = k;
  }
  return best;
}

const kBuckets = 64;
const kLogMin = 0;   // log2(1 px)
const kLogMax = 13;  // log2(8192 px)

function bucketOf(size) {
  const l = Math.log2(Math.max(size, 1));
  const b = Math.floor(((l - kLogMin) / (kLogMax - kLogMin)) * kBuckets);
  return b < 0 ? 0 : b >= kBuckets ? kBuckets - 1 : b;
}

// Among agents with eligible[i] === 1, keeps at most `cap` (largest sizes first; inside the
// boundary bucket, agents that already had `level` first) by setting out[i] = level.
function admitLargest(sizes, count, eligible, prev, level, cap, out, hist) {
  hist.fill(0);
  let total = 0;
  for (let i = 0; i < count; ++i) {
    if (eligible[i]) { hist[bucketOf(sizes[i])]++; total++; }
  }
  if (total <= cap) {
    for (let i = 0; i < count; ++i) if (eligible[i]) out[i] = level;
    return total;
  }
  let above = 0;
  let cut = kBuckets - 1;
  for (; cut >= 0; --cut) {
    if (above + hist[cut] > cap) break;
    above += hist[cut];
  }
  let room = cap - above;
  // Buckets above the cut: all in. The cut bucket: previous holders first (stability), then the
  // largest (exact order inside the one bucket).
  const boundary = [];
  for (let i = 0; i < count; ++i) {
    if (!eligible[i]) continue;
    const b = bucketOf(sizes[i]);
    if (b > cut) out[i] = level;
    else if (b === cut) boundary.push(i);
  }
  boundary.sort((a, b) => {
    const ha = prev && prev[a] === level ? 1 : 0, hb = prev && prev[b] === level ? 1 : 0;
    return hb - ha || sizes[b] - sizes[a] || a - b;
  });
  for (let k = 0; k < boundary.length && room > 0; ++k, --room) out[boundary[k]] = level;
  return cap;
}

/**
 * Picks each agent's level. `sizes[i]`: projected height [px], negative when the agent is off
 * screen (→ Hidden). `prev`: the levels of the previous call (same agent order) or null.
 * `out`: Uint8Array ≥ count. `pinned`: indices always Near when on screen (the selected agent),
 * besides the params.alwaysNear nearest; neither counts against maxNear nor in nearDemand.
 * Returns {near, middle, far, dot, hidden, nearDemand, middleDemand, pinned}: the counts assigned,
 * how many agents were large enough for each level before the caps, and how many were pinned Near.
 */
export function assignLevels(sizes, count, prev, out, params = defaultLodParams, scratch = null, pinned = null) {
  const p = { ...defaultLodParams, ...params };
  const counts = { near: 0, middle: 0, far: 0, dot: 0, hidden: 0, nearDemand: 0, middleDemand: 0, pinned: 0 };
  if (!p.adaptive) {
    for (let i = 0; i < count; ++i) {
      out[i] = sizes[i] < 0 ? Level.Hidden : Level.Near;
      if (out[i] === Level.Near) counts.near++; else counts.hidden++;
    }
    counts.nearDemand = counts.near;
    return counts;
  }
  const s = scratch || makeLodScratch(count);
  if (s.eligible.length < count) Object.assign(s, makeLodScratch(count));
  const eligible = s.eligible;
  const keep = 1 - p.hysteresis;
  for (let i = 0; i < count; ++i) {
    out[i] = sizes[i] < 0 ? Level.Hidden : Level.Far;
    const was = prev ? prev[i] : Level.Far;
    const t = was === Level.Near ? p.nearPx * keep : p.nearPx;
    eligible[i] = sizes[i] >= 0 && sizes[i] >= t ? 1 : 0;
  }
  counts.pinned = pinNear(sizes, count, p, pinned, out, eligible);
  let nd = 0;
  for (let i = 0; i < count; ++i) nd += eligible[i];
  counts.nearDemand = nd;
  admitLargest(sizes, count, eligible, prev, Level.Near, p.maxNear, out, s.hist);
  for (let i = 0; i < count; ++i) {
    if (out[i] !== Level.Far) { eligible[i] = 0; continue; }
    const was = prev ? prev[i] : Level.Far;
    const t = was === Level.Middle || was === Level.Near ? p.middlePx * keep : p.middlePx;
    eligible[i] = sizes[i] >= t ? 1 : 0;
  }
  let md = 0;
  for (let i = 0; i < count; ++i) md += eligible[i];
  counts.middleDemand = md;
  admitLargest(sizes, count, eligible, prev, Level.Middle, p.maxMiddle, out, s.hist);
  // Dots: Far agents below dotPx (a billboard there is a few pixels of texture anyway); an agent
  // that was Far or larger stays Far until it is `hysteresis` below the threshold.
  for (let i = 0; i < count; ++i) {
    if (out[i] !== Level.Far) continue;
    const was = prev ? prev[i] : Level.Far;
    const t = was === Level.Dot ? p.dotPx : p.dotPx * keep;
    if (sizes[i] < t) out[i] = Level.Dot;
  }
  for (let i = 0; i < count; ++i) {
    const l = out[i];
    if (l === Level.Dot) { counts.dot++; continue; }
    if (l === Level.Near) counts.near++;
    else if (l === Level.Middle) counts.middle++;
    else if (l === Level.Far) counts.far++;
    else counts.hidden++;
  }
  return counts;
}

/** Sets the pinned and the alwaysNear nearest visible agents Near, outside the caps; how many. */
function pinNear(sizes, count, p, pinned, out, eligible) {
  let n = 0;
  const pin = (i) => {
    if (i < 0 || i >= count || sizes[i] < 0 || out[i] === Level.Near) return;
    out[i] = Level.Near;
    eligible[i] = 0;
    n++;
  };
  for (const i of nearestVisible(sizes, count, p.alwaysNear, p.alwaysNearMinPx)) pin(i);
  if (pinned) for (const i of pinned) pin(i);
  return n;
}

/** Reusable buffers for assignLevels (avoids allocation per frame). */
export function makeLodScratch(capacity) {
  return { eligible: new Uint8Array(Math.max(capacity, 16)), hist: new Uint32Array(kBuckets) };
}

/**
 * Frame-time budget: adapts the caps, a size-threshold scale and the render scale (dynamic
 * resolution: the fraction of the full pixel ratio the frame is drawn at) so the frame time
 * approaches `targetFrameMs`. Over budget by more than `high` (fraction): caps × 0.75 / 0.8,
 * thresholds × 1.15 and render scale × 0.9 (× 0.8 when over by half or more; not below
 * `minRenderScale`), at most once per `periodS`. Under budget by more than `low`: render scale
 * × 1.05 (up to 1), thresholds ÷ 1.05, and the caps × 1.15 (+1) where binding (more agents want
 * the level than it allows). In between (the dead band): nothing changes — hysteresis against
 * oscillation.
 */
export class LodBudget {
  constructor(options = {}) {
    const o = {
      targetFrameMs: 1000 / 30, high: 0.15, low: 0.25, periodS: 0.5,
      maxNear: defaultLodParams.maxNear, maxMiddle: defaultLodParams.maxMiddle,
      minNear: 2, minMiddle: 50, nearPx: defaultLodParams.nearPx, middlePx: defaultLodParams.middlePx,
      maxScale: 4, minRenderScale: 0.5, dotPx: defaultLodParams.dotPx, ...options,
    };
    this.options = o;
    this.nearCap = o.maxNear;
    this.middleCap = o.maxMiddle;
    this.scale = 1;
    this.renderScale = 1;  // dynamic resolution: fraction of the full pixel ratio to render at
    this.frameMs = o.targetFrameMs;  // smoothed measured frame time
    this.sincePeriod = 0;
    this.lastChange = 'start';
  }

  /** Feeds one frame's duration [ms] and the last assignLevels counts; returns the parameters to
   * use for the next assignLevels call. */
  update(frameMs, counts = null) {
    const o = this.options;
    if (Number.isFinite(frameMs) && frameMs > 0) this.frameMs = this.frameMs * 0.85 + Math.min(frameMs, 2000) * 0.15;
    this.sincePeriod += Math.max(0, frameMs || 0) / 1000;
    if (this.sincePeriod >= o.periodS) {
      this.sincePeriod = 0;
      if (this.frameMs > o.targetFrameMs * (1 + o.high)) {
        this.nearCap = Math.max(o.minNear, Math.floor(this.nearCap * 0.75));
        this.middleCap = Math.max(o.minMiddle, Math.floor(this.middleCap * 0.8));
        this.scale = Math.min(o.maxScale, this.scale * 1.15);
        // Far over budget (≥ 1.5× the target): the resolution drops faster.
        const f = this.frameMs > o.targetFrameMs * 1.5 ? 0.8 : 0.9;
        this.renderScale = Math.max(o.minRenderScale, this.renderScale * f);
        this.lastChange = 'over budget';
      } else if (this.frameMs < o.targetFrameMs * (1 - o.low)) {
        const nearBinding = !counts || counts.nearDemand > this.nearCap;
        const middleBinding = !counts || counts.middleDemand > this.middleCap;
        let changed = false;
        if (nearBinding && this.nearCap < o.maxNear) { this.nearCap = Math.min(o.maxNear, Math.ceil(this.nearCap * 1.15) + 1); changed = true; }
        if (middleBinding && this.middleCap < o.maxMiddle) { this.middleCap = Math.min(o.maxMiddle, Math.ceil(this.middleCap * 1.15) + 1); changed = true; }
        if (this.scale > 1) { this.scale = Math.max(1, this.scale / 1.05); changed = true; }
        if (this.renderScale < 1) { this.renderScale = Math.min(1, this.renderScale * 1.05); changed = true; }
        this.lastChange = changed ? 'under budget' : 'steady';
      } else {
        this.lastChange = 'steady';
      }
    }
    return this.params();
  }

  params() {
    const o = this.options;
    return { nearPx: o.nearPx * this.scale, middlePx: o.middlePx * this.scale, maxNear: this.nearCap,
      maxMiddle: this.middleCap, dotPx: o.dotPx * this.scale, renderScale: this.renderScale, hysteresis: defaultLodParams.hysteresis, adaptive: true };
  }
}
