// Agent panel: what the clicked agent is — id, group, behaviour (its clip), position, detail tier;
// goal and action script fields for when the server sends them; Guide / Release buttons for its
// group once the viewer has joined as a participant.
// How much of the body the server sends for it (its detail tier), said plainly.
const kTier = ['full (every joint)', 'walk or pose only', 'position only (far away)'];

/** What an agent is doing, in a visitor's words: the walk and idle clips are walking and standing;
 * other clips (an action, a gesture) keep their names. */
export function behaviourWords(clipName) {
  if (!clipName) return '—';
  if (clipName === 'walk') return 'walking';
  if (clipName === 'idle') return 'standing';
  return clipName.replaceAll('_', ' ');
}

// The server's words for an agent's state (GET /api/agent/<id>: sim::AgentInfo::state), said so
// that someone new to throng follows them; a state not listed is shown as the server says it.
const kStateWords = {
  'walking to its goal': 'heading there (walking, or standing in a queue on the way)',
  'done': 'done: every goal visited, it stays where it is',
  'at an action point': 'at a place of interest, doing what it came for',
  'playing a Common Ground script': 'doing something with its group (a plan they agreed on: Common Ground)',
  'left': 'gone: it left the world',
};
export function stateWords(state) { return kStateWords[state] || state || ''; }

/** The position row: metres, and the floor height on a multi-level world (z ≠ 0). */
export function positionWords(x, y, z = 0) {
  const xy = `(${x.toFixed(2)}, ${y.toFixed(2)}) m`;
  return Math.abs(z) > 0.05 ? `${xy}, ${z.toFixed(1)} m up` : xy;
}

/** Which side of the view the agent panel goes: 'right' (its place) unless the clicked agent's
 * screen point (x, y) [px] lies under it there, or within `margin` px of it, and not under it on the
 * left; then 'left'. Back to the right only once the point is twice the margin clear of the
 * right-hand place (a panel does not jump to and fro while the agent walks along its edge). `right`, `left`: the
 * panel's rectangle {left, top, right, bottom} [px] on each side; point null: stays. */
export function panelSide(point, right, left, current = 'right', margin = 24) {
  if (!point) return current;
  const under = (r, m = margin) => point.x >= r.left - m && point.x <= r.right + m && point.y >= r.top - m
    && point.y <= r.bottom + m;
  if (current === 'left') return under(right, 2 * margin) ? 'left' : 'right';
  return under(right) && !under(left) ? 'left' : 'right';
}

/** Why a recording's groups cannot be guided (the Guide buttons' title). */
export const kRecordingNoGuide = 'a recording cannot be guided: its people replay what they did';

export class AgentPanel {
  constructor(root, { onGuide, onRelease, onClose }) {
    this.root = root;
    this.$ = (id) => root.querySelector(`#${id}`);
    this.$('guide-button').onclick = () => this.group !== undefined && onGuide(this.group);
    this.$('release-button').onclick = () => this.group !== undefined && onRelease(this.group);
    this.$('agent-close').onclick = () => { this.hide(); onClose(); };
    this.joined = false;
    this.guiding = new Set();
  }

  show(id, group) {
    this.id = id;
    this.group = group;
    this.root.classList.remove('hidden');
    if (id !== this.shownId) { this.$('agent-goal').textContent = '—'; this.$('agent-script').textContent = '—'; this.shownId = id; }
    this.$('agent-id').textContent = `#${id}`;
    this.$('agent-group').textContent = group === undefined ? '—' : `${group}${this.guiding.has(group) ? ' (you guide it)' : ''}`;
    this.refreshButtons();
  }

  hide() { this.root.classList.add('hidden'); this.id = undefined; }

  /** The agent shown is no longer in the world (it left, or a replay went back before it came). */
  gone() {
    if (this.goneId === this.id) return;
    this.goneId = this.id;
    this.$('agent-clip').textContent = 'gone: not in the world now';
    this.$('agent-goal').textContent = '—';
    this.$('agent-script').textContent = '—';
  }

  /** Moves the panel to the other side of the view when it would cover the agent at screen point
   * `point` ({x, y} px, null when off screen): to the left under the HUD, whose bottom is `hudBottom`
   * [px] (panelSide). Returns the side. */
  keepClear(point, hudBottom, viewWidth) {
    if (this.root.classList.contains('hidden')) return this.side || 'right';
    const r = this.root.getBoundingClientRect();
    const w = r.width, h = r.height;
    if (!this.side || this.side === 'right') this.rightTop = r.top;
    const top = this.rightTop ?? r.top;
    const leftTop = hudBottom + 10;
    const side = panelSide(point, { left: viewWidth - 10 - w, top, right: viewWidth - 10, bottom: top + h },
      { left: 10, top: leftTop, right: 10 + w, bottom: leftTop + h }, this.side || 'right');
    if (side !== (this.side || 'right')) {
      this.root.classList.toggle('left', side === 'left');
      this.root.style.top = side === 'left' ? `${leftTop}px` : '';
    }
    this.side = side;
    return side;
  }

  /** Live fields, every frame while shown. */
  update({ clipName, x, y, z = 0, tier, goal, script }) {
    this.goneId = undefined;
    this.$('agent-clip').textContent = behaviourWords(clipName);
    this.$('agent-pos').textContent = positionWords(x, y, z);
    this.$('agent-tier').textContent = kTier[tier] || '—';
    if (goal !== undefined) this.$('agent-goal').textContent = goal;
    if (script !== undefined) this.$('agent-script').textContent = script;
  }

  setJoined(joined) { this.joined = joined; this.refreshButtons(); }

  /** A recording plays: its groups cannot be guided (the buttons say so). */
  setRecording(on) { this.recording = on; this.refreshButtons(); }

  guideResult(r, text) {
    if (r.ok) { if (r.guiding) this.guiding.add(r.groupId); else this.guiding.delete(r.groupId); }
    this.$('guide-status').textContent = text;
    if (this.id !== undefined) this.show(this.id, this.group);
  }

  refreshButtons() {
    const can = this.joined && this.group !== undefined && !this.recording;
    this.$('guide-button').disabled = !can || this.guiding.has(this.group);
    this.$('release-button').disabled = !can || !this.guiding.has(this.group);
    this.$('guide-button').title = this.recording ? kRecordingNoGuide : 'join first, then the group follows your avatar';
  }
}
