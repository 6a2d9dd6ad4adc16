// The legend (bottom left): what every colour, ring, disc and area on screen means — the colour
// mode's own entries (crowd/colour_by.js legendOf: groups, populations, the speed or density ramp,
// states) under a "Colour by" menu (key B cycles the modes), then the marks that mean the same in
// every mode: the selected agent, the picked group, you, other participants, the world's points,
// exits, obstacles, walls and railings, stair risers and floor (and trails, the density and the speed map when they are on). Its header folds it away (folded at start
// on a viewport under 560 px high). Writes the #legend panel.
import { kColourModes, kModeNames, legendOf } from '../crowd/colour_by.js';

const hex = (c) => `#${c.toString(16).padStart(6, '0')}`;

/** Whether people also arrive in an exit of `scenario` (a population's spawn polygon overlaps an
 * exit's box — the mall's entrances): the legend then calls exits entrances too. */
export function exitsAreEntrances(scenario) {
  const box = (poly) => poly.reduce((b, [x, y]) => [Math.min(b[0], x), Math.min(b[1], y), Math.max(b[2], x), Math.max(b[3], y)],
    [Infinity, Infinity, -Infinity, -Infinity]);
  const overlap = (a, b) => a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
  const exits = ((scenario || {}).points || []).filter((p) => p.kind === 'exit').map((p) => (Array.isArray(p.polygon)
    ? box(p.polygon) : Array.isArray(p.position) ? [p.position[0] - (p.radius || 0), p.position[1] - (p.radius || 0),
      p.position[0] + (p.radius || 0), p.position[1] + (p.radius || 0)] : null)).filter(Boolean);
  const spawns = ((scenario || {}).populations || []).map((p) => p.spawn && Array.isArray(p.spawn.polygon) ? box(p.spawn.polygon) : null)
    .filter(Boolean);
  return exits.some((e) => spawns.some((s) => overlap(e, s)));
}

/** Entries shown in every mode: [{colour, shape, label}]; shape: dot, ring, pin, disc, area, line. */
export function fixedEntries({ selected, pickedGroup, self, other, trails, heatmap, speedmap, multiLevel, entrances, exhibits }) {
  return [
    { colour: selected, shape: 'ring', label: 'selected agent (ringed)' },
    { colour: pickedGroup, shape: 'dot', label: 'group picked in the list' },
    { colour: self, shape: 'pin', label: 'you (ring and pin), once joined' },
    { colour: other, shape: 'dot', label: 'participants: own look, else this' },
    { colour: 0x3070d0, shape: 'ring', label: 'interest point' },
    { colour: 0xe08020, shape: 'disc', label: 'action point (arrow: facing)' },
    { colour: 0x30b050, shape: 'area', label: entrances ? 'exit (and entrance: people arrive there too)' : 'exit' },
    { colour: 0xb9a98f, shape: 'area', label: 'obstacle, inner wall (solid, 2.4 m high)' },
    ...(exhibits ? [{ colour: 0x4a3520, shape: 'area', label: 'painting: what visitors at an action point look at (a strip along the wall from above)' }] : []),
    { colour: 0x5a5145, shape: 'line', label: 'outer wall, railing (low, 1.2 m, see-through)' },
    { colour: 0xa8a296, shape: 'area', label: 'stair riser' },
    { colour: 0xd8d4cc, shape: 'area', label: 'walkable floor' },
    ...(multiLevel ? [{ colour: 0xffffff, shape: 'ring', label: 'plan view: white rim = on an upper floor' }] : []),
    ...(trails ? [{ colour: 0x555555, shape: 'line', label: 'trail: where each walked lately' }] : []),
    ...(heatmap ? legendOf('density').map((e) => ({ colour: e.colour, shape: 'area',
      label: `density map${heatmap === 'voronoi' ? ' (Voronoi)' : ''}: ${e.label}` })) : []),
    ...(speedmap ? legendOf('speed').map((e) => ({ colour: e.colour, shape: 'area', label: `speed map${speedmap === 'voronoi' ? ' (Voronoi)' : ''}: ${e.label}` })) : []),
  ];
}

export class Legend {
  /** `onMode(mode)`: the menu changed the colour mode. */
  constructor(root, marks, onMode) {
    this.root = root;
    this.marks = marks;
    this.trails = false;
    this.heatmap = false;
    this.speedmap = false;
    this.multiLevel = false;  // a multi-level world: the plan view's upper-floor rim is explained
    this.entrances = false;   // people also arrive in the exits (exitsAreEntrances)
    this.exhibits = false;    // the world hangs paintings where visitors look (world_view.js, exhibits)
    root.innerHTML = '<div class="legend-head"><button class="fold" title="fold the legend">▾</button> Colour by '
      + '<select id="colour-by" title="what the agents\' colours say (B)"></select></div><div class="legend-body"></div>';
    this.select = root.querySelector('#colour-by');
    for (const m of kColourModes) this.select.add(new Option(kModeNames[m], m));
    this.select.onchange = () => onMode(this.select.value);
    this.body = root.querySelector('.legend-body');
    this.fold = root.querySelector('.fold');
    this.fold.onclick = () => this.setFolded(!this.folded);
    this.setFolded(innerHeight < 560);
    this.key = '';
  }

  setFolded(f) {
    this.folded = f;
    this.body.classList.toggle('hidden', f);
    this.fold.textContent = f ? '▸' : '▾';
  }

  /** Redraws when the mode, the populations or the groups changed. */
  update(mode, context) {
    const rows = [...legendOf(mode, context).map((e) => ({ ...e, shape: 'dot' })), { separator: true },
      ...fixedEntries({ ...this.marks, trails: this.trails, heatmap: this.heatmap, speedmap: this.speedmap,
        multiLevel: this.multiLevel, entrances: this.entrances, exhibits: this.exhibits })];
    const key = JSON.stringify([mode, rows]);  // the groups listed and their colours included
    if (key === this.key) return;
    this.key = key;
    this.select.value = mode;
    this.body.innerHTML = '';
    for (const r of rows) {
      const row = document.createElement('div');
      if (r.separator) { row.className = 'legend-sep'; this.body.appendChild(row); continue; }
      row.className = 'legend-row';
      const sw = document.createElement('span');
      sw.className = `swatch swatch-${r.colour === null ? 'none' : r.shape}`;
      if (r.colour !== null) sw.style.setProperty('--c', hex(r.colour));
      const label = document.createElement('span');
      label.textContent = r.label;
      row.append(sw, label);
      this.body.appendChild(row);
    }
  }

  /** Labels of the rows shown (for tests). */
  labels() { return [...this.body.querySelectorAll('.legend-row span:last-child')].map((s) => s.textContent); }
}
