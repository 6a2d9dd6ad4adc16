// Group list: the world's groups (world description: id, population, members) in a drop-down, so a
// participant can pick one without finding its members on screen, filtered by the search box
// (filterGroups: population names, ids, sizes); Guide makes the picked group
// follow the participant's avatar, Release gives it back. Shows which groups this viewer guides
// (from GuideResult) and how many of a group's members are in view. Writes nothing but the DOM;
// onSelect / onGuide / onRelease go to main.js.
import { kRecordingNoGuide } from './agent_panel.js';

/** The groups matching `query`: words separated by spaces, all of which must match — a number or
 * #number: the group's id; >=n, <=n, >n, <n, =n: its size (members); any other word: part of its
 * population's name (case-insensitive). An empty query keeps every group. */
export function filterGroups(groups, query) {
  const words = String(query || '').trim().toLowerCase().split(/\s+/).filter(Boolean);
  const tests = words.map((w) => {
    const id = /^#?(\d+)$/.exec(w);
    if (id) return (g) => g.id === Number(id[1]);
    const size = /^(>=|<=|>|<|=)(\d+)$/.exec(w);
    if (size) {
      const n = Number(size[2]);
      const cmp = { '>=': (a) => a >= n, '<=': (a) => a <= n, '>': (a) => a > n, '<': (a) => a < n, '=': (a) => a === n }[size[1]];
      return (g) => cmp((g.members || []).length);
    }
    return (g) => String(g.population || '').toLowerCase().includes(w);
  });
  return (groups || []).filter((g) => tests.every((t) => t(g)));
}

export class GroupList {
  constructor(root, { onSelect, onGuide, onRelease }) {
    this.root = root;
    this.$ = (id) => root.querySelector(`#${id}`);
    this.select = this.$('group-select');
    this.guideButton = this.$('group-guide');
    this.releaseButton = this.$('group-release');
    this.status = this.$('group-status');
    this.filter = this.$('group-filter');
    this.query = '';
    if (this.filter) this.filter.oninput = () => { this.query = this.filter.value; this.signature = null; this.setGroups(this.groups); };
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
    const shown = filterGroups(this.groups, this.query);
    const none = document.createElement('option');
    none.value = '-1';
    none.textContent = !this.groups.length ? 'no groups'
      : shown.length === this.groups.length ? `groups (${this.groups.length})…` : `${shown.length} of ${this.groups.length} groups…`;
    this.select.append(none);
    for (const g of shown) {
      const o = document.createElement('option');
      o.value = String(g.id);
      o.textContent = `group ${g.id}${g.population ? ` · ${g.population}` : ''} · ${(g.members || []).length}`;
      this.select.append(o);
    }
    if (shown.some((g) => g.id === keep)) this.select.value = String(keep);
    this.$('group-row').classList.toggle('hidden', this.groups.length === 0);
    this.refresh();
  }

  selected() { const v = this.select.value; return v === '' || v === undefined ? -1 : Number(v); }

  /** Picks group `g` (e.g. the group of a clicked agent). */
  pick(g) {
    if (g === undefined || !this.groups.some((x) => x.id === g)) return;
    if (!filterGroups(this.groups, this.query).some((x) => x.id === g)) {  // picked on screen: show it
      this.query = '';
      if (this.filter) this.filter.value = '';
      this.signature = null;
      this.setGroups(this.groups);
    }
    this.select.value = String(g);
    this.refresh();
  }

  setJoined(joined) {
    this.joined = joined;
    if (!joined) { this.guiding.clear(); this.status.textContent = ''; }
    this.refresh();
  }

  /** A recording plays: its groups cannot be guided (the buttons say so). */
  setRecording(on) { this.recording = on; this.refresh(); }

  guideResult(r, text) {
    if (r.ok) { if (r.guiding) this.guiding.add(r.groupId); else this.guiding.delete(r.groupId); }
    const list = [...this.guiding].map((x) => `#${x}`).join(', ');
    this.status.textContent = list ? `${text}; guiding ${list}` : text;
    this.refresh();
  }

  refresh() {
    const g = this.selected();
    const can = this.joined && g >= 0 && !this.recording;
    this.guideButton.disabled = !can || this.guiding.has(g);
    this.releaseButton.disabled = !can || !this.guiding.has(g);
    // One place for both (the row is too narrow for the filter, the list and two buttons).
    this.guideButton.classList.toggle('hidden', this.guiding.has(g));
    this.releaseButton.classList.toggle('hidden', !this.guiding.has(g));
    this.guideButton.title = this.recording ? kRecordingNoGuide
      : this.joined ? 'the group follows your avatar' : 'join first: the group follows your avatar';
  }
}
