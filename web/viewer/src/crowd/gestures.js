// Participants' gestures — pure, no three.js. The local participant plays a gesture (wave, nod,
// point, call out: the world's clips of those names, else procedural ones) on its avatar; while
// it plays, its joint angles are sampled from the clip (3 per skeleton joint, radians, BVH order:
// the same convention as near-tier crowd joints) and sent as Joints at ~10 Hz. Remote avatars
// show the latest relayed Joints of their participant until none has arrived for 1 s, then go
// back to their own idle/walk pose. Reads baked clips (clip_library.js); writes nothing else.
import { sampleClip, eulerZXYFromQuat } from './pose_math.js';
import { makeGestureClip } from './procedural_clips.js';

/** The gestures a participant can play: key (clip name), button label, keyboard key. */
export const kGestures = Object.freeze([
  { name: 'wave', label: 'Wave', key: '1', match: /wave/i },
  { name: 'nod', label: 'Nod', key: '2', match: /nod/i },
  { name: 'point', label: 'Point', key: '3', match: /point/i },
  { name: 'call_out', label: 'Call out', key: '4', match: /call[\s_-]*out|shout/i },
]);

/** How long [ms] a remote avatar keeps the last relayed Joints. */
export const kJointsTimeoutMs = 1000;
/** Interval [ms] between two Joints messages while a gesture plays (~10 Hz). */
export const kJointsIntervalMs = 100;

/** The clip of gesture `name`: the world's clip of that name (`clips`: a ClipLibrary) when it has
 * one, else the procedural one for `joints`. */
export function gestureClip(clips, name, joints) {
  const g = kGestures.find((x) => x.name === name);
  const info = clips && g ? clips.info.find((c) => g.match.test(c.name)) : null;
  if (info) return { ...clips.get(info.id), loops: false };
  return makeGestureClip(name, joints);
}

/** Joint angles (Float32Array, 3 per joint: x, y, z radians) of `clip` at `phase`. */
export function sampleJointAngles(clip, phase, out = new Float32Array(clip.jointCount * 3)) {
  const q = new Float32Array(clip.jointCount * 4);
  sampleClip(clip, phase, q, null);
  for (let j = 0; j < clip.jointCount; ++j) eulerZXYFromQuat(q, j * 4, out, j * 3);
  return out;
}

/** The local participant's gesture: start(name, clip, now) plays it once; sample(now) gives its
 * joint angles while it plays (null after), and whether a Joints message is due (~10 Hz). */
export class GesturePlayer {
  constructor() { this.playing = null; this.lastSentAt = -Infinity; }

  start(name, clip, nowMs) { this.playing = { name, clip, startMs: nowMs }; this.lastSentAt = -Infinity; }

  /** {name, phase, angles, send} while a gesture plays, else null. */
  sample(nowMs) {
    const p = this.playing;
    if (!p) return null;
    const phase = (nowMs - p.startMs) / 1000 / p.clip.duration;
    if (phase >= 1) { this.playing = null; return null; }
    const send = nowMs - this.lastSentAt >= kJointsIntervalMs;
    if (send) this.lastSentAt = nowMs;
    return { name: p.name, phase, angles: sampleJointAngles(p.clip, phase), send };
  }
}

/** Latest relayed Joints per participant; stale (older than kJointsTimeoutMs) ones are ignored. */
export class RemoteJoints {
  constructor(timeoutMs = kJointsTimeoutMs) { this.timeoutMs = timeoutMs; this.latest = new Map(); this.received = 0; }

  /** Relayed Joints of participant `id` (angles in radians) received at `nowMs`. */
  set(id, angles, nowMs) { this.latest.set(id, { angles, at: nowMs }); this.received++; }

  /** The angles to pose participant `id` with, or null (idle pose) when none came in the last second. */
  get(id, nowMs) {
    const e = this.latest.get(id);
    if (!e) return null;
    if (nowMs - e.at > this.timeoutMs) { this.latest.delete(id); return null; }
    return e.angles;
  }

  delete(id) { this.latest.delete(id); }
}
