// HUD figures (src/ui/hud.js): the simulated-time clock, and agents present and gone from the
// ids of successive frames (afresh after a seek back).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { clock, Attendance, hudWorld, timeWords, goneWords } from '../src/ui/hud.js';

test('clock formats seconds as m:ss or h:mm:ss', () => {
  assert.equal(clock(0), '0:00');
  assert.equal(clock(83.9), '1:23');
  assert.equal(clock(300), '5:00');
  assert.equal(clock(3725), '1:02:05');
  assert.equal(clock(-4), '0:00');
});

test('agents gone: seen in an earlier frame, not in the latest', () => {
  const a = new Attendance();
  a.frame(Uint32Array.of(1, 2, 3), 3);
  assert.deepEqual([a.present, a.gone], [3, 0]);
  a.frame(Uint32Array.of(2, 3, 4, 5), 4);
  assert.deepEqual([a.present, a.gone], [4, 1], 'agent 1 left, 4 and 5 came');
  a.frame(Uint32Array.of(5), 1);
  assert.deepEqual([a.present, a.gone], [1, 4]);
});

test('a replay seeked back starts the count of agents gone afresh', () => {
  const a = new Attendance();
  a.frame(Uint32Array.of(1, 2, 3), 3, 100);
  a.frame(Uint32Array.of(3), 1, 150);
  assert.equal(a.gone, 2);
  a.frame(Uint32Array.of(1), 1, 20);
  assert.deepEqual([a.present, a.gone], [1, 0]);
});

test('a replay seeked forward counts those gone since the jump, and says so', () => {
  const a = new Attendance();
  a.frame(Uint32Array.of(1, 2, 3), 3, 0, 40);
  a.frame(Uint32Array.of(2, 3), 2, 2, 40);
  assert.equal(goneWords(a, 0.05), '  (1 gone)');
  a.frame(Uint32Array.of(7, 8, 9), 3, 300, 40);  // 15 s on: a seek (more than 40 ticks)
  assert.deepEqual([a.present, a.gone, a.since], [3, 0, 300], 'those jumped over were never seen');
  a.frame(Uint32Array.of(9), 1, 302, 40);
  assert.equal(goneWords(a, 0.05), '  (2 gone since 0:15)');
});

test('past the scenario\'s duration the clock says it runs on', () => {
  assert.equal(timeWords(65, 300), '1:05 of 5:00');
  assert.equal(timeWords(331, 300), '5:31 (its 5:00 are over; it runs on)');
  assert.equal(timeWords(331, 0), '5:31');
});

test("the clock counts towards a recording's length when replaying, else the scenario's duration", () => {
  const scenario = { name: 'bottleneck', duration: 300 };
  assert.deepEqual(hudWorld({ dt: 0.05, scenario }), { name: 'bottleneck', dt: 0.05, duration: 300, about: '' });
  assert.equal(hudWorld({ dt: 0.05, scenario, replay: { duration: 60, fps: 10 } }).duration, 60);
  assert.equal(hudWorld({ dt: 0.05, scenario: { name: 'open' } }).duration, 0);
  assert.equal(hudWorld({ tickRate: 20, scenario: {} }).dt, 0.05);
});

test("the scenario's description is what the HUD says the world is about", () => {
  const about = '100 people leave a room by a 1 m door: watch the jam.';
  assert.equal(hudWorld({ dt: 0.05, scenario: { name: 'bottleneck', description: about } }).about, about);
  assert.equal(hudWorld({ dt: 0.05, scenario: { name: 'x', description: 42 } }).about, '', 'only a string');
});
