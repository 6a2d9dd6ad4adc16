// Adapter between the viewer and web/protocol's decoder (decode.js, owned by the protocol
// library): turns each server message into a plain object {type, …} in viewer units — world
// description parsed, 64-bit values as BigInt, positions in metres, angles in radians, phases in
// [0, 1) — and applies crowd frames to the delta state (CrowdDecoder), converting them to the
// viewer's frame layout (sources/frame.js). The only file that knows web/protocol's API.
import { decodeAny, CrowdDecoder } from '../../../protocol/decode.js';
import { makeFrame } from '../sources/frame.js';

const kTurn16 = (2 * Math.PI) / 65536;
const angle16 = (u) => ((u << 16) >> 16) * kTurn16;  // uint16 1/65536 turn → [−π, π)

/** Viewer frame from CrowdDecoder's agents (wire units). */
export function frameFromWire(header, agents) {
  const f = makeFrame(agents.length);
  f.simTick = Number(header.simTick);
  for (let i = 0; i < agents.length; ++i) {
    const a = agents[i];
    f.ids[i] = a.id; f.tier[i] = a.tier;
    f.x[i] = a.x / 100; f.y[i] = a.y / 100; f.z[i] = a.z / 100;
    f.yaw[i] = angle16(a.yaw);
    f.clip[i] = a.clip; f.phase[i] = a.phase / 256;
    if (a.tier === 0 && a.joints.length) f.joints.set(a.id, Float32Array.from(a.joints, (q) => q * kTurn16));
  }
  return f;
}

export function createDecoder() {
  const crowd = new CrowdDecoder();
  return {
    decode(bytes) {
      const m = decodeAny(bytes);
      switch (m.type) {
        case 'Welcome': return { ...m, world: JSON.parse(m.world) };
        case 'Joined': return { ...m, token: BigInt(m.token) };
        case 'Heartbeat': return { ...m, timeUs: BigInt(m.timeUs), echoUs: BigInt(m.echoUs) };
        case 'Move':
          return { type: 'Move', participantId: m.subject.kind === 1 ? Number(m.subject.value) : -1, seq: m.seq,
            x: m.x / 100, y: m.y / 100, z: m.z / 100, yaw: angle16(m.yaw) };
        case 'Joints': case 'HandJoints':
          return { type: m.type, participantId: m.subject.kind === 1 ? Number(m.subject.value) : -1,
            angles: m.angles.map((q) => q * kTurn16) };
        case 'CrowdFrame': {
          let view;
          try {
            view = crowd.apply(m);
          } catch (e) {
            // A delta against a frame we no longer hold: skip it (no Ack) until a key frame comes.
            if (/baseFrame/.test(e.field || '') || /base frame/.test(e.message)) return { type: 'Skip', reason: e.message };
            throw e;
          }
          return { type: 'CrowdFrame', frameNumber: view.header.frameNumber, header: view.header,
            frame: frameFromWire(view.header, view.agents) };
        }
        default: return m;
      }
    },
  };
}
