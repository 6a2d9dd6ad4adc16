// The heatmaps' grids (src/crowd/heatmap.js): PedPy's classic density per cell, averaged
// over the last seconds of frames, and the mean speed per cell, against values done by hand.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { DensityGrid, SpeedGrid } from '../src/crowd/heatmap.js';

const bounds = { minX: 0, minY: 0, maxX: 10, maxY: 4 };

test('one frame: persons in a cell / its area', () => {
  const g = new DensityGrid(bounds, 1, 5);
  // Three in cell (2, 1), one in (9, 3), one outside the world.
  g.record(Float32Array.of(2.1, 2.5, 2.9, 9.5, 12), Float32Array.of(1.2, 1.5, 1.9, 3.5, 1), 5, 0);
  assert.equal(g.nx, 10);
  assert.equal(g.ny, 4);
  assert.equal(g.density(2, 1), 3);
  assert.equal(g.density(9, 3), 1);
  assert.equal(g.densityAt(0.5, 0.5), 0);
  assert.equal(g.densityAt(2.5, 1.5), 3);
});

test('half-metre cells divide by 0.25 m²', () => {
  const g = new DensityGrid(bounds, 0.5, 5);
  g.record(Float32Array.of(0.1, 0.2), Float32Array.of(0.1, 0.3), 2, 0);
  assert.equal(g.density(0, 0), 8);
});

test('the mean over the window, frames older than it dropped, time going back clears', () => {
  const g = new DensityGrid(bounds, 1, 5);
  const one = [Float32Array.of(0.5), Float32Array.of(0.5)];
  g.record(...one, 1, 0);                                    // someone in (0, 0) at t = 0
  g.record(Float32Array.of(5.5), Float32Array.of(0.5), 1, 1);  // elsewhere at t = 1
  assert.equal(g.densityAt(0.5, 0.5), 0.5);                 // 1 of 2 frames
  g.record(...one, 1, 1);                                    // the same frame again: not counted twice
  assert.equal(g.densityAt(0.5, 0.5), 0.5);
  for (let t = 2; t <= 7; ++t) g.record(Float32Array.of(5.5), Float32Array.of(0.5), 1, t);
  assert.equal(g.densityAt(0.5, 0.5), 0);                   // t = 0 has left the 5 s window
  assert.equal(g.densityAt(5.5, 0.5), 1);
  g.record(...one, 1, 3);                                    // a replay seeked back
  assert.equal(g.frames.length, 1);
  assert.equal(g.densityAt(0.5, 0.5), 1);
});

test('speed map: mean speed per cell from successive frames, jumps and newcomers give no sample', () => {
  const g = new SpeedGrid(bounds, 1, 5);
  const ids = Uint32Array.of(1, 2, 3);
  g.recordSpeeds(ids, Float32Array.of(0.2, 5.5, 8.5), Float32Array.of(0.5, 0.5, 2.5), 3, 0);
  assert.equal(g.speedAt(0.5, 0.5), null);                 // first frame: no speeds yet
  // 1 walks 0.5 m in 0.5 s within cell (0, 0); 2 stands in (5, 0); 3 jumps 8 m (not walking).
  g.recordSpeeds(ids, Float32Array.of(0.7, 5.5, 0.5), Float32Array.of(0.5, 0.5, 2.5), 3, 0.5);
  assert.equal(g.speedAt(0.5, 0.5), 1);
  assert.equal(g.speedAt(5.5, 0.5), 0);                    // sampled, standing: 0 m/s, not empty
  assert.equal(g.speedAt(0.5, 2.5), null);                 // the jump gives no sample
  // 1 now walks 0.6 m in 0.5 s in the same cell: the mean of 1.0 and 1.2 m/s; a newcomer (4) none.
  g.recordSpeeds(Uint32Array.of(1, 4), Float32Array.of(0.1, 9.5), Float32Array.of(0.5, 3.5), 2, 1);
  assert.ok(Math.abs(g.speedAt(0.5, 0.5) - 1.1) < 1e-6);
  assert.equal(g.speedAt(9.5, 3.5), null);
  for (let t = 1.5; t <= 7; t += 0.5) g.recordSpeeds(Uint32Array.of(1), Float32Array.of(0.1), Float32Array.of(0.5), 1, t);
  assert.equal(g.speedAt(0.5, 0.5), 0);                    // the walking samples left the 5 s window
  assert.equal(g.speedAt(5.5, 0.5), null);
  g.recordSpeeds(Uint32Array.of(1), Float32Array.of(0.3), Float32Array.of(0.5), 1, 2);  // seeked back
  assert.equal(g.frames.length, 1);
  assert.equal(g.speedAt(0.5, 0.5), null);                 // starts afresh: no previous positions
});

test('the legend lists the speed map\'s ramp only while it shows', async () => {
  const { fixedEntries } = await import('../src/ui/legend.js');
  const labels = (on) => fixedEntries({ selected: 1, pickedGroup: 2, self: 3, other: 4, speedmap: on }).map((e) => e.label);
  assert.ok(labels(true).some((l) => l.startsWith('speed map:') && l.includes('m/s')), labels(true).join(', '));
  assert.ok(!labels(false).some((l) => l.startsWith('speed map')));
});
