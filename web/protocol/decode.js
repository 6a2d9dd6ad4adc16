// throng shared-world protocol, version 2 — JavaScript decoder (docs/protocol.md). Plain ES
// module; zstd payloads go through fzstd. decodeAny(bytes) → a plain object in wire units
// (cm, 1/65536 turn, 1/256 phase, int16 joint angles; 64-bit values as decimal strings), or
// throws ProtocolError {offset, field, message}. CrowdDecoder applies crowd frames to their base.
import { decompress } from 'fzstd';

export const PROTOCOL_VERSION = 2;  // 2: Presence's optional trailing `avatar` (version-1 messages still decode)
export const MAGIC = 0x54;
export const LIMITS = { maxMessageSize: 8 << 20, maxCrowdPayload: 16 << 20, maxWorldSize: 64 << 20,
  maxNameLength: 64, maxTextLength: 1024, maxAgents: 65536, maxJoints: 128, maxExpressionWeights: 64,
  maxCrowdJson: 1 << 20, minFragments: 2, maxFragments: 8192, cookieSize: 16 };
export const TYPES = ['?', 'Hello', 'Refuse', 'Welcome', 'Join', 'Joined', 'Leave', 'Heartbeat', 'Bye', 'Move',
  'Joints', 'HandJoints', 'FaceExpression', 'Guide', 'Release', 'GuideResult', 'Ack', 'CrowdFrame',
  'Presence', 'ReplayControl', 'ReplayStatus', 'InsertCrowd', 'RemoveCrowd', 'CrowdResult',
  'Fragment', 'Cookie', 'UdpHello'];
/** ReplayControl commands (value: 0 for play/pause, time [s] for seek, factor for speed). */
export const REPLAY_COMMANDS = Object.freeze({ Play: 0, Pause: 1, Seek: 2, Speed: 3 });
export const MAX_REPLAY_SPEED = 64;
const MASK = { x: 1, y: 2, z: 4, yaw: 8, clip: 16, phase: 32, pose: 64, tier: 128 };

export class ProtocolError extends Error {
  constructor(field, offset, message) {
    super(`${field}: ${message} at byte ${offset}`);
    this.field = field;
    this.offset = offset;
  }
}

class Reader {
  constructor(bytes, name) { this.b = bytes; this.p = 0; this.name = name; }
  fail(field, msg, at = this.p) { throw new ProtocolError(`/${this.name}/${field}`, at, msg); }
  need(n, field) { if (this.b.length - this.p < n) this.fail(field, `truncated: ${this.b.length - this.p} bytes left, ${n} needed`); }
  u8(f) { this.need(1, f); return this.b[this.p++]; }
  u16(f) { this.need(2, f); const v = this.b[this.p] | (this.b[this.p + 1] << 8); this.p += 2; return v; }
  u32(f) { this.need(4, f); const v = new DataView(this.b.buffer, this.b.byteOffset + this.p, 4).getUint32(0, true); this.p += 4; return v; }
  u64(f) { this.need(8, f); const v = new DataView(this.b.buffer, this.b.byteOffset + this.p, 8).getBigUint64(0, true); this.p += 8; return v.toString(); }
  i32(f) { return this.u32(f) | 0; }
  f32(f) { this.need(4, f); const v = new DataView(this.b.buffer, this.b.byteOffset + this.p, 4).getFloat32(0, true); this.p += 4; return v; }
  f64(f) { this.need(8, f); const v = new DataView(this.b.buffer, this.b.byteOffset + this.p, 8).getFloat64(0, true); this.p += 8; return v; }
  varintBig(f) {
    const at = this.p; let v = 0n;
    for (let i = 0; i < 10; i++) {
      if (this.p >= this.b.length) this.fail(f, 'truncated varint', at);
      const c = this.b[this.p++];
      if (i === 9 && c > 1) this.fail(f, 'varint overflows 64 bits', at);
      v |= BigInt(c & 0x7f) << BigInt(7 * i);
      if (!(c & 0x80)) return v;
    }
    this.fail(f, 'varint longer than 10 bytes', at);
  }
  varint(f, max = 0xffffffff) {
    const at = this.p; const v = this.varintBig(f);
    if (v > BigInt(max)) this.fail(f, `value ${v} out of range, at most ${max}`, at);
    return Number(v);
  }
  svarint(f, min, max) {
    const at = this.p; const z = this.varintBig(f);
    const v = (z & 1n) ? -((z >> 1n) + 1n) : (z >> 1n);
    if (v < BigInt(min) || v > BigInt(max)) this.fail(f, `value ${v} out of range [${min}, ${max}]`, at);
    return Number(v);
  }
  string(f, max) {
    const at = this.p; const n = this.varint(f, 0xffffffff);
    if (n > max) this.fail(f, `string of ${n} bytes too long (at most ${max})`, at);
    return new TextDecoder().decode(this.bytes(f, n));
  }
  bytes(f, n) { this.need(n, f); const s = this.b.subarray(this.p, this.p + n); this.p += n; return s; }
  end() { if (this.p !== this.b.length) this.fail('end', `${this.b.length - this.p} trailing bytes`); }
}

function hex(bytes) { return Array.from(bytes, (b) => b.toString(16).padStart(2, '0')).join(''); }
function enumByte(r, f, max) { const at = r.p; const v = r.u8(f); if (v > max) r.fail(f, `unknown value ${v} (0..${max})`, at); return v; }
function flag(r, f) { const at = r.p; const v = r.u8(f); if (v > 1) r.fail(f, `value ${v}, expected 0 or 1`, at); return v === 1; }
function seconds(r, f) {
  const at = r.p; const v = r.f64(f);
  if (!(Number.isFinite(v) && v >= 0)) r.fail(f, `${f} ${v} s, expected a finite time >= 0 s`, at);
  return v;
}
function replayValue(r, command) {
  const at = r.p; const v = r.f64('value');
  const bad = (why) => r.fail('value', `value ${v} for ${why}`, at);
  if (command <= 1 && v !== 0) bad('play/pause, expected 0');
  if (command === 2 && !(Number.isFinite(v) && v >= 0)) bad('seek, expected a finite time >= 0 s');
  if (command === 3 && !(Number.isFinite(v) && v > 0 && v <= MAX_REPLAY_SPEED)) bad('speed, expected a finite factor in (0, 64]');
  return v;
}
function subject(r) {
  const kind = enumByte(r, 'subject', 1);
  return { kind, value: kind === 0 ? r.u64('subject') : String(r.varint('subject')) };
}
function angles(r) {
  const at = r.p; const n = r.u8('jointCount');
  if (n > LIMITS.maxJoints) r.fail('jointCount', `${n} joints (at most ${LIMITS.maxJoints})`, at);
  const a = [];
  for (let i = 0; i < n * 3; i++) a.push((r.u16('angles') << 16) >> 16);
  return a;
}
function unzstd(r, field, data, size) {
  let out;
  try { out = decompress(data); } catch (e) { r.fail(field, `corrupt zstd frame (${e.message})`); }
  if (out.length !== size) r.fail(field, `zstd frame holds ${out.length} bytes, header says ${size}`);
  return out;
}

const bodies = {
  Hello: (r) => ({ protocolVersion: r.u16('protocolVersion'), clientKind: enumByte(r, 'clientKind', 2), clientName: r.string('clientName', LIMITS.maxNameLength) }),
  Refuse: (r) => ({ protocolVersion: r.u16('protocolVersion'), reason: enumByte(r, 'reason', 13), text: r.string('text', LIMITS.maxTextLength) }),
  Welcome: (r) => {
    const m = { protocolVersion: r.u16('protocolVersion'), serverName: r.string('serverName', LIMITS.maxNameLength) };
    m.tickRateHz = r.f32('tickRateHz');
    if (!(Number.isFinite(m.tickRateHz) && m.tickRateHz > 0)) r.fail('tickRateHz', `tick rate ${m.tickRateHz}, expected > 0`, r.p - 4);
    m.worldEncoding = enumByte(r, 'worldEncoding', 1);
    m.worldSize = r.varint('worldSize', LIMITS.maxWorldSize);
    const n = r.varint('worldLength', LIMITS.maxMessageSize);
    if (m.worldEncoding === 0 && n !== m.worldSize) r.fail('worldLength', `raw JSON world of ${n} bytes, expected worldSize`);
    const data = r.bytes('world', n);
    m.world = new TextDecoder().decode(m.worldEncoding === 1 ? unzstd(r, 'world', data, m.worldSize) : data);
    return m;
  },
  Join: (r) => ({ name: r.string('name', LIMITS.maxNameLength), avatar: r.u16('avatar') }),
  Joined: (r) => ({ participantId: r.u32('participantId'), token: r.u64('token') }),
  Leave: (r) => ({ token: r.u64('token') }),
  Heartbeat: (r) => ({ token: r.u64('token'), timeUs: r.u64('timeUs'), echoUs: r.u64('echoUs') }),
  Bye: (r) => ({ reason: enumByte(r, 'reason', 13), text: r.string('text', LIMITS.maxTextLength) }),
  Move: (r) => ({ subject: subject(r), seq: r.varint('seq'), x: r.i32('x'), y: r.i32('y'), z: r.i32('z'), yaw: r.u16('yaw') }),
  Joints: (r) => ({ subject: subject(r), seq: r.varint('seq'), angles: angles(r) }),
  HandJoints: (r) => ({ subject: subject(r), seq: r.varint('seq'), angles: angles(r) }),
  FaceExpression: (r) => {
    const m = { subject: subject(r), seq: r.varint('seq'), expression: r.u16('expression') };
    const at = r.p; const n = r.u8('weightCount');
    if (n > LIMITS.maxExpressionWeights) r.fail('weightCount', `${n} weights`, at);
    m.weights = Array.from(r.bytes('weights', n));
    return m;
  },
  Guide: (r) => ({ token: r.u64('token'), groupId: r.varint('groupId') }),
  Release: (r) => ({ token: r.u64('token'), groupId: r.varint('groupId') }),
  GuideResult: (r) => {
    const groupId = r.varint('groupId'); const at = r.p; const flags = r.u8('flags');
    if (flags > 3) r.fail('flags', `unknown flag bits ${flags}`, at);
    return { groupId, ok: (flags & 1) !== 0, guiding: (flags & 2) !== 0, reason: enumByte(r, 'reason', 13) };
  },
  Ack: (r) => ({ token: r.u64('token'), frameNumber: r.varint('frameNumber') }),
  Presence: (r) => {
    const m = { participantId: r.varint('participantId'), present: flag(r, 'present'), name: r.string('name', LIMITS.maxNameLength) };
    if (r.p < r.b.length) m.avatar = r.u16('avatar');  // version 2: the participant's look (Join's avatar)
    return m;
  },
  ReplayControl: (r) => {
    const token = r.u64('token'); const command = enumByte(r, 'command', 3);
    return { token, command, value: replayValue(r, command) };
  },
  ReplayStatus: (r) => {
    const m = { time: seconds(r, 'time'), duration: seconds(r, 'duration'), playing: flag(r, 'playing') };
    const at = r.p; m.speed = r.f32('speed');
    if (!(Number.isFinite(m.speed) && m.speed > 0)) r.fail('speed', `speed ${m.speed}, expected a finite factor > 0`, at);
    return m;
  },
  InsertCrowd: (r) => ({ token: r.u64('token'), requestId: r.varint('requestId'), crowdJson: r.string('crowdJson', LIMITS.maxCrowdJson) }),
  RemoveCrowd: (r) => ({ token: r.u64('token'), requestId: r.varint('requestId'), crowdId: r.string('crowdId', LIMITS.maxNameLength) }),
  CrowdResult: (r) => ({
    requestId: r.varint('requestId'), ok: flag(r, 'ok'), crowdIndex: r.varint('crowdIndex'),
    crowdId: r.string('crowdId', LIMITS.maxNameLength), text: r.string('text', LIMITS.maxTextLength),
  }),
  // One piece of a larger message (UDP only: browsers never receive it; decoded for tools and tests).
  Fragment: (r) => {
    const messageId = r.varintBig('messageId').toString();
    const indexAt = r.p; const index = r.varint('index');
    const countAt = r.p; const count = r.varint('count');
    if (count < LIMITS.minFragments || count > LIMITS.maxFragments) {
      r.fail('count', `count ${count}, expected ${LIMITS.minFragments}..${LIMITS.maxFragments} fragments`, countAt);
    }
    if (index >= count) r.fail('index', `index ${index} of ${count} fragments, expected an index below count`, indexAt);
    if (r.p >= r.b.length) r.fail('payload', 'an empty payload, expected at least 1 payload byte');
    return { messageId, index, count, payload: Array.from(r.bytes('payload', r.b.length - r.p)) };
  },
  // The UDP handshake (browsers never see it; decoded for tools and tests). Cookies as hex.
  Cookie: (r) => ({ cookie: hex(r.bytes('cookie', LIMITS.cookieSize)) }),
  UdpHello: (r) => {
    const cookie = hex(r.bytes('cookie', LIMITS.cookieSize));
    let at = r.p; const magic = r.u8('hello');
    if (magic !== MAGIC) r.fail('hello', `bad magic byte ${magic} of the Hello, expected 0x54`, at);
    at = r.p; const type = r.u8('hello');
    if (type !== 1) r.fail('hello', `a message of type ${type} after the cookie, expected a Hello (type 1)`, at);
    return { cookie, hello: bodies.Hello(r) };
  },
  CrowdFrame: (r) => {
    const at = r.p; const flags = r.u8('flags');
    if (flags & ~3) r.fail('flags', `unknown flag bits ${flags}`, at);
    const h = { compressed: (flags & 1) !== 0, farIncluded: (flags & 2) !== 0 };
    h.frameNumber = r.varint('frameNumber');
    if (h.frameNumber === 0) r.fail('frameNumber', 'frame number 0');
    h.baseFrame = r.varint('baseFrame');
    if (h.baseFrame >= h.frameNumber) r.fail('baseFrame', `base frame ${h.baseFrame} not before frame ${h.frameNumber}`);
    h.simTick = r.varintBig('simTick').toString();
    h.animationInterval = r.u8('animationInterval');
    if (h.animationInterval === 0) r.fail('animationInterval', 'animation interval 0');
    h.jointCount = r.u8('jointCount');
    if (h.jointCount > LIMITS.maxJoints) r.fail('jointCount', `${h.jointCount} joints`);
    h.jointShift = r.u8('jointShift');
    if (h.jointShift > 8) r.fail('jointShift', `joint shift ${h.jointShift}`);
    h.nearCount = r.varint('nearCount', LIMITS.maxAgents);
    h.middleCount = r.varint('middleCount', LIMITS.maxAgents);
    h.farCount = r.varint('farCount', LIMITS.maxAgents);
    if (h.nearCount + h.middleCount + h.farCount > LIMITS.maxAgents) r.fail('farCount', 'too many agents');
    h.payloadSize = r.varint('payloadSize', LIMITS.maxCrowdPayload);
    const rest = r.bytes('payload', r.b.length - r.p);
    if (!h.compressed && rest.length !== h.payloadSize) r.fail('payload', `${rest.length} payload bytes, expected ${h.payloadSize}`);
    return { header: h, payload: h.compressed ? unzstd(r, 'payload', rest, h.payloadSize) : rest };
  },
};

/** Decodes one message (Uint8Array) into {type, ...fields}; throws ProtocolError. */
export function decodeAny(bytes) {
  if (bytes.length > LIMITS.maxMessageSize) throw new ProtocolError('/message/size', 0, `message of ${bytes.length} bytes too large`);
  const r0 = new Reader(bytes, 'message');
  const magic = r0.u8('magic');
  if (magic !== MAGIC) r0.fail('magic', `bad magic byte ${magic}, expected 0x54`, 0);
  const t = r0.u8('type');
  if (t === 0 || t >= TYPES.length) r0.fail('type', `unknown message type ${t}`, 1);
  const r = new Reader(bytes, TYPES[t]);
  r.p = 2;
  const m = { type: TYPES[t], ...bodies[TYPES[t]](r) };
  r.end();
  return m;
}

function readIds(r, n, field) {
  const ids = new Array(n); let prev = -1;
  for (let i = 0; i < n; i++) {
    const at = r.p; const id = prev + 1 + r.varint(field);
    if (id > 0xffffffff) r.fail(field, `agent id ${id} beyond 32 bits`, at);
    ids[i] = prev = id;
  }
  return ids;
}

function tierRules(a, tier, J) {
  a.tier = tier;
  if (tier === 2) { a.yaw = 0; a.clip = 0; a.phase = 0; a.joints = []; }
  else if (tier === 1) { a.yaw &= 0xff00; a.joints = []; }
  else if (a.joints.length !== 3 * J) a.joints = new Array(3 * J).fill(0);
}

/** Client-side crowd state: keeps the last `historyFrames` reconstructed frames as bases. */
export class CrowdDecoder {
  constructor(historyFrames = 64) { this.historyFrames = historyFrames; this.history = new Map(); this.newestFrame = 0; }

  /** Applies a decoded CrowdFrame message; returns {header, agents} (agents ascending id). */
  apply(frame) {
    const h = frame.header; const J = h.jointCount; const shift = h.jointShift;
    let base = [];
    if (h.baseFrame !== 0) {
      if (!this.history.has(h.baseFrame)) throw new ProtocolError('/CrowdFrame/baseFrame', 0, `base frame ${h.baseFrame} unknown; wait for a key frame`);
      base = this.history.get(h.baseFrame);
    }
    const r = new Reader(frame.payload, 'CrowdFrame');
    const removed = readIds(r, r.varint('removalCount', LIMITS.maxAgents), 'removals');
    const n = r.varint('recordCount', LIMITS.maxAgents);
    if (n > r.b.length - r.p) r.fail('recordCount', `${n} records in ${r.b.length - r.p} bytes`);
    const recs = readIds(r, n, 'records').map((id) => ({ id }));
    for (const rec of recs) rec.mask = r.u8('masks');
    for (const rec of recs) if (rec.mask & MASK.tier) rec.tier = enumByte(r, 'tiers', 2);
    const P = 2 ** 32;
    for (const k of ['x', 'y', 'z']) for (const rec of recs) if (rec.mask & MASK[k]) rec['d' + k] = r.svarint(k, -P, P);
    for (const rec of recs) if (rec.mask & MASK.yaw) rec.dyaw = r.svarint('yaw', -32768, 32767);
    for (const rec of recs) if (rec.mask & MASK.clip) rec.clip = r.varint('clip', 0xffff);
    for (const rec of recs) if (rec.mask & MASK.phase) rec.dphase = r.svarint('phase', -128, 127);
    let poseRecords = 0;
    for (const rec of recs) if (rec.mask & MASK.pose) { rec.pose = r.varint('poses', LIMITS.maxAgents); poseRecords++; }
    const poseCount = r.varint('poseCount', LIMITS.maxAgents);
    if (poseCount > poseRecords) r.fail('poseCount', `${poseCount} poses for ${poseRecords} records with a pose`);
    const comps = 3 * J; const half = 2 ** (15 - shift);
    if (poseCount * comps > r.b.length - r.p) r.fail('poseCount', 'pose table larger than the payload');
    const table = [];
    for (let i = 0; i < poseCount * comps; i++) table.push(r.svarint('poseTable', -half, half - 1));
    r.end();

    const fail = (msg) => { throw new ProtocolError(`/CrowdFrame/${h.frameNumber}`, 0, msg); };
    const removedSet = new Set(removed);
    const byId = new Map(base.map((a) => [a.id, a]));
    for (const id of removed) if (!byId.has(id)) fail(`removal of agent ${id} that is not in base frame ${h.baseFrame}`);
    const out = new Map();
    for (const a of base) if (!removedSet.has(a.id)) out.set(a.id, a);
    const resolved = new Array(poseCount).fill(null);
    const m16 = 0xffff >>> shift;
    for (const rec of recs) {
      if (removedSet.has(rec.id)) fail(`agent ${rec.id} both removed and updated`);
      const b = out.get(rec.id);
      const a = b ? { ...b, joints: b.joints.slice() } : { id: rec.id, tier: 0, x: 0, y: 0, z: 0, yaw: 0, clip: 0, phase: 0, joints: [] };
      const tier = rec.mask & MASK.tier ? rec.tier : a.tier;
      tierRules(a, tier, J);
      if (tier === 2 && (rec.mask & (MASK.yaw | MASK.clip | MASK.phase | MASK.pose))) fail(`agent ${rec.id}: far agent with yaw, clip, phase or pose`);
      if (tier === 1 && (rec.mask & MASK.pose)) fail(`agent ${rec.id}: middle agent with a pose`);
      if (tier === 1 && rec.dyaw !== undefined && (rec.dyaw < -128 || rec.dyaw > 127)) fail(`agent ${rec.id}: middle yaw delta ${rec.dyaw}`);
      for (const k of ['x', 'y', 'z']) {
        const v = a[k] + (rec['d' + k] ?? 0);
        if (v < -(2 ** 31) || v > 2 ** 31 - 1) fail(`agent ${rec.id}: position outside the int32 cm range`);
        a[k] = v;
      }
      if (rec.mask & MASK.yaw) a.yaw = tier === 0 ? (a.yaw + rec.dyaw) & 0xffff : (((a.yaw >> 8) + rec.dyaw) & 0xff) << 8;
      if (rec.mask & MASK.clip) a.clip = rec.clip;
      if (rec.mask & MASK.phase) a.phase = (a.phase + rec.dphase) & 0xff;
      if (rec.mask & MASK.pose) {
        if (rec.pose >= poseCount) fail(`agent ${rec.id}: pose ${rec.pose} beyond the table of ${poseCount}`);
        if (resolved[rec.pose] === null) {
          const u16 = a.joints.map((q, j) => ((((q & 0xffff) >>> shift) + table[rec.pose * comps + j]) & m16) << shift);
          resolved[rec.pose] = u16.map((q) => (q << 16) >> 16);
        }
        a.joints = resolved[rec.pose].slice();
      }
      out.set(rec.id, a);
    }
    if (resolved.some((p) => p === null)) fail('a pose of the table is never used');
    const agents = [...out.values()].sort((p, q) => p.id - q.id);
    const counts = [0, 0, 0];
    for (const a of agents) counts[a.tier]++;
    if (counts[0] !== h.nearCount || counts[1] !== h.middleCount || counts[2] !== h.farCount) {
      fail(`tier counts ${counts.join('/')} differ from the header's ${h.nearCount}/${h.middleCount}/${h.farCount}`);
    }
    this.history.set(h.frameNumber, agents);
    while (this.history.size > this.historyFrames) this.history.delete(this.history.keys().next().value);
    this.newestFrame = Math.max(this.newestFrame, h.frameNumber);
    return { header: h, agents };
  }

  /** decodeAny + apply. */
  decode(bytes) {
    const m = decodeAny(bytes);
    if (m.type !== 'CrowdFrame') throw new ProtocolError('/CrowdFrame', 1, `a ${m.type} message, expected a CrowdFrame`);
    return this.apply(m);
  }
}
