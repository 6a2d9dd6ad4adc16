// Fit to the free part of the viewport (src/camera/framing.js): freeRect finds, among the rectangles
// that overlap no panel, the one in which a picture of the world's aspect is largest (checked
// against a brute-force search over a pixel grid), falls back to the whole viewport when the panels
// leave too little; planFrame puts the world's box inside that rectangle, centred, with its margin.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { freeRect, overlaps, planFrame, kPanelGap, kMinFreeScale } from '../src/camera/framing.js';

const rect = (left, top, w, h) => ({ left, top, right: left + w, bottom: top + h });
// The viewer's panels at 1280×720 with the museum (HUD top left, controls top right, legend bottom left).
const kPanels1280 = [rect(10, 10, 188, 111), rect(1010, 10, 260, 183), rect(10, 427, 212, 283)];
const grown = (p, g = kPanelGap) => ({ left: p.left - g, top: p.top - g, right: p.right + g, bottom: p.bottom + g });
const scale = (r, aspect) => Math.min((r.right - r.left) / aspect, r.bottom - r.top);

/** The largest picture height over every rectangle on a `step` px grid that overlaps no panel. */
function bruteBest(width, height, panels, aspect, step = 10) {
  const boxes = panels.map((p) => grown(p));
  let best = 0;
  for (let l = 0; l < width; l += step) {
    for (let t = 0; t < height; t += step) {
      for (let r = width; r > l; r -= step) {
        for (let b = height; b > t; b -= step) {
          const c = { left: l, top: t, right: r, bottom: b };
          if (scale(c, aspect) <= best) break;  // smaller b only shrinks it
          if (!boxes.some((p) => overlaps(p, c))) { best = scale(c, aspect); break; }
        }
      }
    }
  }
  return best;
}

test('without panels the world gets the whole viewport', () => {
  assert.deepEqual(freeRect(1280, 720, [], 2), { left: 0, top: 0, right: 1280, bottom: 720, full: true });
  assert.deepEqual(freeRect(640, 360, [rect(-300, 10, 100, 100)], 2).full, true, 'a panel off screen is no panel');
});

test('the free rectangle overlaps no panel and is the best one for the picture\'s aspect', () => {
  for (const aspect of [0.5, 1, 1.9, 3, 6]) {
    const r = freeRect(1280, 720, kPanels1280, aspect);
    assert.equal(r.full, false, `aspect ${aspect}`);
    for (const p of kPanels1280) assert.ok(!overlaps(grown(p), r), `aspect ${aspect}: ${JSON.stringify(r)} clear of ${JSON.stringify(p)} by ${kPanelGap} px`);
    assert.ok(r.left >= 0 && r.top >= 0 && r.right <= 1280 && r.bottom <= 720, `inside the viewport: ${JSON.stringify(r)}`);
    const brute = bruteBest(1280, 720, kPanels1280, aspect);
    assert.ok(scale(r, aspect) >= brute - 1e-9, `aspect ${aspect}: picture ${scale(r, aspect).toFixed(1)} px high, the best on a 10 px grid ${brute.toFixed(1)}`);
  }
});

test('a wide world goes under the top panels, a tall one between the side panels', () => {
  const wide = freeRect(1280, 720, kPanels1280, 1.9);   // the museum: 51 × 27 m
  assert.ok(wide.top >= 193 + kPanelGap && wide.left >= 222 + kPanelGap, JSON.stringify(wide));
  const tall = freeRect(1280, 720, kPanels1280, 0.5);
  assert.equal(tall.top, 0);
  assert.equal(tall.bottom, 720);
  assert.ok(tall.left >= 222 && tall.right <= 1010, JSON.stringify(tall));
});

test('panels that leave too little give the whole viewport back', () => {
  // A 400 × 300 window with a control panel 260 wide and 250 high in its top right and a HUD top left.
  const panels = [rect(10, 10, 188, 111), rect(130, 10, 260, 250)];
  const r = freeRect(400, 300, panels, 2);
  assert.equal(r.full, true, JSON.stringify(r));
  // The same panels in a large window leave plenty.
  assert.equal(freeRect(1600, 900, panels, 2).full, false);
  assert.ok(kMinFreeScale > 0 && kMinFreeScale < 1);
});

test('planFrame puts the box in the rectangle, centred, with the margin', () => {
  const r = rect(228, 199, 1052, 521);
  for (const [spanX, spanY] of [[51, 27], [10, 30], [200, 5], [1, 1]]) {
    const f = planFrame(spanX, spanY, 1280, 720, r, 0.06);
    const sx = Math.max(spanX, 4), sy = Math.max(spanY, 4);
    // The box centred at the world's origin: screen x = W/2 + (X − camX)·s, screen y = H/2 − (Y − camY)·s.
    const toScreen = (X, Y) => [640 + (X - f.dx) * f.pxPerMetre, 360 - (Y - f.dy) * f.pxPerMetre];
    const [cx, cy] = toScreen(0, 0);
    assert.ok(Math.abs(cx - (r.left + r.right) / 2) < 1e-6 && Math.abs(cy - (r.top + r.bottom) / 2) < 1e-6, 'centred');
    const [l, t] = toScreen(-sx / 2, sy / 2), [rr, b] = toScreen(sx / 2, -sy / 2);
    assert.ok(l >= r.left - 1e-6 && rr <= r.right + 1e-6 && t >= r.top - 1e-6 && b <= r.bottom + 1e-6, `inside: ${[l, t, rr, b]}`);
    const fill = Math.max((rr - l) / (r.right - r.left), (b - t) / (r.bottom - r.top));
    assert.ok(Math.abs(fill - 1 / 1.12) < 1e-6, `fills the rectangle but the margins: ${fill}`);
    assert.ok(Math.abs(f.halfW / f.halfH - 1280 / 720) < 1e-9, 'the frustum has the viewport\'s aspect');
  }
});
