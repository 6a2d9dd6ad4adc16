// Name labels above the participants' avatars: one absolutely positioned <div class="name-label">
// per avatar in an overlay, placed each frame at the screen point above the avatar's head (names
// from Presence; the local participant's own name too). Reads screen positions computed by the
// caller; writes the overlay's children.
export class NameLabels {
  constructor(root) { this.root = root; this.divs = new Map(); }

  /** entries: [{key, name, screen: {x, y} | null}]; labels of keys not listed are removed. */
  update(entries) {
    const seen = new Set();
    for (const e of entries) {
      seen.add(e.key);
      let d = this.divs.get(e.key);
      if (!d) {
        d = document.createElement('div');
        d.className = 'name-label';
        this.root.appendChild(d);
        this.divs.set(e.key, d);
      }
      if (d.textContent !== e.name) d.textContent = e.name;
      d.style.display = e.screen ? '' : 'none';
      if (e.screen) d.style.transform = `translate(${Math.round(e.screen.x)}px, ${Math.round(e.screen.y)}px) translate(-50%, -100%)`;
    }
    for (const [k, d] of this.divs) if (!seen.has(k)) { d.remove(); this.divs.delete(k); }
  }

  /** Texts of the labels on screen (for tests). */
  visible() { return [...this.divs.values()].filter((d) => d.style.display !== 'none').map((d) => d.textContent); }
}
