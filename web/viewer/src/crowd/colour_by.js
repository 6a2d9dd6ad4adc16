// What an agent's colour says — pure, no three.js. Five modes (the legend, ui/legend.js, shows the
// colours of the one in use): group (each group one of kGroupPalette's ten colours, repeating),
// population (the scenario's populations in order), speed (ground speed from successive positions,
// interpolate.js, 0 … kSpeedMax on kRamp), local density (persons per m² within kDensityRadius of
// the agent, counted on a grid of that cell size, 0 … kDensityMax on kRamp) and state, from what
// the frames carry: walking (walk clip, or a far-tier agent moving faster than 0.25 m/s), waiting
// (idle clip, or a far-tier agent standing), acting (any other clip: looking at an exhibit, an
// action), coordinating (its group waits for its members: `waiting` in /api/groups, live only).
// Colours are 0xRRGGBB numbers.

export const kColourModes = ['group', 'population', 'speed', 'density', 'state'];
export const kModeNames = { group: 'group', population: 'population', speed: 'speed', density: 'local density', state: 'state' };
export const kGroupPalette = [0x3f7fbf, 0xbf5f3f, 0x4f9f5f, 0x9f4fa0, 0xc0a040, 0x40a0a8, 0x8f6f4f, 0x707fa0, 0xb0607a, 0x6a8f30];
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
 * group whose members have all gone is not, as its colour now marks another group). */
export function legendOf(mode, { populations = [], groups = [] } = {}) {
  if (mode === 'population') {
    return [...populations.map((p, k) => ({ colour: kGroupPalette[k % kGroupPalette.length], label: p })),
      { colour: kNoGroup, label: 'no population known' }];
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
  const shown = present.slice(0, 5).map((g) => ({ colour: kGroupPalette[g.id % kGroupPalette.length],
    label: `group ${g.id}${g.population ? ` (${g.population})` : ''}` }));
  const n = kGroupPalette.length;
  const more = present.length > shown.length
    ? [{ colour: null, label: `… ${present.length} groups in ${n} colours: groups ${n} apart share one` }] : [];
  return [...shown, ...more];
}
