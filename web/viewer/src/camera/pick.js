// Picking — pure, no three.js: which agent a screen ray hits, from any camera angle. Each agent is
// an upright capsule (its axis from the feet to `height` above them, `radius` around it); the ray
// hits it when it passes within the radius of the axis segment (side, top-down and oblique views
// alike; a vertical ray from a plan view meets the axis end-on). Of the agents hit, the one whose
// axis the ray passes closest to wins, nearer along the ray on a tie — so a click between two
// neighbours takes the one under the pointer, not the one in front. Scene coordinates: world
// (x, y, z) → scene (x, z, −y), as everywhere in the viewer (coords.js).

/** Closest approach of the ray o + t·d (t ≥ 0) to the vertical segment from (ax, ay, az) to
 * (ax, ay + h, az): {dist [m], t} (t in units of d). */
export function rayToUprightSegment(o, d, ax, ay, az, h) {
  const wx = o.x - ax, wy = o.y - ay, wz = o.z - az;
  const dd = d.x * d.x + d.y * d.y + d.z * d.z;
  const b = d.y * h;           // d · u, u = (0, h, 0)
  const c = h * h;             // u · u
  const e = wy * h;            // u · w
  const f = d.x * wx + d.y * wy + d.z * wz;  // d · w
  const denom = dd * c - b * b;
  let s = denom > 1e-12 * dd * c ? (dd * e - b * f) / denom : e / c;  // parallel: any s; start at the origin's height
  s = Math.min(Math.max(s, 0), 1);
  let t = Math.max(0, (b * s - f) / dd);
  s = Math.min(Math.max((e + b * t) / c, 0), 1);
  t = Math.max(0, (b * s - f) / dd);
  const px = wx + d.x * t, py = wy + d.y * t - h * s, pz = wz + d.z * t;
  return { dist: Math.hypot(px, py, pz), t };
}

/** Index of the agent of `state` (CrowdState: x, y, z, count) under the ray {origin, direction}, or
 * −1. `radius` [m]: how far from an agent's axis a ray still hits it (a plan view passes the
 * larger of the body radius and a few pixels' worth); `height` [m] of the capsule. */
export function pickAgent(ray, state, radius = 0.4, height = 1.8) {
  let best = -1, bestDist = Infinity, bestT = Infinity;
  const o = ray.origin, d = ray.direction;
  for (let i = 0; i < state.count; ++i) {
    const { dist, t } = rayToUprightSegment(o, d, state.x[i], state.z[i], -state.y[i], height);
    if (dist > radius) continue;
    if (dist < bestDist - 0.05 || (Math.abs(dist - bestDist) <= 0.05 && t < bestT)) { best = i; bestDist = dist; bestT = t; }
  }
  return best;
}
