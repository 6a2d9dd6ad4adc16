// web/protocol/decode.js against the C++ golden set: every tests/protocol/golden/<name>.bin
// decodes to <name>.json (crowd deltas after their base), and truncations throw ProtocolError.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { decodeAny, CrowdDecoder, ProtocolError } from './decode.js';

const dir = fileURLToPath(new URL('../../tests/protocol/golden/', import.meta.url));
const names = readdirSync(dir).filter((f) => f.endsWith('.json')).map((f) => f.slice(0, -5)).sort();
const bin = (n) => new Uint8Array(readFileSync(dir + n + '.bin'));
const json = (n) => JSON.parse(readFileSync(dir + n + '.json', 'utf8'));

test('golden set is present', () => assert.ok(names.length >= 20, `found ${names.length} golden messages in ${dir}`));

for (const name of names) {
  test(`golden ${name}`, () => {
    const expected = json(name);
    if (expected.type !== 'CrowdFrame') {
      assert.deepEqual(decodeAny(bin(name)), expected);
      return;
    }
    const decoder = new CrowdDecoder();
    if (expected.base) decoder.decode(bin(expected.base));
    const { header, agents } = decoder.decode(bin(name));
    const got = { type: 'CrowdFrame', header, agents };
    if (expected.base) got.base = expected.base;
    assert.deepEqual(got, expected);
  });
}

test('every truncation throws ProtocolError', () => {
  for (const name of names) {
    const b = bin(name);
    // A Fragment's payload is the rest of the datagram: only cuts into its 6-byte header (or
    // leaving no payload) are errors.
    const cuts = name === 'fragment' ? 7 : b.length;
    // A Presence's look (version 2) is optional: without its 2 bytes it is a version-1 Presence.
    const look = name.startsWith('presence') && 'avatar' in decodeAny(b);
    for (let n = 0; n < cuts; n++) {
      if (look && n === b.length - 2) {
        assert.equal('avatar' in decodeAny(b.subarray(0, n)), false, `${name} cut before its look`);
        continue;
      }
      assert.throws(() => decodeAny(b.subarray(0, n)), ProtocolError, `${name} cut at ${n}`);
    }
  }
});

test('a delta without its base is refused cleanly', () => {
  assert.throws(() => new CrowdDecoder().decode(bin('crowd_delta')), /base frame 1 unknown/);
});

// Presence, ReplayControl, ReplayStatus (types 18–20): the value rules of docs/protocol.md.
const f64le = (v) => { const b = new Uint8Array(8); new DataView(b.buffer).setFloat64(0, v, true); return [...b]; };
const f32le = (v) => { const b = new Uint8Array(4); new DataView(b.buffer).setFloat32(0, v, true); return [...b]; };
const replayControl = (command, value) => new Uint8Array([0x54, 19, ...new Array(8).fill(0), command, ...f64le(value)]);
const replayStatus = (time, duration, playing, speed) =>
  new Uint8Array([0x54, 20, ...f64le(time), ...f64le(duration), playing, ...f32le(speed)]);

test('Presence: present flag must be 0 or 1', () => {
  const ok = decodeAny(new Uint8Array([0x54, 18, 5, 0, 2, 0x42, 0x6f]));
  assert.deepEqual(ok, { type: 'Presence', participantId: 5, present: false, name: 'Bo' });
  assert.throws(() => decodeAny(new Uint8Array([0x54, 18, 5, 2, 0])),
    (e) => e instanceof ProtocolError && e.field === '/Presence/present' && e.offset === 3);
  assert.throws(() => decodeAny(new Uint8Array([0x54, 18, 5, 1, 65, ...new Array(65).fill(0x78)])), /\/Presence\/name/);
});

test('Presence: the look trails the name in version 2; a version-1 Presence decodes without one', () => {
  assert.deepEqual(decodeAny(new Uint8Array([0x54, 18, 5, 1, 2, 0x42, 0x6f, 3, 1])),
    { type: 'Presence', participantId: 5, present: true, name: 'Bo', avatar: 259 });
  assert.equal('avatar' in decodeAny(new Uint8Array([0x54, 18, 5, 1, 2, 0x42, 0x6f])), false);
  assert.throws(() => decodeAny(new Uint8Array([0x54, 18, 5, 1, 2, 0x42, 0x6f, 3])),
    (e) => e instanceof ProtocolError && e.field === '/Presence/avatar' && e.offset === 7);
  assert.throws(() => decodeAny(new Uint8Array([0x54, 18, 5, 1, 2, 0x42, 0x6f, 3, 0, 0])), /\/Presence\/end/);
});

test('ReplayControl: command and value rules', () => {
  for (const [c, v] of [[0, 0], [1, 0], [2, 0], [2, 1e6], [3, 0.25], [3, 64]]) {
    assert.deepEqual(decodeAny(replayControl(c, v)), { type: 'ReplayControl', token: '0', command: c, value: v });
  }
  for (const [c, v] of [[0, 1], [1, -0.5], [2, -1], [2, NaN], [2, Infinity], [3, 0], [3, -1], [3, 64.5], [3, NaN]]) {
    assert.throws(() => decodeAny(replayControl(c, v)),
      (e) => e instanceof ProtocolError && e.field === '/ReplayControl/value' && e.offset === 11, `command ${c} value ${v}`);
  }
  assert.throws(() => decodeAny(replayControl(4, 0)),
    (e) => e instanceof ProtocolError && e.field === '/ReplayControl/command' && e.offset === 10);
});

test('ReplayStatus: finite non-negative times, 0/1 playing, positive speed', () => {
  assert.deepEqual(decodeAny(replayStatus(1.5, 10, 0, 0.5)), { type: 'ReplayStatus', time: 1.5, duration: 10, playing: false, speed: 0.5 });
  const fails = (bytes, field, offset) => assert.throws(() => decodeAny(bytes),
    (e) => e instanceof ProtocolError && e.field === `/ReplayStatus/${field}` && e.offset === offset, field);
  fails(replayStatus(-0.1, 10, 1, 1), 'time', 2);
  fails(replayStatus(0, NaN, 1, 1), 'duration', 10);
  fails(replayStatus(0, 1, 2, 1), 'playing', 18);
  fails(replayStatus(0, 1, 1, 0), 'speed', 19);
  fails(replayStatus(0, 1, 1, Infinity), 'speed', 19);
});

// InsertCrowd, RemoveCrowd, CrowdResult (types 21–23): limits and the ok flag.
test('CrowdResult: ok must be 0 or 1; crowd ids are names', () => {
  const ok = decodeAny(new Uint8Array([0x54, 23, 3, 1, 2, 1, 0x61, 1, 0x62]));
  assert.deepEqual(ok, { type: 'CrowdResult', requestId: 3, ok: true, crowdIndex: 2, crowdId: 'a', text: 'b' });
  assert.throws(() => decodeAny(new Uint8Array([0x54, 23, 3, 2, 2, 1, 0x61, 1, 0x62])),
    (e) => e instanceof ProtocolError && e.field === '/CrowdResult/ok' && e.offset === 3);
  assert.throws(() => decodeAny(new Uint8Array([0x54, 22, ...new Array(8).fill(0), 1, 65, ...new Array(65).fill(0x78)])),
    /\/RemoveCrowd\/crowdId/);
  // A crowd file one byte over 1 MiB: refused from its length prefix (0x80 0x80 0x40 = 2^20, +1).
  assert.throws(() => decodeAny(new Uint8Array([0x54, 21, ...new Array(8).fill(0), 1, 0x81, 0x80, 0x40])),
    (e) => e instanceof ProtocolError && e.field === '/InsertCrowd/crowdJson' && e.offset === 11);
});

// Fragment (type 24): messageId, index, count (2..8192, index < count), then ≥ 1 payload byte.
test('Fragment: count and index rules', () => {
  const ok = decodeAny(new Uint8Array([0x54, 24, 0xac, 0x02, 1, 3, 9, 8]));
  assert.deepEqual(ok, { type: 'Fragment', messageId: '300', index: 1, count: 3, payload: [9, 8] });
  assert.throws(() => decodeAny(new Uint8Array([0x54, 24, 0, 0, 1, 9])),
    (e) => e instanceof ProtocolError && e.field === '/Fragment/count' && e.offset === 4);
  assert.throws(() => decodeAny(new Uint8Array([0x54, 24, 0, 0, 0x81, 0x40, 9])), /\/Fragment\/count/);  // 8193
  assert.throws(() => decodeAny(new Uint8Array([0x54, 24, 0, 3, 3, 9])),
    (e) => e instanceof ProtocolError && e.field === '/Fragment/index' && e.offset === 3);
  assert.throws(() => decodeAny(new Uint8Array([0x54, 24, 0, 0, 2])), /\/Fragment\/payload/);
});

// The UDP handshake (types 25, 26): a UdpHello holds a cookie and one whole Hello.
test('UdpHello: the bytes after the cookie must be a Hello', () => {
  const hello = [0x54, 1, 1, 0, 1, 3, 0x41, 0x64, 0x61];
  const ok = decodeAny(new Uint8Array([0x54, 26, ...new Array(16).fill(0), ...hello]));
  assert.deepEqual(ok, { type: 'UdpHello', cookie: '0'.repeat(32), hello: { protocolVersion: 1, clientKind: 1, clientName: 'Ada' } });
  assert.throws(() => decodeAny(new Uint8Array([0x54, 26, ...new Array(16).fill(0), 0x54, 4, 3, 0x41, 0x64, 0x61, 0, 0])),
    (e) => e instanceof ProtocolError && e.field === '/UdpHello/hello' && e.offset === 19);
  assert.throws(() => decodeAny(new Uint8Array([0x54, 25, ...new Array(17).fill(7)])), /\/Cookie\/end/);
});
