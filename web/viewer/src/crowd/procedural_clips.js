// Procedural motion clips (no file): the H-Anim skeleton of the bundled library, a walk cycle
// (legs and arms swing, knees bend, pelvis bobs) and an idle (breathing sway), baked like a BVH
// clip. Used by the ?demo world and when a served clip has no file. Angles follow the library's
// conventions: a positive X rotation swings a hanging limb backwards.
import { quatFromZXY } from './pose_math.js';

/** The bundled library's skeleton (scenarios/motions/*.bvh), as the world description lists it. */
export const kHanimSkeleton = [
  { name: 'HumanoidRoot', parent: -1, offset: [0, 0.95, 0] },
  { name: 'sacroiliac', parent: 0, offset: [0, 0, 0] },
  { name: 'l_hip', parent: 1, offset: [0.09, -0.05, 0] },
  { name: 'l_knee', parent: 2, offset: [0, -0.42, 0] },
  { name: 'l_ankle', parent: 3, offset: [0, -0.41, 0] },
  { name: 'r_hip', parent: 1, offset: [-0.09, -0.05, 0] },
  { name: 'r_knee', parent: 5, offset: [0, -0.42, 0] },
  { name: 'r_ankle', parent: 6, offset: [0, -0.41, 0] },
  { name: 'vl5', parent: 0, offset: [0, 0.1, 0] },
  { name: 'skullbase', parent: 8, offset: [0, 0.52, 0] },
  { name: 'l_shoulder', parent: 8, offset: [0.19, 0.42, 0] },
  { name: 'l_elbow', parent: 10, offset: [0, -0.29, 0] },
  { name: 'l_wrist', parent: 11, offset: [0, -0.26, 0] },
  { name: 'r_shoulder', parent: 8, offset: [-0.19, 0.42, 0] },
  { name: 'r_elbow', parent: 13, offset: [0, -0.29, 0] },
  { name: 'r_wrist', parent: 14, offset: [0, -0.26, 0] },
];

const kDeg = Math.PI / 180;

function bake(joints, name, duration, loops, frames, pose) {
  const J = joints.length;
  const quats = new Float32Array(frames * J * 4);
  const root = new Float32Array(frames * 3);
  const index = new Map(joints.map((j, i) => [j.name, i]));
  for (let f = 0; f < frames; ++f) {
    const p = f / frames;
    const angles = pose(p);  // name → [x, y, z] degrees; 'root' → [x, y, z] metres
    for (let j = 0; j < J; ++j) quats[(f * J + j) * 4 + 3] = 1;
    for (const [n, a] of Object.entries(angles)) {
      if (n === 'root') { root.set(a, f * 3); continue; }
      const j = index.get(n);
      if (j !== undefined) quatFromZXY(a[0] * kDeg, a[1] * kDeg, a[2] * kDeg, quats, (f * J + j) * 4);
    }
    if (!angles.root) root.set([0, joints[0] ? joints[0].offset[1] : 0.95, 0], f * 3);
  }
  return { name, duration, loops, frames, jointCount: J, quats, root };
}

export function makeWalkClip(joints = kHanimSkeleton) {
  const h = joints[0] ? joints[0].offset[1] : 0.95;
  return bake(joints, 'walk', 1.12, true, 28, (p) => {
    const s = Math.cos(2 * Math.PI * p);  // +1: left leg forward (heel strike at 0)
    const k = (x) => Math.max(0, Math.sin(2 * Math.PI * x));
    return {
      root: [0, h - 0.03 + 0.025 * Math.abs(Math.cos(2 * Math.PI * p)), 0],
      l_hip: [-25 * s, 0, 0], r_hip: [25 * s, 0, 0],
      l_knee: [10 + 45 * k(p + 0.5), 0, 0], r_knee: [10 + 45 * k(p), 0, 0],
      l_ankle: [-8 * s, 0, 0], r_ankle: [8 * s, 0, 0],
      l_shoulder: [20 * s, 0, 4], r_shoulder: [-20 * s, 0, -4],
      l_elbow: [-15 - 10 * Math.max(0, -s), 0, 0], r_elbow: [-15 - 10 * Math.max(0, s), 0, 0],
      vl5: [3, 6 * s, 0], skullbase: [-2, -4 * s, 0],
    };
  });
}

export function makeIdleClip(joints = kHanimSkeleton) {
  const h = joints[0] ? joints[0].offset[1] : 0.95;
  return bake(joints, 'idle', 2, true, 50, (p) => {
    const s = Math.sin(2 * Math.PI * p);
    return {
      root: [0.01 * s, h, 0],
      l_shoulder: [0, 0, 5], r_shoulder: [0, 0, -5],
      l_elbow: [-8, 0, 0], r_elbow: [-8, 0, 0],
      vl5: [1 + s, 0, 0], skullbase: [2 * s, 3 * Math.sin(Math.PI * p), 0],
    };
  });
}

/** The Common Ground gestures as procedural clips (not looping, ~2 s), for worlds whose clip list
 * has none: 'wave' (right arm raised, forearm swinging), 'nod' (head down and up twice), 'point'
 * (right arm held forward), 'call_out' (both hands raised to the mouth, head up). */
export function makeGestureClip(name, joints = kHanimSkeleton) {
  const h = joints[0] ? joints[0].offset[1] : 0.95;
  const ease = (p) => Math.sin(Math.PI * Math.min(1, Math.max(0, p)));  // 0 → 1 → 0 over the clip
  const poses = {
    wave: (p) => ({ r_shoulder: [0, 0, -150 * Math.min(1, 3 * ease(p))], r_elbow: [0, 0, -30 * Math.sin(6 * Math.PI * p) * ease(p)] }),
    nod: (p) => ({ skullbase: [25 * Math.abs(Math.sin(2 * Math.PI * p)), 0, 0], vl5: [4 * ease(p), 0, 0] }),
    point: (p) => ({ r_shoulder: [-85 * Math.min(1, 3 * ease(p)), 0, -10], r_elbow: [-5, 0, 0] }),
    call_out: (p) => ({
      l_shoulder: [-70 * ease(p), 0, 20 * ease(p)], r_shoulder: [-70 * ease(p), 0, -20 * ease(p)],
      l_elbow: [-110 * ease(p), 0, 0], r_elbow: [-110 * ease(p), 0, 0], skullbase: [-15 * ease(p), 0, 0],
    }),
  };
  const pose = poses[name] || poses.wave;
  return bake(joints, name, 2, false, 50, (p) => ({ root: [0, h, 0], l_shoulder: [0, 0, 5], r_shoulder: [0, 0, -5], ...pose(p) }));
}
