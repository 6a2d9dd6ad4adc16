// Client → server message encoders of the throng wire protocol, version 2 (docs/protocol.md),
// byte for byte as libs/protocol encodes them: magic 0x54 ('T'), the type byte, then the fields;
// integers little-endian, varints LEB128, strings varint length + UTF-8 bytes (cut at the limits),
// positions int32 centimetres, angles uint16 1/65536 turn. Tokens are 64-bit: pass a BigInt (or a
// number ≤ 2^53). Checked against tests/protocol/golden/<message>.bin (test/encode.test.js).
// The server → client direction is decoded by web/protocol/ (not here).

export const kProtocolVersion = 2;
export const kMagic = 0x54;
export const MessageType = Object.freeze({
  Hello: 1, Refuse: 2, Welcome: 3, Join: 4, Joined: 5, Leave: 6, Heartbeat: 7, Bye: 8, Move: 9, Joints: 10,
  HandJoints: 11, FaceExpression: 12, Guide: 13, Release: 14, GuideResult: 15, Ack: 16, CrowdFrame: 17,
  Presence: 18, ReplayControl: 19, ReplayStatus: 20,
});
/** ReplayControl commands; value: 0 for Play/Pause, time [s] ≥ 0 for Seek, factor in (0, 64] for Speed. */
export const ReplayCommand = Object.freeze({ Play: 0, Pause: 1, Seek: 2, Speed: 3 });
export const kMaxReplaySpeed = 64;
export const ClientKind = Object.freeze({ Browser: 0, Native: 1, Loadgen: 2 });
export const kMaxNameLength = 64;
export const kMaxTextLength = 1024;
export const kMaxJoints = 128;

const utf8 = new TextEncoder();

class Writer {
  constructor(type) { this.bytes = [kMagic, type]; }
  u8(v) { this.bytes.push(v & 0xff); return this; }
  u16(v) { this.bytes.push(v & 0xff, (v >>> 8) & 0xff); return this; }
  u32(v) { for (let i = 0; i < 4; ++i) this.bytes.push((v >>> (8 * i)) & 0xff); return this; }
  i32(v) { return this.u32(v >>> 0); }
  u64(v) {
    let b = BigInt.asUintN(64, BigInt(v));
    for (let i = 0; i < 8; ++i) { this.bytes.push(Number(b & 0xffn)); b >>= 8n; }
    return this;
  }
  f64(v) {
    const b = new Uint8Array(8);
    new DataView(b.buffer).setFloat64(0, v, true);
    for (const x of b) this.bytes.push(x);
    return this;
  }
  varint(v) {
    let b = BigInt.asUintN(64, BigInt(v));
    while (b >= 0x80n) { this.bytes.push(Number((b & 0x7fn) | 0x80n)); b >>= 7n; }
    this.bytes.push(Number(b));
    return this;
  }
  string(s, max) {
    let b = utf8.encode(s);
    if (b.length > max) b = b.subarray(0, max);  // the C++ encoder cuts bytes the same way
    this.varint(b.length);
    for (const x of b) this.bytes.push(x);
    return this;
  }
  done() { return Uint8Array.from(this.bytes); }
}

/** Metres → int32 centimetres (round half to even like nearbyint, saturating). */
export function quantizePosition(m) {
  const cm = roundEven(m * 100);
  if (Number.isNaN(cm)) return 0;
  return Math.min(Math.max(cm, -2147483648), 2147483647);
}

/** Radians → uint16 in 1/65536 turn (wraps); NaN → 0. */
export function quantizeAngle16(rad) {
  const steps = 65536;
  const t = (Math.fround(rad) / (2 * Math.PI)) * steps;
  if (!Number.isFinite(t)) return 0;
  return roundEven(t - Math.floor(t / steps) * steps) & (steps - 1);
}

function roundEven(x) {
  const r = Math.round(x);
  return Math.abs(x % 1) === 0.5 && r % 2 !== 0 ? r - 1 : r;
}

// Positions are computed in double from the float value, as the C++ side does.
const f32 = Math.fround;

export function encodeHello({ protocolVersion = kProtocolVersion, clientKind = ClientKind.Browser, clientName = '' } = {}) {
  return new Writer(MessageType.Hello).u16(protocolVersion).u8(clientKind).string(clientName, kMaxNameLength).done();
}

export function encodeJoin({ name, avatar = 0 }) {
  return new Writer(MessageType.Join).string(name, kMaxNameLength).u16(avatar).done();
}

export function encodeLeave({ token }) {
  return new Writer(MessageType.Leave).u64(token).done();
}

export function encodeHeartbeat({ token = 0n, timeUs, echoUs = 0n }) {
  return new Writer(MessageType.Heartbeat).u64(token).u64(timeUs).u64(echoUs).done();
}

export function encodeBye({ reason = 13, text = '' }) {
  return new Writer(MessageType.Bye).u8(reason).string(text, kMaxTextLength).done();
}

/** Subject: {kind: 0 (token) | 1 (participant id), value}. */
function subject(w, s) {
  w.u8(s.kind);
  if (s.kind === 0) w.u64(s.value); else w.varint(BigInt(s.value) & 0xffffffffn);
}

export function encodeMove({ subject: s, seq, x, y, z = 0, yaw }) {
  const w = new Writer(MessageType.Move);
  subject(w, s);
  return w.varint(seq).i32(quantizePosition(f32(x))).i32(quantizePosition(f32(y))).i32(quantizePosition(f32(z)))
    .u16(quantizeAngle16(yaw)).done();
}

function encodeAngles(type, { subject: s, seq, angles }) {
  const w = new Writer(type);
  subject(w, s);
  w.varint(seq);
  const joints = Math.min(Math.floor(angles.length / 3), kMaxJoints);
  w.u8(joints);
  for (let i = 0; i < joints * 3; ++i) w.u16(quantizeAngle16(angles[i]));
  return w.done();
}

export function encodeJoints(m) { return encodeAngles(MessageType.Joints, m); }
export function encodeHandJoints(m) { return encodeAngles(MessageType.HandJoints, m); }

export function encodeGuide({ token, groupId }) {
  return new Writer(MessageType.Guide).u64(token).varint(groupId).done();
}

export function encodeRelease({ token, groupId }) {
  return new Writer(MessageType.Release).u64(token).varint(groupId).done();
}

export function encodeAck({ token = 0n, frameNumber }) {
  return new Writer(MessageType.Ack).u64(token).varint(frameNumber).done();
}

/**
 * Drives a server replaying a recording: {token (0 when not joined), command (ReplayCommand),
 * value}. Throws RangeError for a value the server would refuse (docs/protocol.md, type 19).
 */
export function encodeReplayControl({ token = 0n, command, value = 0 }) {
  const ok = command === ReplayCommand.Play || command === ReplayCommand.Pause ? value === 0
    : command === ReplayCommand.Seek ? Number.isFinite(value) && value >= 0
      : command === ReplayCommand.Speed ? Number.isFinite(value) && value > 0 && value <= kMaxReplaySpeed
        : false;
  if (!ok) throw new RangeError(`ReplayControl: command ${command} with value ${value} is not allowed`);
  return new Writer(MessageType.ReplayControl).u64(token).u8(command).f64(value).done();
}

// Crowds inserted at run time (docs/protocol.md, types 21–23): a participant sends a crowd file's
// JSON (at most kMaxCrowdJson bytes) or names a crowd id to remove; the server answers a
// CrowdResult (decoded by web/protocol/decode.js) with the same requestId.
export const CrowdMessageType = Object.freeze({ InsertCrowd: 21, RemoveCrowd: 22, CrowdResult: 23 });
export const kMaxCrowdJson = 1 << 20;

/** {token, requestId, crowdJson (a "throng-crowd/1" file's text)}; throws RangeError over 1 MiB. */
export function encodeInsertCrowd({ token, requestId, crowdJson }) {
  const text = typeof crowdJson === 'string' ? crowdJson : JSON.stringify(crowdJson);
  const bytes = utf8.encode(text);
  if (bytes.length > kMaxCrowdJson) {
    throw new RangeError(`InsertCrowd: crowd file of ${bytes.length} bytes; at most ${kMaxCrowdJson} bytes`);
  }
  return new Writer(CrowdMessageType.InsertCrowd).u64(token).varint(requestId).string(text, kMaxCrowdJson).done();
}

/** {token, requestId, crowdId (the id of a crowd inserted earlier, ≤ 64 bytes)}. */
export function encodeRemoveCrowd({ token, requestId, crowdId }) {
  return new Writer(CrowdMessageType.RemoveCrowd).u64(token).varint(requestId).string(crowdId, kMaxNameLength).done();
}
