// Labels at a fixed screen size: one absolutely positioned <div> per labelled thing in an overlay
// above the canvas — participants' names (`name-label`, from Presence; your own too) and the
// world's points (`point-label`, their ids, coloured by kind) — so a label reads the same at any
// zoom and never grows over the agents. Each frame the caller gives every label's anchor on screen
// (the point above a head or a marker); label_layout.js keeps only those clear of each other and
// of the panels (HUD, controls, agent panel, legend, help, timeline), most important and nearest
// first. Point labels can be switched off (key L); names always show. Reads the panels' rectangles
// (every 250 ms) and the labels' sizes (once per text); writes the overlay's children.
import { layoutLabels } from './label_layout.js';

const kPanels = ['hud', 'controls', 'agent-panel', 'timeline', 'legend', 'help'];

export class ScreenLabels {
  constructor(root) {
    this.root = root;
    this.divs = new Map();  // key → {div, w, h, text}
    this.showPoints = true;
    this.blockers = [];
    this.blockersAt = -Infinity;
  }

  /** Rectangles of the visible panels, re-read every 250 ms. */
  panels(now) {
    if (now - this.blockersAt < 250) return this.blockers;
    this.blockersAt = now;
    this.blockers = [];
    for (const id of kPanels) {
      const el = document.getElementById(id);
      if (!el || el.classList.contains('hidden')) continue;
      const r = el.getBoundingClientRect();
      if (r.width > 0 && r.height > 0) this.blockers.push({ left: r.left, top: r.top, w: r.width, h: r.height });
    }
    return this.blockers;
  }

  entry(key, text, cls) {
    let e = this.divs.get(key);
    if (!e) {
      const div = document.createElement('div');
      this.root.appendChild(div);
      e = { div, text: null };
      this.divs.set(key, e);
    }
    if (e.div.className !== cls) e.div.className = cls;
    if (e.text !== text) {
      e.text = text;
      e.div.textContent = text;
      e.div.style.display = '';
      e.w = e.div.offsetWidth; e.h = e.div.offsetHeight;
    }
    return e;
  }

  /** entries: [{key, name, screen: {x, y} | null, kind: 'name' | 'exit' | 'action' | 'interest',
   * importance, distance [m]}]; labels of keys not listed are removed. */
  update(entries, now = performance.now()) {
    const seen = new Set();
    const items = [];
    for (const en of entries) {
      const isName = !en.kind || en.kind === 'name';
      if (!isName && !this.showPoints) continue;
      seen.add(en.key);
      const e = this.entry(en.key, en.name, isName ? 'name-label' : `point-label point-${en.kind}`);
      if (en.screen) {
        items.push({ key: en.key, x: en.screen.x, y: en.screen.y, w: e.w, h: e.h,
          importance: en.importance ?? (isName ? 10 : 1), distance: en.distance ?? 0 });
      }
    }
    const shown = layoutLabels(items, this.panels(now), { w: innerWidth, h: innerHeight });
    for (const [k, e] of this.divs) {
      if (!seen.has(k)) { e.div.remove(); this.divs.delete(k); continue; }
      const at = shown.get(k);
      e.div.style.display = at ? '' : 'none';
      if (at) e.div.style.transform = `translate(${Math.round(at.left)}px, ${Math.round(at.top)}px)`;
    }
  }

  /** Texts of the labels on screen (for tests); `cls`: only those of that class. */
  visible(cls = null) {
    return [...this.divs.values()].filter((e) => e.div.style.display !== 'none' && (!cls || e.div.classList.contains(cls)))
      .map((e) => e.text);
  }
}
