// Where "fit to world" puts the world on screen: the part of the viewport the panels leave free
// (pure, test/framing.test.js). The viewer's panels sit in the corners and along the bottom (HUD,
// controls, legend, measurements, timeline); framing the world over the whole canvas hides part of
// it behind them (the museum's north-east corner under the controls at 1280×720). freeRect picks,
// among the rectangles of the viewport that overlap no panel, the one in which a picture of the
// world's aspect is drawn largest; the cameras (cameras.js fit) then frame the world in it.

/** Gap [px] kept between the world's picture and a panel. */
export const kPanelGap = 6;
/** When the best free rectangle would draw the world smaller than this fraction of the size the
 * whole viewport gives it (a small window mostly covered by panels), the whole viewport is used. */
export const kMinFreeScale = 0.4;

/**
 * The rectangle {left, top, right, bottom} [px] of a `width` × `height` viewport in which a picture
 * `aspect` (width / height) wide is drawn largest without overlapping any of `panels` ({left, top,
 * right, bottom} [px], each grown by `gap`); ties go to the larger rectangle. Candidates are the
 * maximal empty rectangles, whose edges are the viewport's or a panel's. The whole viewport when
 * there are no panels, or when the best rectangle would draw the picture under kMinFreeScale of
 * the whole viewport's size (`full: true` then).
 */
export function freeRect(width, height, panels, aspect, gap = kPanelGap) {
  const whole = { left: 0, top: 0, right: width, bottom: height, full: true };
  const a = aspect > 0 && Number.isFinite(aspect) ? aspect : 1;
  const scaleOf = (w, h) => Math.min(w / a, h);  // the picture's height when it fits in w × h
  const boxes = panels
    .map((p) => ({ left: p.left - gap, top: p.top - gap, right: p.right + gap, bottom: p.bottom + gap }))
    .filter((p) => p.right > 0 && p.bottom > 0 && p.left < width && p.top < height && p.right > p.left && p.bottom > p.top);
  if (!boxes.length) return whole;
  const clamp = (v, hi) => Math.min(Math.max(v, 0), hi);
  const lefts = [0, ...boxes.map((p) => clamp(p.right, width))];
  const rights = [width, ...boxes.map((p) => clamp(p.left, width))];
  const tops = [0, ...boxes.map((p) => clamp(p.bottom, height))];
  const bottoms = [height, ...boxes.map((p) => clamp(p.top, height))];
  let best = null, bestScale = -1, bestArea = -1;
  for (const l of lefts) {
    for (const r of rights) {
      if (r - l < 1) continue;
      for (const t of tops) {
        for (const b of bottoms) {
          if (b - t < 1) continue;
          if (boxes.some((p) => p.left < r && l < p.right && p.top < b && t < p.bottom)) continue;
          const s = scaleOf(r - l, b - t), area = (r - l) * (b - t);
          if (s > bestScale + 1e-9 || (Math.abs(s - bestScale) <= 1e-9 && area > bestArea)) {
            best = { left: l, top: t, right: r, bottom: b, full: false };
            bestScale = s; bestArea = area;
          }
        }
      }
    }
  }
  if (!best || bestScale < kMinFreeScale * scaleOf(width, height)) return whole;
  return best;
}

/** Does rectangle `a` overlap rectangle `b` (both {left, top, right, bottom}; touching is not)? */
export function overlaps(a, b) {
  return a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
}

/**
 * The plan camera's frame that shows the box spanX × spanY [m] (at least 4 m each way) whole and as
 * large as fits in `rect` of a `width` × `height` viewport [px], centred in it, with `margin` (0.06:
 * 6 % of the rectangle on each side): {pxPerMetre, halfW, halfH} (the orthographic frustum's
 * half-sizes [m] at zoom 1) and {dx, dy} [m], where the camera's centre goes relative to the box's
 * centre (world x east, y north) so that the box's centre lands on the rectangle's.
 */
export function planFrame(spanX, spanY, width, height, rect, margin = 0.06) {
  const rw = rect.right - rect.left, rh = rect.bottom - rect.top;
  const s = Math.min(rw / Math.max(spanX, 4), rh / Math.max(spanY, 4)) / (1 + 2 * margin);
  const rcx = (rect.left + rect.right) / 2, rcy = (rect.top + rect.bottom) / 2;
  return { pxPerMetre: s, halfW: width / 2 / s, halfH: height / 2 / s, dx: -(rcx - width / 2) / s, dy: (rcy - height / 2) / s };
}
