// Trails of a large crowd as a raster on the floor (src/crowd/trail_map.js, and Trails switching to
// it in src/crowd/trails.js): the layout within its caps, stamps and ages coming round modulo 255,
// opacity by age, segments drawn where they lie (clipped), sweeping only what is too old; a big
// crowd in a flat world goes to the map, a small one or a multi-level world stays with lines.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import * as THREE from 'three';
import { rasterLayout, stampOf, stampAge, slotOpacity, TrailRaster, kMapSlots, kMapMaxPx } from '../src/crowd/trail_map.js';
import { Trails, kLineBudget } from '../src/crowd/trails.js';

test('the raster is at most 10 px/m and 1024 px a side', () => {
  assert.deepEqual(rasterLayout({ minX: 0, minY: 0, maxX: 20, maxY: 12 }), { nx: 200, ny: 120, ppm: 10, minX: 0, minY: 0 });
  const big = rasterLayout({ minX: -100, minY: 0, maxX: 300, maxY: 50 });
  assert.equal(big.nx, kMapMaxPx);
  assert.ok(big.ny <= kMapMaxPx && Math.abs(big.ppm - kMapMaxPx / 400) < 1e-9);
});

test('stamps run 1–255 and ages come round modulo 255; opacity fades, none from the window on', () => {
  assert.deepEqual([stampOf(0), stampOf(254), stampOf(255), stampOf(-1)], [1, 255, 1, 255]);
  assert.equal(stampAge(stampOf(7), stampOf(7)), 0);
  assert.equal(stampAge(stampOf(250), stampOf(256)), 6, 'across the wrap');
  assert.equal(slotOpacity(0), 1);
  assert.ok(slotOpacity(kMapSlots - 1) > 0 && slotOpacity(kMapSlots - 1) < slotOpacity(1));
  assert.equal(slotOpacity(kMapSlots), 0);
});

test('a segment marks the pixels between its ends, clipped to the raster; sweep clears the old only', () => {
  const r = new TrailRaster({ minX: 0, minY: 0, maxX: 10, maxY: 10 });  // 100 × 100 px
  r.segment(1, 1, 3, 1, 200, 100, 50, 9);
  const at = (x, y) => [...r.data.subarray((y * r.nx + x) * 4, (y * r.nx + x) * 4 + 4)];
  for (const x of [10, 20, 30]) assert.deepEqual(at(x, 10), [200, 100, 50, 9], `pixel ${x}`);
  assert.deepEqual(at(10, 30), [0, 0, 0, 0], 'nothing off the segment');
  r.segment(9, 9, 14, 9, 1, 2, 3, 4);  // runs off the raster's east edge
  assert.deepEqual(at(99, 90), [1, 2, 3, 4]);
  r.sweep(9 + kMapSlots - 1);  // the first segment still inside the window
  assert.equal(at(20, 10)[3], 9);
  r.sweep(9 + kMapSlots);
  assert.equal(at(20, 10)[3], 0, 'swept once as old as the window');
  r.clear();
  assert.ok(r.data.every((v) => v === 0));
});

/** `n` agents walking east at 1 m/s in rows 1 m apart, sampled every 0.1 s up to time `until`. */
function walk(trails, n, until, from = 0) {
  const ids = Uint32Array.from({ length: n }, (_, i) => i);
  const y = Float32Array.from({ length: n }, (_, i) => 1 + (i % 50));
  const z = new Float32Array(n);
  for (let t = from; t <= until + 1e-9; t += 0.1) {
    trails.record({ ids, x: new Float32Array(n).fill(1 + t), y, z, count: n }, t);
  }
}

test('a big crowd in a flat world is drawn into the map; a small one or a multi-level world keeps lines', () => {
  const flat = { minX: 0, minY: 0, maxX: 60, maxY: 60, minZ: 0, maxZ: 0 };
  const per = new Trails(new THREE.Scene(), undefined, flat).buffer.cap - 1;  // segments an agent keeps
  const big = Math.ceil(kLineBudget / per) + 10;
  const t = new Trails(new THREE.Scene(), undefined, flat);
  t.enabled = true;
  walk(t, big, 3);
  assert.equal(t.mode, 'map');
  assert.ok(t.mapSegments >= big * 10, `${t.mapSegments} segments drawn for ${big} agents`);
  const r = t.map.raster, px = (x, y) => r.data[((Math.floor(y * r.ppm)) * r.nx + Math.floor(x * r.ppm)) * 4 + 3];
  assert.ok(px(2.5, 1) > 0 && px(3.9, 1) > 0, 'stamped along the walk');
  assert.equal(px(10, 1), 0, 'nothing ahead of the walkers');
  walk(t, big, 1, 0.05);  // time went back (a replay seeked): the map starts afresh
  assert.equal(px(3.9, 1), 0);
  t.enabled = false;
  assert.equal(t.mode, 'lines');

  const small = new Trails(new THREE.Scene(), undefined, flat);
  small.enabled = true;
  walk(small, 10, 3);
  assert.equal(small.mode, 'lines');
  const levels = new Trails(new THREE.Scene(), undefined, { ...flat, maxZ: 3 });
  levels.enabled = true;
  walk(levels, big, 1);
  assert.equal(levels.mode, 'lines');
});
