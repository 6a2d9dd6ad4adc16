// Label layout (src/ui/label_layout.js): of many labels crowding a small screen, the ones kept never
// overlap each other or a panel and stay inside the viewport; the more important one wins a
// collision, then the nearer; a label with room is always kept.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { layoutLabels, overlaps } from '../src/ui/label_layout.js';

/** A deterministic pseudo-random sequence in [0, 1). */
function rng(seed) {
  let s = seed >>> 0;
  return () => ((s = (Math.imul(s, 1664525) + 1013904223) >>> 0) / 2 ** 32);
}

test('kept labels overlap neither each other nor a panel, and stay on screen', () => {
  const r = rng(7);
  const viewport = { w: 640, h: 360 };
  const hud = { left: 10, top: 10, w: 180, h: 150 };
  for (let round = 0; round < 20; ++round) {
    const items = Array.from({ length: 150 }, (_, k) => ({
      key: k, x: r() * 700 - 30, y: r() * 400, w: 30 + r() * 60, h: 15, importance: Math.floor(r() * 4), distance: r() * 50,
    }));
    const shown = layoutLabels(items, [hud], viewport);
    const rects = [...shown].map(([k, p]) => ({ ...p, w: items[k].w, h: items[k].h }));
    assert.ok(rects.length > 10, `some labels are kept (${rects.length})`);
    for (let i = 0; i < rects.length; ++i) {
      const a = rects[i];
      assert.ok(a.left >= 0 && a.top >= 0 && a.left + a.w <= viewport.w && a.top + a.h <= viewport.h, 'on screen');
      assert.ok(!overlaps(a, hud), 'not over the HUD');
      for (let j = i + 1; j < rects.length; ++j) assert.ok(!overlaps(a, rects[j]), `labels ${i} and ${j} overlap`);
    }
  }
});

test('a collision keeps the more important label, then the nearer', () => {
  const v = { w: 640, h: 360 };
  const a = { key: 'a', x: 100, y: 100, w: 60, h: 15, importance: 1, distance: 5 };
  const b = { key: 'b', x: 110, y: 105, w: 60, h: 15, importance: 3, distance: 50 };
  assert.deepEqual([...layoutLabels([a, b], [], v).keys()], ['b']);
  const c = { ...b, importance: 1 };
  assert.deepEqual([...layoutLabels([c, a], [], v).keys()], ['a']);
  const far = { ...b, key: 'far', x: 400 };
  assert.deepEqual([...layoutLabels([a, far], [], v).keys()].sort(), ['a', 'far'], 'labels apart are both kept');
  assert.deepEqual(layoutLabels([{ ...a, y: 5 }], [], v).size, 0, 'off the top of the screen: dropped');
  assert.equal(layoutLabels([a], [{ left: 0, top: 0, w: 200, h: 200 }], v).size, 0, 'under a panel: dropped');
  assert.deepEqual(layoutLabels([a], [], v).get('a'), { left: 70, top: 85 }, 'centred above its anchor');
});
