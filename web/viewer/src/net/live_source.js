// Live data source: the WebSocket to `throng serve` at ws(s)://<host>/ws. Session: sends Hello,
// receives Welcome (→ 'world': the world description JSON), then crowd frames (→ 'frame', each
// acknowledged with Ack so the server delta-codes against it), relayed participant Moves
// (→ 'participant'), Joined (→ 'joined'), GuideResult (→ 'guide'). Pings (Heartbeat, echoUs 0) every second
// and answers the server's pings at once (round-trip times both ways), Move at most 10 Hz from the avatar,
// Join/Leave/Guide/Release on request. Connection lost: 'status' {state: 'lost', retryIn} and a
// reconnect with exponential backoff (0.5 s … 10 s, jittered); after it, the participant joins
// again under the same name. Presence (participants joining/leaving, with names) → 'presence';
// a server replaying a recording sends ReplayStatus (→ 'timeline' {time, duration, playing,
// speed}) and takes ReplayControl from play()/pause()/seek()/setSpeed(). A Welcome after a
// reconnect with another world description than the first (the server now plays another
// recording) → 'worldChanged' (the page reloads). Relayed Joints of other
// participants (→ 'joints' {participantId, angles}); sendJoints() sends the avatar's. Decoding is
// web/protocol's (through protocol_adapter.js).
import { Emitter } from '../sources/emitter.js';
import * as encode from './encode.js';
import { createDecoder } from './protocol_adapter.js';

const kReason = ['none', 'version mismatch', 'server full', 'bad message', 'unexpected message', 'bad token',
  'rate limited', 'timeout', 'slow client', 'server shutting down', 'unknown group', 'group taken',
  'not guiding', 'client quit'];

const {
  ClientKind, encodeAck, encodeGuide, encodeHeartbeat, encodeHello, encodeJoin, encodeLeave, encodeMove, encodeRelease,
  encodeBye, encodeJoints,
} = encode;
const kReplayCommand = { play: encode.ReplayCommand.Play, pause: encode.ReplayCommand.Pause,
  seek: encode.ReplayCommand.Seek, speed: encode.ReplayCommand.Speed };

function nowUs() { return BigInt(Math.round((performance.timeOrigin + performance.now()) * 1000)); }

export function reasonText(code) { return kReason[code] || `reason ${code}`; }

export function defaultWsUrl(loc = globalThis.location) {
  const proto = loc.protocol === 'https:' ? 'wss:' : 'ws:';
  return `${proto}//${loc.host}/ws`;
}

export class LiveSource extends Emitter {
  constructor(url = defaultWsUrl()) {
    super();
    this.kind = 'live';
    this.url = url;
    this.bytesReceived = 0;
    this.participants = 0;
    this.token = 0n;
    this.participantId = 0;
    this.moveSeq = 0;
    this.jointsSeq = 0;
    this.lastMoveAt = 0;
    this.peerTimeUs = 0n;
    this.rttMs = 0;
    this.attempt = 0;
    this.world = null;
    this.joinName = null;
    this.joinAvatar = 0;
    this.stopped = false;
    this.others = new Map();  // participant id → last Move
    this.names = new Map();   // participant id → name (Presence)
    this.looks = new Map();   // participant id → look index (Presence's avatar; none from a version-1 server)
    this.present = new Set(); // participant ids present (Presence), this viewer's own included
    this.replay = null;       // last ReplayStatus when the server replays a recording
  }

  start() { this.stopped = false; this.connect(); }

  stop() {
    this.stopped = true;
    clearTimeout(this.retryTimer);
    clearInterval(this.heartbeatTimer);
    if (this.ws && this.ws.readyState === WebSocket.OPEN) this.ws.send(encodeBye({ reason: 13, text: 'viewer closed' }));
    if (this.ws) this.ws.close();
  }

  connect() {
    this.emit('status', { state: 'connecting', text: `connecting to ${this.url}` });
    this.decoder = createDecoder();
    let ws;
    try {
      ws = new WebSocket(this.url);
    } catch (e) {
      this.lost(`cannot connect: ${e.message}`);
      return;
    }
    ws.binaryType = 'arraybuffer';
    this.ws = ws;
    ws.onopen = () => {
      ws.send(encodeHello({ clientKind: ClientKind.Browser, clientName: 'throng-viewer' }));
      clearInterval(this.heartbeatTimer);
      this.heartbeatTimer = setInterval(() => this.heartbeat(), 1000);
    };
    ws.onmessage = (e) => this.receive(new Uint8Array(e.data));
    ws.onclose = (e) => { if (ws === this.ws) this.lost(this.closeReason || `connection closed (${e.code})`); };
    ws.onerror = () => {};
  }

  lost(text) {
    clearInterval(this.heartbeatTimer);
    this.token = 0n;
    if (this.stopped) return;
    if (this.refused) { this.emit('status', { state: 'closed', text }); return; }
    const delay = Math.min(10, 0.5 * 2 ** this.attempt) * (0.8 + Math.random() * 0.4);
    this.attempt++;
    this.emit('status', { state: 'lost', text, retryIn: delay });
    this.closeReason = null;
    clearTimeout(this.retryTimer);
    this.retryTimer = setTimeout(() => this.connect(), delay * 1000);
  }

  send(bytes) { if (this.ws && this.ws.readyState === WebSocket.OPEN) this.ws.send(bytes); }

  /** A ping (echoUs 0): the server answers at once, echoing our time (round trip). */
  heartbeat() {
    this.send(encodeHeartbeat({ token: this.token, timeUs: nowUs(), echoUs: 0n }));
  }

  receive(bytes) {
    this.bytesReceived += bytes.length;
    let m;
    try {
      m = this.decoder.decode(bytes);
    } catch (e) {
      console.warn('throng: undecodable message', e);
      this.closeReason = `bad message from the server: ${e.message}`;
      this.ws.close();
      return;
    }
    switch (m.type) {
      case 'Refuse':
        this.refused = m.reason === 1;
        this.closeReason = `refused: ${reasonText(m.reason)}${m.text ? ` — ${m.text}` : ''}`;
        break;
      case 'Welcome': {
        this.attempt = 0;
        const first = !this.world;
        // Another world than before the reconnect (the server switched recordings): 'worldChanged'.
        const text = JSON.stringify(m.world);
        if (!first && text !== this.worldText) { this.emit('worldChanged', m.world); return; }
        this.worldText = text;
        this.world = m.world;
        this.tickRate = m.tickRateHz;
        this.emit('status', { state: 'open', text: `connected to ${m.serverName}` });
        if (first) this.emit('world', m.world);
        if (this.joinName) this.send(encodeJoin({ name: this.joinName, avatar: this.joinAvatar }));
        break;
      }
      case 'Joined':
        this.token = BigInt(m.token);
        this.participantId = m.participantId;
        this.countParticipants();
        this.emit('joined', { participantId: m.participantId, token: this.token, name: this.joinName });
        break;
      case 'CrowdFrame':
        this.send(encodeAck({ token: this.token, frameNumber: m.frameNumber }));
        this.emit('frame', m.frame);
        break;
      case 'Move':
        if (m.participantId !== this.participantId) {
          this.others.set(m.participantId, { ...m, at: performance.now() });
          this.countParticipants();
          this.emit('participant', m);
        }
        break;
      case 'Joints':
        if (m.participantId !== this.participantId && m.participantId >= 0) this.emit('joints', m);
        break;
      case 'Presence': {
        const id = Number(m.participantId);
        if (m.present) {
          this.present.add(id); this.names.set(id, m.name);
          if (m.avatar !== undefined) this.looks.set(id, m.avatar);  // protocol 2: the look they chose
        } else { this.present.delete(id); this.others.delete(id); this.looks.delete(id); }
        this.countParticipants();
        this.emit('presence', { participantId: id, present: !!m.present, name: m.name, avatar: m.avatar });
        break;
      }
      case 'ReplayStatus':
        this.kind = 'replay';
        this.replay = { time: Number(m.time), duration: Number(m.duration), playing: !!m.playing, speed: Number(m.speed) };
        this.emit('timeline', this.replay);
        break;
      case 'GuideResult':
        this.emit('guide', m);
        break;
      case 'Heartbeat':
        this.peerTimeUs = BigInt(m.timeUs);
        if (BigInt(m.echoUs) === 0n) {
          // The server's ping: answer at once, echoing its time.
          this.send(encodeHeartbeat({ token: this.token, timeUs: nowUs(), echoUs: this.peerTimeUs }));
        } else {
          this.rttMs = Number(nowUs() - BigInt(m.echoUs)) / 1000;
        }
        break;
      case 'Bye':
        this.closeReason = `server closed the connection: ${m.text && m.text.startsWith(reasonText(m.reason)) ? m.text
          : `${reasonText(m.reason)}${m.text ? ` — ${m.text}` : ''}`}`;
        break;
      default:
        break;
    }
  }

  countParticipants() {
    const ids = new Set([...this.present, ...this.others.keys()]);
    if (this.token) ids.add(this.participantId);
    this.participants = ids.size;
  }

  /** Replay control (a server started on a recording). */
  replayControl(command, value = 0) {
    this.send(encode.encodeReplayControl({ token: this.token, command: kReplayCommand[command], value }));
  }

  play() { this.replayControl('play'); }
  pause() { this.replayControl('pause'); }
  seek(t) { this.replayControl('seek', Math.max(0, t)); }
  setSpeed(s) { this.replayControl('speed', s); }

  /** Joins as `name`; `avatar`: the look chosen (crowd/avatar_looks.js), sent as Join's avatar index. */
  join(name, avatar = 0) {
    this.joinName = name;
    this.joinAvatar = avatar;
    this.send(encodeJoin({ name, avatar }));
  }

  /** A new look while joined: Join again (same name; the server keeps the id and token and tells
   * everyone in Presence). Before joining it only changes what join() will send. */
  changeLook(avatar) {
    this.joinAvatar = avatar;
    if (this.token && this.joinName) this.send(encodeJoin({ name: this.joinName, avatar }));
  }

  leave() {
    if (this.token) this.send(encodeLeave({ token: this.token }));
    this.joinName = null;
    this.token = 0n;
    this.present.delete(this.participantId);  // gone at once from our own count (the HUD's participants)
    this.countParticipants();
  }

  /** The avatar's pose, world metres and radians; sent at most every 100 ms. */
  sendMove(x, y, z, yaw, force = false) {
    if (!this.token) return;
    const now = performance.now();
    if (!force && now - this.lastMoveAt < 100) return;
    this.lastMoveAt = now;
    this.send(encodeMove({ subject: { kind: 0, value: this.token }, seq: ++this.moveSeq, x, y, z, yaw }));
  }

  /** The avatar's joint angles (3 per skeleton joint, radians, BVH order) while it gestures. */
  sendJoints(angles) {
    if (!this.token) return;
    this.send(encodeJoints({ subject: { kind: 0, value: this.token }, seq: ++this.jointsSeq, angles }));
  }

  guide(groupId) { if (this.token) this.send(encodeGuide({ token: this.token, groupId })); }
  release(groupId) { if (this.token) this.send(encodeRelease({ token: this.token, groupId })); }
}
