// Label layout — pure, no DOM: which labels to show and where, so that none overlaps another or a
// panel (HUD, controls, legend…). Greedy screen-space collision culling: the labels are taken by
// importance (participants' names, then exits, actions, interest points), then nearest first;
// each is placed centred above its anchor and kept only when its rectangle lies inside the
// viewport and clear of every panel and every label already kept. Screen pixels throughout.

/** Do rectangles {left, top, w, h} a and b overlap, with `pad` px kept between them? */
export function overlaps(a, b, pad = 0) {
  return a.left < b.left + b.w + pad && b.left < a.left + a.w + pad && a.top < b.top + b.h + pad && b.top < a.top + a.h + pad;
}

/** items: [{key, x, y (anchor: the label's bottom centre), w, h, importance, distance}];
 * blockers: panel rectangles [{left, top, w, h}]; viewport {w, h}. Returns Map key → {left, top}
 * of the labels to show. `pad`: px kept clear around each label. */
export function layoutLabels(items, blockers, viewport, pad = 2) {
  const order = items.filter((it) => Number.isFinite(it.x) && Number.isFinite(it.y))
    .sort((a, b) => (b.importance - a.importance) || (a.distance - b.distance) || (String(a.key) < String(b.key) ? -1 : 1));
  const placed = [];
  const out = new Map();
  for (const it of order) {
    const r = { left: it.x - it.w / 2, top: it.y - it.h, w: it.w, h: it.h };
    if (r.left < 0 || r.top < 0 || r.left + r.w > viewport.w || r.top + r.h > viewport.h) continue;
    if (blockers.some((b) => overlaps(r, b, pad))) continue;
    if (placed.some((p) => overlaps(r, p, pad))) continue;
    placed.push(r);
    out.set(it.key, { left: r.left, top: r.top });
  }
  return out;
}
