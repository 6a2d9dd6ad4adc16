// Pose math — pure, no three.js: sampling a baked clip at a phase (normalised lerp of joint
// quaternions between frames, root position lerp) and BVH Euler angles (Z, X, Y order) to
// quaternions. Reads baked clips (clip_library.js); writes into caller-owned typed arrays.

/** Samples a baked clip {name, duration [s], loops, frames, jointCount, quats Float32Array(frames×J×4),
 * root Float32Array(frames×3) [m]}. */
export function sampleClip(clip, phase, outQuats, outRoot) {
  const J = clip.jointCount;
  const n = clip.frames;
  let f;
  let p = clip.loops ? phase - Math.floor(phase) : Math.min(Math.max(phase, 0), 1);
  if (clip.loops) f = p * n; else f = p * (n - 1);
  let f0 = Math.floor(f);
  const t = f - f0;
  f0 = Math.min(f0, n - 1);
  const f1 = clip.loops ? (f0 + 1) % n : Math.min(f0 + 1, n - 1);
  const q = clip.quats;
  for (let j = 0; j < J; ++j) {
    const a = (f0 * J + j) * 4, b = (f1 * J + j) * 4;
    let bx = q[b], by = q[b + 1], bz = q[b + 2], bw = q[b + 3];
    if (q[a] * bx + q[a + 1] * by + q[a + 2] * bz + q[a + 3] * bw < 0) { bx = -bx; by = -by; bz = -bz; bw = -bw; }
    const x = q[a] + (bx - q[a]) * t, y = q[a + 1] + (by - q[a + 1]) * t;
    const z = q[a + 2] + (bz - q[a + 2]) * t, w = q[a + 3] + (bw - q[a + 3]) * t;
    const l = Math.hypot(x, y, z, w) || 1;
    outQuats[j * 4] = x / l; outQuats[j * 4 + 1] = y / l; outQuats[j * 4 + 2] = z / l; outQuats[j * 4 + 3] = w / l;
  }
  if (outRoot) {
    const r = clip.root;
    for (let k = 0; k < 3; ++k) outRoot[k] = r[f0 * 3 + k] + (r[f1 * 3 + k] - r[f0 * 3 + k]) * t;
  }
}

/** Quaternion (x, y, z, w) of BVH Euler angles applied Z, then X, then Y [rad] (three's 'ZXY'). */
export function quatFromZXY(ax, ay, az, out, o = 0) {
  const cx = Math.cos(ax / 2), sx = Math.sin(ax / 2), cy = Math.cos(ay / 2), sy = Math.sin(ay / 2);
  const cz = Math.cos(az / 2), sz = Math.sin(az / 2);
  out[o] = sx * cy * cz - cx * sy * sz;
  out[o + 1] = cx * sy * cz + sx * cy * sz;
  out[o + 2] = cx * cy * sz + sx * sy * cz;
  out[o + 3] = cx * cy * cz - sx * sy * sz;
}


/** BVH Euler angles [rad] (x, y, z; applied Z, then X, then Y) of the unit quaternion at q[o..o+3]:
 * the inverse of quatFromZXY, written to out[oo..oo+2]; x in [−π/2, π/2]. */
export function eulerZXYFromQuat(q, o, out, oo = 0) {
  const x = q[o], y = q[o + 1], z = q[o + 2], w = q[o + 3];
  const m11 = 1 - 2 * (y * y + z * z), m12 = 2 * (x * y - w * z), m21 = 2 * (x * y + w * z);
  const m22 = 1 - 2 * (x * x + z * z), m31 = 2 * (x * z - w * y), m32 = 2 * (y * z + w * x);
  const m33 = 1 - 2 * (x * x + y * y);
  const s = Math.min(Math.max(m32, -1), 1);
  out[oo] = Math.asin(s);
  if (Math.abs(s) < 0.9999999) {
    out[oo + 1] = Math.atan2(-m31, m33);
    out[oo + 2] = Math.atan2(-m12, m22);
  } else {
    out[oo + 1] = 0;
    out[oo + 2] = Math.atan2(m21, m11);
  }
}
