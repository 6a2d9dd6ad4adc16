// Procedural body geometry built from the skeleton of the world description (no modelled asset):
// one solid per bone segment (parent joint → child joint), plus pelvis, head, hands and feet at
// the leaves, placed in the rest pose. Two variants:
//   skinned (near level): capsules and a sphere head, each vertex skinned (weight 1) to its bone;
//   low-poly (middle level and the billboard atlas source): boxes, with per-vertex `part` (0 torso,
//   1 left leg, 2 right leg, 3 left arm, 4 right arm) and `pivot` (hip or shoulder joint) so a
//   vertex shader can swing the limbs from a per-instance walk phase.
// Reads the skeleton joints [{name, parent, offset [m]}] (Y up, facing +Z); writes BufferGeometry.
import * as THREE from 'three';
import { mergeGeometries } from 'three/examples/jsm/utils/BufferGeometryUtils.js';

/** Rest-pose world positions of the joints (parents come before children). */
export function restPositions(joints) {
  const w = [];
  joints.forEach((j, i) => {
    const o = new THREE.Vector3(...j.offset);
    w[i] = j.parent >= 0 && j.parent < i ? w[j.parent].clone().add(o) : o;
  });
  return w;
}

function limbOf(joints, i) {
  // Walks up to the joint below the root/pelvis to find which limb a joint belongs to.
  for (let k = i; k >= 0; k = joints[k].parent) {
    const n = joints[k].name.toLowerCase();
    const left = /^l_|left/.test(n), right = /^r_|right/.test(n);
    if (/hip|thigh|upleg/.test(n)) return { part: left ? 1 : right ? 2 : 0, pivot: k };
    if (/shoulder|upperarm|uparm/.test(n)) return { part: left ? 3 : right ? 4 : 0, pivot: k };
    if (joints[k].parent < 0) break;
  }
  return { part: 0, pivot: 0 };
}

function thickness(name, length) {
  const n = name.toLowerCase();
  if (/hip|thigh/.test(n)) return [0.15, 0.15];
  if (/knee|shin|leg/.test(n)) return [0.11, 0.11];
  if (/shoulder|upperarm/.test(n)) return [0.095, 0.095];
  if (/elbow|forearm/.test(n)) return [0.08, 0.08];
  if (length > 0.3) return [0.36, 0.22];  // the spine segment: the torso
  return [0.24, 0.2];
}

/** Solids of the body: [{geometry (BoxGeometry or capsule/sphere), bone, part, pivot}]. */
function solids(joints, lowPoly) {
  const W = restPositions(joints);
  const children = joints.map(() => []);
  joints.forEach((j, i) => { if (j.parent >= 0) children[j.parent].push(i); });
  const out = [];
  const up = new THREE.Vector3(0, 1, 0);
  const add = (geometry, bone, limbJoint) => {
    const { part, pivot } = limbOf(joints, limbJoint);
    out.push({ geometry, bone, part, pivot: W[pivot].clone() });
  };
  const segment = (from, to, w, d, bone, limbJoint) => {
    const dir = to.clone().sub(from);
    const len = dir.length();
    const g = lowPoly
      ? new THREE.BoxGeometry(w, len + Math.min(w, d) * 0.5, d)
      : new THREE.CapsuleGeometry(Math.min(w, d) / 2, Math.max(len - Math.min(w, d) * 0.2, 0.01), 3, 8);
    if (!lowPoly && w > d * 1.3) g.scale(w / d, 1, 1);
    g.applyQuaternion(new THREE.Quaternion().setFromUnitVectors(up, dir.normalize()));
    g.translate(...from.clone().add(to).multiplyScalar(0.5).toArray());
    add(g, bone, limbJoint);
  };
  joints.forEach((j, i) => {
    const p = j.parent;
    const name = j.name.toLowerCase();
    if (p >= 0) {
      const len = W[i].distanceTo(W[p]);
      const childName = name;
      const skip = len < 0.02 || /shoulder|clav|hip/.test(childName);
      if (!skip) {
        const [w, d] = thickness(joints[p].name, len);
        segment(W[p], W[i], w, d, p, p);
      }
    }
    if (children[i].length === 0) {
      // Leaves: head, feet, hands.
      let g;
      if (/skull|head|neck/.test(name)) {
        g = lowPoly ? new THREE.BoxGeometry(0.19, 0.23, 0.21) : new THREE.SphereGeometry(0.115, 12, 9);
        if (!lowPoly) g.scale(0.95, 1.1, 1);
        g.translate(W[i].x, W[i].y + 0.12, W[i].z + 0.01);
      } else if (/ankle|foot|toe/.test(name)) {
        g = new THREE.BoxGeometry(0.1, 0.07, 0.25);
        g.translate(W[i].x, W[i].y - 0.04, W[i].z + 0.06);
      } else if (/wrist|hand/.test(name)) {
        g = new THREE.BoxGeometry(0.07, 0.16, 0.09);
        g.translate(W[i].x, W[i].y - 0.08, W[i].z);
      } else {
        g = new THREE.BoxGeometry(0.06, 0.06, 0.06);
        g.translate(W[i].x, W[i].y, W[i].z);
      }
      add(g, i, i);
    }
  });
  // Pelvis: a box around the hips, on the joint the hips hang from.
  const hips = joints.map((j, i) => [j, i]).filter(([j]) => /hip/i.test(j.name));
  if (hips.length === 2) {
    const a = W[hips[0][1]], b = W[hips[1][1]];
    const g = new THREE.BoxGeometry(Math.abs(a.x - b.x) + 0.16, 0.2, 0.2);
    g.translate((a.x + b.x) / 2, (a.y + b.y) / 2 + 0.06, (a.z + b.z) / 2);
    add(g, hips[0][0].parent, hips[0][0].parent);
  }
  return out;
}

function withAttributes(list, extra) {
  const parts = list.map((s) => {
    const g = s.geometry.index ? s.geometry : s.geometry;
    const n = g.attributes.position.count;
    extra(g, s, n);
    return g;
  });
  const merged = mergeGeometries(parts.map((g) => (g.index ? g : g)), false);
  merged.computeBoundingSphere();
  return merged;
}

/** Geometry for a SkinnedMesh bound to bones created in joint order. */
export function skinnedBodyGeometry(joints) {
  return withAttributes(solids(joints, false), (g, s, n) => {
    const idx = new Uint16Array(n * 4), wt = new Float32Array(n * 4);
    for (let v = 0; v < n; ++v) { idx[v * 4] = s.bone; wt[v * 4] = 1; }
    g.setAttribute('skinIndex', new THREE.Uint16BufferAttribute(idx, 4));
    g.setAttribute('skinWeight', new THREE.Float32BufferAttribute(wt, 4));
  });
}

/** Low-polygon geometry with `part` and `pivot` attributes for the instanced walk shader. */
export function lowPolyBodyGeometry(joints) {
  return withAttributes(solids(joints, true), (g, s, n) => {
    g.setAttribute('part', new THREE.Float32BufferAttribute(new Float32Array(n).fill(s.part), 1));
    const pv = new Float32Array(n * 3);
    for (let v = 0; v < n; ++v) pv.set([s.pivot.x, s.pivot.y, s.pivot.z], v * 3);
    g.setAttribute('pivot', new THREE.Float32BufferAttribute(pv, 3));
  });
}
