// The client → server encoders (src/net/encode.js) against the C++ golden bytes
// (tests/protocol/golden/<name>.bin, written by libs/protocol's golden test from the same sample
// values as below), and against bytes computed by hand from docs/protocol.md.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import * as enc from '../src/net/encode.js';

const golden = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../../tests/protocol/golden');
const token = 0x0123456789abcdefn;

// The samples of tests/protocol/protocol_test_util.hpp goldenMessages().
const samples = {
  hello: () => enc.encodeHello({ clientKind: enc.ClientKind.Browser, clientName: 'viewer-firefox' }),
  join: () => enc.encodeJoin({ name: 'Ada', avatar: 2 }),
  leave: () => enc.encodeLeave({ token }),
  heartbeat: () => enc.encodeHeartbeat({ token, timeUs: 1700000000123456n, echoUs: 1700000000000001n }),
  bye: () => enc.encodeBye({ reason: 9, text: 'server shutting down' }),
  move: () => enc.encodeMove({ subject: { kind: 0, value: 0xfedcba9876543210n }, seq: 42, x: 12.34, y: -5.67, z: 0.5, yaw: 1.5 }),
  joints: () => enc.encodeJoints({ subject: { kind: 1, value: 7 }, seq: 300, angles: [0, 0.5, -0.5, 3.0, -3.0, 1.0] }),
  hand_joints: () => enc.encodeHandJoints({ subject: { kind: 0, value: 99n }, seq: 1, angles: [0.25, 0, -0.25] }),
  guide: () => enc.encodeGuide({ token, groupId: 4 }),
  release: () => enc.encodeRelease({ token, groupId: 4 }),
  ack: () => enc.encodeAck({ token, frameNumber: 129 }),
  replay_control: () => enc.encodeReplayControl({ token, command: enc.ReplayCommand.Seek, value: 12.5 }),
};

for (const [name, make] of Object.entries(samples)) {
  const file = path.join(golden, `${name}.bin`);
  test(`${name} matches the C++ golden bytes`, () => {
    assert.deepEqual([...make()], [...fs.readFileSync(file)]);
  });
}

const le64 = (v) => { const o = []; let b = BigInt(v); for (let i = 0; i < 8; ++i) { o.push(Number(b & 0xffn)); b >>= 8n; } return o; };

test('hand-computed bytes (docs/protocol.md layouts)', () => {
  // Hello: magic, type 1, u16 version 2, u8 kind 0 (browser), varint length 2, "ab".
  assert.deepEqual([...enc.encodeHello({ clientName: 'ab' })], [0x54, 1, 2, 0, 0, 2, 0x61, 0x62]);
  // Join: string "Ada", u16 avatar 2.
  assert.deepEqual([...enc.encodeJoin({ name: 'Ada', avatar: 2 })], [0x54, 4, 3, 0x41, 0x64, 0x61, 2, 0]);
  // Ack: u64 token, varint 129 = 0x81 0x01.
  assert.deepEqual([...enc.encodeAck({ token, frameNumber: 129 })], [0x54, 16, ...le64(token), 0x81, 0x01]);
  // Guide: u64 token, varint group 300 = 0xac 0x02.
  assert.deepEqual([...enc.encodeGuide({ token: 1n, groupId: 300 })], [0x54, 13, ...le64(1n), 0xac, 0x02]);
  // Move: subject token (kind 0, u64), varint seq 1, int32 cm x = 100, y = −1 (0xffffffff), z = 0,
  // u16 yaw π/2 = 16384 (a quarter turn).
  assert.deepEqual([...enc.encodeMove({ subject: { kind: 0, value: 5n }, seq: 1, x: 1, y: -0.01, z: 0, yaw: Math.PI / 2 })],
    [0x54, 9, 0, ...le64(5n), 1, 100, 0, 0, 0, 0xff, 0xff, 0xff, 0xff, 0, 0, 0, 0, 0x00, 0x40]);
  // Move with a participant subject: kind 1 then a varint id.
  assert.deepEqual([...enc.encodeMove({ subject: { kind: 1, value: 7 }, seq: 2, x: 0, y: 0, yaw: -Math.PI })].slice(0, 5), [0x54, 9, 1, 7, 2]);
});

test('quantization rounds like the C++ side', () => {
  assert.equal(enc.quantizePosition(0.125), 12);   // 12.5 → even
  assert.equal(enc.quantizePosition(-0.135), -14); // float32(−0.135)·100 ≈ −13.5000002 → −14
  assert.equal(enc.quantizeAngle16(-Math.PI), 32768);
  assert.equal(enc.quantizeAngle16(2 * Math.PI), 0);
  assert.equal(enc.quantizeAngle16(NaN), 0);
  assert.equal(enc.quantizePosition(1e12), 2147483647);
});

test('names are cut at 64 bytes', () => {
  const b = enc.encodeJoin({ name: 'x'.repeat(100) });
  assert.equal(b[2], 64);
  assert.equal(b.length, 2 + 1 + 64 + 2);
});

test('ReplayControl: hand-computed bytes and refused values', () => {
  // u64 token 0, u8 command 3 (speed), f64 2.0 = 0x4000000000000000 little-endian.
  assert.deepEqual([...enc.encodeReplayControl({ command: enc.ReplayCommand.Speed, value: 2 })],
    [0x54, 19, ...le64(0n), 3, 0, 0, 0, 0, 0, 0, 0, 0x40]);
  assert.deepEqual([...enc.encodeReplayControl({ token: 5n, command: enc.ReplayCommand.Pause })],
    [0x54, 19, ...le64(5n), 1, 0, 0, 0, 0, 0, 0, 0, 0]);
  for (const [command, value] of [[0, 1], [2, -1], [2, NaN], [3, 0], [3, 65], [4, 0]]) {
    assert.throws(() => enc.encodeReplayControl({ command, value }), RangeError, `${command} ${value}`);
  }
});

test('InsertCrowd / RemoveCrowd match the C++ golden bytes and hand-computed layouts', () => {
  const crowdJson = '{"format":"throng-crowd/1","id":"tour","populations":[{"id":"p","count":3}]}';
  const goldens = {
    insert_crowd: () => enc.encodeInsertCrowd({ token, requestId: 300, crowdJson }),
    remove_crowd: () => enc.encodeRemoveCrowd({ token, requestId: 301, crowdId: 'tour' }),
  };
  for (const [name, make] of Object.entries(goldens)) {
    const file = path.join(golden, `${name}.bin`);
    assert.deepEqual([...make()], [...fs.readFileSync(file)], name);
  }
  // RemoveCrowd: u64 token, varint request 1, string "ab".
  assert.deepEqual([...enc.encodeRemoveCrowd({ token: 2n, requestId: 1, crowdId: 'ab' })], [0x54, 22, ...le64(2n), 1, 2, 0x61, 0x62]);
  // InsertCrowd: an object is sent as its JSON; over 1 MiB is refused.
  assert.deepEqual([...enc.encodeInsertCrowd({ token: 0n, requestId: 128, crowdJson: {} })], [0x54, 21, ...le64(0n), 0x80, 0x01, 2, 0x7b, 0x7d]);
  assert.throws(() => enc.encodeInsertCrowd({ token: 1n, requestId: 1, crowdJson: 'x'.repeat(enc.kMaxCrowdJson + 1) }), RangeError);
});
