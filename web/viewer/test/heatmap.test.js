// The density heatmap's grid (src/crowd/heatmap.js): PedPy's classic density per cell, averaged
// over the last seconds of frames, against counts done by hand.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { DensityGrid } from '../src/crowd/heatmap.js';

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
