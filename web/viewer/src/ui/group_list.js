// Group list: the world's groups (world description: id, population, members) in a drop-down, so a
// participant can pick one without finding its members on screen; Guide makes the picked group
// follow the participant's avatar, Release gives it back. Shows which groups this viewer guides
// (from GuideResult) and how many of a group's members are in view. Writes nothing but the DOM;
// onSelect / onGuide / onRelease go to main.js.
export class GroupList {
  constructor(root, { onSelect, onGuide, onRelease }) {
    this.root = root;
    this.$ = (id) => root.querySelector(`#${id}`);
    this.select = this.$('group-select');
    this.guideButton = this.$('group-guide');
    this.releaseButton = this.$('group-release');
    this.status = this.$('group-status');
    this.groups = [];
    this.guiding = new Set();
    this.joined = false;
    this.select.onchange = () => { this.refresh(); onSelect(this.selected()); };
    this.guideButton.onclick = () => { const g = this.selected(); if (g >= 0) onGuide(g); };
    this.releaseButton.onclick = () => { const g = this.selected(); if (g >= 0) onRelease(g); };
  }

  /** The world description's groups: [{id, population, members}]. */
  setGroups(groups) {
    const keep = this.selected();
    const signature = JSON.stringify((groups || []).map((g) => [g.id, g.population, (g.members || []).length]));
    this.groups = groups || [];
    if (signature === this.signature) return;  // unchanged: leave an open drop-down alone
    this.signature = signature;
    this.select.replaceChildren();
    const none = document.createElement('option');
    none.value = '-1';
    none.textContent = this.groups.length ? `groups (${this.groups.length})…` : 'no groups';
    this.select.append(none);
    for (const g of this.groups) {
      const o = document.createElement('option');
      o.value = String(g.id);
      o.textContent = `group ${g.id}${g.population ? ` · ${g.population}` : ''} · ${(g.members || []).length}`;
      this.select.append(o);
    }
    if (this.groups.some((g) => g.id === keep)) this.select.value = String(keep);
    this.$('group-row').classList.toggle('hidden', this.groups.length === 0);
    this.refresh();
  }

  selected() { const v = this.select.value; return v === '' || v === undefined ? -1 : Number(v); }

  /** Picks group `g` (e.g. the group of a clicked agent). */
  pick(g) {
    if (g === undefined || !this.groups.some((x) => x.id === g)) return;
    this.select.value = String(g);
    this.refresh();
  }

  setJoined(joined) {
    this.joined = joined;
    if (!joined) { this.guiding.clear(); this.status.textContent = ''; }
    this.refresh();
  }

  guideResult(r, text) {
    if (r.ok) { if (r.guiding) this.guiding.add(r.groupId); else this.guiding.delete(r.groupId); }
    const list = [...this.guiding].map((x) => `#${x}`).join(', ');
    this.status.textContent = list ? `${text}; guiding ${list}` : text;
    this.refresh();
  }

  refresh() {
    const g = this.selected();
    const can = this.joined && g >= 0;
    this.guideButton.disabled = !can || this.guiding.has(g);
    this.releaseButton.disabled = !can || !this.guiding.has(g);
    this.guideButton.title = this.joined ? 'the group follows your avatar' : 'join first: the group follows your avatar';
  }
}
