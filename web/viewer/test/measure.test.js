// Live measurements (src/crowd/measure.js) against hand-computed answers: crossings of a line,
// flow over the window, classic density and speed in an area, the fundamental-diagram samples.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { LineMeter, AreaMeter, Measurements, segmentsCross } from '../src/crowd/measure.js';

const frame = (agents) => ({
  count: agents.length,
  ids: Uint32Array.from(agents.map((a) => a[0])),
  x: Float32Array.from(agents.map((a) => a[1])),
  y: Float32Array.from(agents.map((a) => a[2])),
});
const near = (a, b, eps = 1e-6) => Math.abs(a - b) <= eps;

test('segments cross, or do not', () => {
  assert.ok(segmentsCross([0, -1], [0, 1], [-1, 0], [1, 0]));
  assert.ok(!segmentsCross([2, -1], [2, 1], [-1, 0], [1, 0]));   // beside the line
  assert.ok(!segmentsCross([0, 1], [0, 2], [-1, 0], [1, 0]));    // not reaching it
});

test('a line counts crossings both ways and gives the flow over its window', () => {
  const m = new LineMeter([[5, 0], [5, 2]], 10);  // 2 m long, at x = 5
  // Agent 1 walks east across at t 1 -> 2; agent 2 west across at t 3 -> 4; agent 3 never crosses.
  const step = (t, a) => { const f = frame(a); m.record(f.ids, f.x, f.y, f.count, t); };
  step(0, [[1, 4.0, 1], [2, 6, 1], [3, 1, 1]]);
  step(1, [[1, 4.6, 1], [2, 6, 1], [3, 1.5, 1]]);
  step(2, [[1, 5.4, 1], [2, 5.8, 1], [3, 2, 1]]);
  step(3, [[1, 6.0, 1], [2, 5.3, 1], [3, 2.5, 1]]);
  step(4, [[1, 6.5, 1], [2, 4.7, 1], [3, 3, 1]]);
  assert.equal(m.total, 2);
  assert.ok(near(m.flow(), 2 / 4));          // 2 crossings in the 4 s seen
  assert.ok(near(m.specificFlow(), 0.25));   // over 2 m
  step(20, [[1, 7, 1], [2, 4, 1], [3, 3, 1]]);
  assert.ok(near(m.flow(), 0));              // both out of the 10 s window
  step(1, [[1, 4, 1]]);                      // seeking back starts afresh
  assert.equal(m.total, 0);
});

test('an area gives the classic density and the speed of those inside', () => {
  const m = new AreaMeter([[0, 0], [2, 0], [2, 2], [0, 2]], 10);  // 4 m²
  const step = (t, a) => { const f = frame(a); m.record(f.ids, f.x, f.y, f.count, t); };
  step(0, [[1, 0.5, 0.5], [2, 1.5, 0.5], [3, 5, 5]]);
  step(1, [[1, 1.0, 0.5], [2, 1.5, 1.5], [3, 5, 5]]);   // 0.5 m/s and 1 m/s
  assert.ok(near(m.density(), 2 / 4));                  // 2 inside in both frames
  assert.ok(near(m.speed(), 0.75));
  assert.equal(m.fd.length, 1);
  assert.ok(near(m.fd[0].density, 0.5) && near(m.fd[0].speed, 0.75));
  step(2, [[1, 1.2, 0.5], [2, 3, 1.5], [3, 5, 5]]);     // agent 2 left
  assert.ok(near(m.density(), (2 + 2 + 1) / (3 * 4)));
});

test('the scenario list becomes one meter per entry, rows for the panel', () => {
  const ms = new Measurements([
    { id: 'door', line: [[5, 0], [5, 2]] },
    { id: 'room', polygon: [[0, 0], [2, 0], [2, 2], [0, 2]] },
    { id: 'bad', line: [[0, 0]] },
  ]);
  assert.equal(ms.size, 2);
  ms.record(frame([[1, 1, 1]]), 0);
  ms.record(frame([[1, 1.5, 1]]), 1);
  const rows = ms.rows();
  assert.deepEqual(rows.map((r) => [r.id, r.kind]), [['door', 'line'], ['room', 'area']]);
  assert.match(rows[1].text, /0\.25 \/m² · 0\.50 m\/s/);
});
