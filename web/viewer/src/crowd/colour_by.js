// What an agent's colour says — pure, no three.js. Five modes (the legend, ui/legend.js, shows the
// colours of the one in use): group (each group one of kGroupPalette's twelve colours, handed out
// by GroupColours so that groups arriving near each other get different ones, then kept),
// population (the scenario's populations in order), speed (ground speed from successive positions,
// interpolate.js, 0 … kSpeedMax on kRamp), local density (persons per m² within kDensityRadius of
// the agent, counted on a grid of that cell size, 0 … kDensityMax on kRamp) and state, from what
// the frames carry: walking (walk clip, or a far-tier agent moving faster than 0.25 m/s), waiting
// (idle clip, or a far-tier agent standing), acting (any other clip: looking at an exhibit, an
// action), coordinating (its group waits for its members: `waiting` in /api/groups, live only).
// Colours are 0xRRGGBB numbers.

export const kColourModes = ['group', 'population', 'speed', 'density', 'state'];
export const kModeNames = { group: 'group', population: 'population', speed: 'speed', density: 'local density', state: 'state' };
export const kGroupPalette = [0x3f7fbf, 0xbf5f3f, 0x4f9f5f, 0x9f4fa0, 0xc0a040, 0x40a0a8, 0x8f6f4f, 0x707fa0, 0xb0607a, 0x6a8f30,
  0x2f4f8f, 0xd08080];
/** Groups whose centres are nearer than this [m] get different colours when the palette allows
 * (GroupColours): about what one sees of a crowd at once from a person's height. */
export const kGroupColourRadius = 12;
export const kRamp = [0x2b59c3, 0x2bb0c3, 0x5dbb63, 0xf08a24, 0x9e1030];  // low → high (no yellow: the selection's colour)
export const kSpeedMax = 2.0;       // [m/s] top of the speed ramp (a brisk walk is 1.3–1.6 m/s)
export const kDensityMax = 4.0;     // [persons/m²] top of the density ramp (Weidmann's walking limit is ~5)
export const kDensityRadius = 1.0;  // [m] the neighbourhood counted for local density
export const kStates = ['walking', 'waiting', 'acting', 'coordinating'];
export const kStateColours = { walking: 0x3f7fbf, waiting: 0x9a9a9a, acting: 0x8e44ad, coordinating: 0x16a085 };
export const kNoGroup = 0x8a8a8a;

/**
 * The colour mode a world opens in: by group, unless every group is one person (a bottleneck's
 * crowd, an evacuation), where ten colours repeating over a hundred loners tell nothing — then by
 * population when there are several, else by speed (a jam shows). `groups`: [{members: [...]}];
 * `populations`: how many.
 */
export function defaultColourMode(groups, populations) {
  const list = Array.isArray(groups) ? groups : [];
  const loners = list.length > 0 && list.every((g) => !Array.isArray(g.members) || g.members.length <= 1);
  if (!loners) return 'group';
  return populations > 1 ? 'population' : 'speed';
}

/**
 * Which of kGroupPalette's colours each group wears: with hundreds of groups colours must repeat, so
 * a group, when first seen, takes the colour whose nearest wearer is farthest from it (of the groups
 * with centres within `radius` metres), and keeps it for good — a colour that changed would read as
 * another group (a stand-in newcomer's check). So groups that arrive side by side differ.
 * Pure (no three.js): `update(ids, x, y, n, groupOf)` from the agents' stable ids and world
 * positions, `index(g)` the palette index of group g (its id modulo the palette for a group not
 * seen yet).
 */
export class GroupColours {
  constructor(paletteSize = kGroupPalette.length, radius = kGroupColourRadius) {
    this.n = paletteSize;
    this.radius = radius;
    this.of = new Map();  // group id → palette index
  }

  index(g) {
    const k = this.of.get(g);
    return k === undefined ? ((g % this.n) + this.n) % this.n : k;
  }

  /** Gives every group first seen among the n agents (ids[i], x[i], y[i]; groupOf: id → group) a
   * colour, lowest id first, from the groups' centres now. Returns how many got one. */
  update(ids, x, y, n, groupOf) {
    let fresh = false;  // a group without a colour among those present (else nothing to do)
    for (let i = 0; i < n && !fresh; ++i) { const g = groupOf.get(ids[i]); fresh = g !== undefined && !this.of.has(g); }
    if (!fresh) return 0;
    const sum = new Map();  // group → [sx, sy, count]
    for (let i = 0; i < n; ++i) {
      const g = groupOf.get(ids[i]);
      if (g === undefined) continue;
      const s = sum.get(g);
      if (s) { s[0] += x[i]; s[1] += y[i]; s[2]++; } else sum.set(g, [x[i], y[i], 1]);
    }
    const groups = [...sum.keys()].sort((a, b) => a - b);
    const cx = new Map(), cy = new Map(), cells = new Map();
    const r = this.radius, key = (a, b) => `${a},${b}`;
    for (const g of groups) {
      const [sx, sy, c] = sum.get(g);
      cx.set(g, sx / c); cy.set(g, sy / c);
      const k = key(Math.floor(sx / c / r), Math.floor(sy / c / r));
      const list = cells.get(k);
      if (list) list.push(g); else cells.set(k, [g]);
    }
    const near = (g, f) => {  // f(h, d²) for every other group h within r of g
      const gx = cx.get(g), gy = cy.get(g), ix = Math.floor(gx / r), iy = Math.floor(gy / r);
      for (let dx = -1; dx <= 1; ++dx) {
        for (let dy = -1; dy <= 1; ++dy) {
          for (const h of cells.get(key(ix + dx, iy + dy)) || []) {
            const d2 = (cx.get(h) - gx) ** 2 + (cy.get(h) - gy) ** 2;
            if (h !== g && d2 < r * r) f(h, d2);
          }
        }
      }
    };
    let changed = 0;
    for (const g of groups) {
      if (this.of.has(g)) continue;  // kept for good
      // How near the nearest other group wearing each colour is (Infinity: none within r).
      const nearest = new Float64Array(this.n).fill(Infinity);
      near(g, (h, d2) => {
        const k = this.of.get(h);
        if (k !== undefined) nearest[k] = Math.min(nearest[k], Math.sqrt(d2));
      });
      let best = this.index(g);
      for (let j = 0; j < this.n; ++j) {
        const k = (this.index(g) + j) % this.n;  // from the group's own default on: the same input, the same colours
        if (nearest[k] > nearest[best]) best = k;
      }
      this.of.set(g, best);
      changed++;
    }
    return changed;
  }
}

/** Colour at t ∈ [0, 1] on kRamp (linear between its stops). */
export function rampColour(t) {
  const u = Math.min(Math.max(Number.isFinite(t) ? t : 0, 0), 1) * (kRamp.length - 1);
  const k = Math.min(Math.floor(u), kRamp.length - 2), f = u - k;
  const a = kRamp[k], b = kRamp[k + 1];
  const mix = (s) => Math.round(((a >> s) & 255) * (1 - f) + ((b >> s) & 255) * f);
  return (mix(16) << 16) | (mix(8) << 8) | mix(0);
}

/** State of an agent: clip name ('' for far-tier agents, which carry none), ground speed [m/s],
 * whether its group is waiting for its members. */
export function stateOf(clipName, speed, groupWaiting) {
  if (groupWaiting) return 'coordinating';
  if (!clipName) return speed > 0.25 ? 'walking' : 'waiting';
  if (/walk|run/i.test(clipName)) return 'walking';
  if (/idle|stand|wait/i.test(clipName)) return 'waiting';
  return 'acting';
}

/** Persons per m² around each of the n agents at (x[i], y[i]) (itself included) within `radius`
 * [m], written to out[i]: neighbours found through a uniform grid of cell `radius` (3 × 3 cells). */
export function localDensity(x, y, n, radius = kDensityRadius, out = new Float32Array(n)) {
  const cells = new Map();
  const key = (cx, cy) => cx * 73856093 ^ cy * 19349663;
  for (let i = 0; i < n; ++i) {
    const k = key(Math.floor(x[i] / radius), Math.floor(y[i] / radius));
    const list = cells.get(k);
    if (list) list.push(i); else cells.set(k, [i]);
  }
  const r2 = radius * radius, area = Math.PI * r2;
  for (let i = 0; i < n; ++i) {
    const cx = Math.floor(x[i] / radius), cy = Math.floor(y[i] / radius);
    let count = 0;
    for (let dx = -1; dx <= 1; ++dx) {
      for (let dy = -1; dy <= 1; ++dy) {
        const list = cells.get(key(cx + dx, cy + dy));
        if (!list) continue;
        for (const j of list) {
          const ex = x[j] - x[i], ey = y[j] - y[i];
          if (ex * ex + ey * ey <= r2 && Math.floor(x[j] / radius) === cx + dx && Math.floor(y[j] / radius) === cy + dy) count++;
        }
      }
    }
    out[i] = count / area;
  }
  return out;
}

/** Legend entries of a mode: [{colour, label}]. `populations`: names in order; `groups`:
 * [{id, population, members?}] (in group mode the first few with someone in them are listed — a
 * group whose members have all gone is not, as its colour now marks another group); `groupColour`:
 * a group id's palette index (GroupColours.index; the id modulo the palette when not given). */
export function legendOf(mode, { populations = [], groups = [], groupColour } = {}) {
  if (mode === 'population') {
    // At most eight listed (the mall has 266 populations): a list that runs off the screen hides the rest.
    const shown = populations.slice(0, 8).map((p, k) => ({ colour: kGroupPalette[k % kGroupPalette.length], label: p }));
    const more = populations.length > shown.length
      ? [{ colour: null, label: `… ${populations.length} populations in ${kGroupPalette.length} colours` }] : [];
    return [...shown, ...more, { colour: kNoGroup, label: 'no population known' }];
  }
  if (mode === 'speed' || mode === 'density') {
    const max = mode === 'speed' ? kSpeedMax : kDensityMax, unit = mode === 'speed' ? 'm/s' : 'persons/m²';
    return kRamp.map((c, k) => {
      const v = (max * k) / (kRamp.length - 1);
      return { colour: c, label: `${k === kRamp.length - 1 ? '≥ ' : ''}${v.toFixed(1)} ${unit}` };
    });
  }
  if (mode === 'state') return kStates.map((s) => ({ colour: kStateColours[s], label: s }));
  const present = groups.filter((g) => !Array.isArray(g.members) || g.members.length > 0);
  const n = kGroupPalette.length;
  const indexOf = groupColour || ((g) => g % n);
  const shown = present.slice(0, 5).map((g) => ({ colour: kGroupPalette[indexOf(g.id)],
    label: `group ${g.id}${g.population ? ` (${g.population})` : ''}` }));
  const more = present.length > shown.length
    ? [{ colour: null, label: `… ${present.length} groups in ${n} colours: groups that came side by side differ, far apart ones may share one` }] : [];
  return [...shown, ...more];
}
