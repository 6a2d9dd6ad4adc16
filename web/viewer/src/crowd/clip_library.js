// Motion clips as the viewer plays them: each clip baked to per-frame joint quaternions (skeleton
// order) and a root position, sampled at any phase with normalised lerp between frames. Reads the
// BVH files the server lists in the world description (three's BVHLoader parses them) or the
// procedural clips (procedural_clips.js) when a clip has no file; writes nothing.
import { BVHLoader } from 'three/examples/jsm/loaders/BVHLoader.js';
import { makeIdleClip, makeWalkClip } from './procedural_clips.js';

export { sampleClip, quatFromZXY } from './pose_math.js';

/** Bakes a BVHLoader result onto `jointNames` (joints the file lacks keep identity). */
export function bakeBvh(result, jointNames, name, loops) {
  const J = jointNames.length;
  const tracks = new Map(result.clip.tracks.map((t) => [t.name, t]));
  const anyTrack = result.clip.tracks[0];
  const frames = anyTrack ? anyTrack.times.length : 1;
  const quats = new Float32Array(frames * J * 4);
  const root = new Float32Array(frames * 3);
  for (let j = 0; j < J; ++j) {
    const t = tracks.get(`${jointNames[j]}.quaternion`);
    for (let f = 0; f < frames; ++f) {
      const o = (f * J + j) * 4;
      if (t && t.values.length >= (f + 1) * 4) quats.set(t.values.subarray(f * 4, f * 4 + 4), o);
      else quats[o + 3] = 1;
    }
  }
  // The root's position channels hold where the hips are (0.95 m up in the bundled clips); three's
  // BVHLoader adds the root's OFFSET to them, which would lift every body by that offset again.
  const rootTrack = tracks.get(`${jointNames[0]}.position`);
  const offset = result.skeleton?.bones?.[0]?.position ?? { x: 0, y: 0, z: 0 };
  for (let f = 0; f < frames; ++f) {
    if (!rootTrack || rootTrack.values.length < (f + 1) * 3) continue;
    const v = rootTrack.values;
    root.set([v[f * 3] - offset.x, v[f * 3 + 1] - offset.y, v[f * 3 + 2] - offset.z], f * 3);
  }
  const frameTime = frames > 1 && anyTrack ? anyTrack.times[1] - anyTrack.times[0] : 0.04;
  return { name, duration: frames * frameTime, loops, frames, jointCount: J, quats, root };
}

/** All clips of a world description, by id. Clips without a url (or that fail to load) get the
 * procedural walk (names containing "walk") or idle clip. */
export class ClipLibrary {
  constructor(description) {
    this.joints = description.skeleton.joints;
    this.names = this.joints.map((j) => j.name);
    this.rootHeight = this.joints[0] ? this.joints[0].offset[1] : 0.95;
    this.clips = [];
    this.info = description.clips || [];
    this.walkIds = new Set();
    for (const c of this.info) {
      if (/walk/i.test(c.name)) this.walkIds.add(c.id);
      this.clips[c.id] = this.fallback(c);
    }
  }

  fallback(c) {
    const base = /walk/i.test(c.name) ? makeWalkClip(this.joints) : makeIdleClip(this.joints);
    return { ...base, name: c.name, loops: c.loops !== false };
  }

  /** Loads every clip that has a url (relative to `baseUrl`); resolves when all are settled. */
  async load(baseUrl = '') {
    const loader = new BVHLoader();
    const jobs = this.info.filter((c) => c.url).map(async (c) => {
      try {
        const res = await fetch(baseUrl + c.url);
        if (!res.ok) throw new Error(`HTTP ${res.status}`);
        const parsed = loader.parse(await res.text());
        this.clips[c.id] = bakeBvh(parsed, this.names, c.name, c.loops !== false);
      } catch (e) {
        console.warn(`throng: clip ${c.name} (${c.url}) not loaded: ${e.message}; using a procedural clip`);
      }
    });
    await Promise.all(jobs);
  }

  get(id) {
    return this.clips[id] || this.clips[this.walkIds.values().next().value] || makeIdleClip(this.joints);
  }

  isWalk(id) { return this.walkIds.has(id); }

  name(id) { return (this.info[id] && this.info[id].name) || `clip ${id}`; }

  walkClipId() { const v = this.walkIds.values().next(); return v.done ? 0 : v.value; }

  idleClipId() {
    const c = this.info.find((i) => /idle/i.test(i.name));
    return c ? c.id : 0;
  }
}
