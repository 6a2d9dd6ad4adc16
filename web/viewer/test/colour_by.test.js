// Colour modes (src/crowd/colour_by.js): local density from the grid equals a brute-force count;
// the ramp runs from its first to its last stop and clamps; states from clips, far-tier speed and
// group waiting; every mode has a legend (the ramp's labels up to its maximum).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { localDensity, rampColour, kRamp, stateOf, legendOf, kColourModes, kSpeedMax, defaultColourMode, GroupColours, kGroupPalette }
  from '../src/crowd/colour_by.js';

test('local density on the grid equals a brute-force count', () => {
  let s = 12345;
  const r = () => ((s = (Math.imul(s, 1103515245) + 12345) >>> 0) / 2 ** 32);
  const n = 400, x = new Float32Array(n), y = new Float32Array(n);
  for (let i = 0; i < n; ++i) { x[i] = r() * 12 - 6; y[i] = r() * 8 - 20; }
  const got = localDensity(x, y, n, 1.0);
  for (let i = 0; i < n; ++i) {
    let c = 0;
    for (let j = 0; j < n; ++j) if ((x[j] - x[i]) ** 2 + (y[j] - y[i]) ** 2 <= 1) c++;
    assert.ok(Math.abs(got[i] - c / Math.PI) < 1e-5, `agent ${i}: ${got[i]} vs ${c / Math.PI}`);
  }
  const lone = localDensity(Float32Array.of(0, 5), Float32Array.of(0, 0), 2);
  assert.ok(Math.abs(lone[0] - 1 / Math.PI) < 1e-6, 'alone: itself only');
});

test('the ramp goes from its first stop to its last and clamps', () => {
  assert.equal(rampColour(0), kRamp[0]);
  assert.equal(rampColour(1), kRamp[kRamp.length - 1]);
  assert.equal(rampColour(-3), kRamp[0]);
  assert.equal(rampColour(7), kRamp[kRamp.length - 1]);
  assert.equal(rampColour(0.25), kRamp[1]);
  assert.notEqual(rampColour(0.1), rampColour(0.15), 'it varies between stops');
});

test('states from clips, far-tier speed and group waiting', () => {
  assert.equal(stateOf('walk', 1.2, false), 'walking');
  assert.equal(stateOf('idle', 0, false), 'waiting');
  assert.equal(stateOf('look', 0, false), 'acting');
  assert.equal(stateOf('', 1.0, false), 'walking');
  assert.equal(stateOf('', 0.1, false), 'waiting');
  assert.equal(stateOf('walk', 1.2, true), 'coordinating');
});

test('every mode has a legend', () => {
  for (const m of kColourModes) {
    const l = legendOf(m, { populations: ['family', 'couples'], groups: [{ id: 0, population: 'family' }] });
    assert.ok(l.length >= 1 && l.every((e) => typeof e.label === 'string' && e.label), `${m}: ${JSON.stringify(l)}`);
  }
  assert.match(legendOf('speed').at(-1).label, new RegExp(`${kSpeedMax.toFixed(1)} m/s`));
  assert.deepEqual(legendOf('population', { populations: ['a', 'b'] }).map((e) => e.label), ['a', 'b', 'no population known']);
  const many = legendOf('population', { populations: Array.from({ length: 266 }, (_, k) => `p${k}`) }).map((e) => e.label);
  assert.equal(many.length, 10, 'eight listed, then how many in all');
  assert.match(many[8], /266 populations/);
});

test('a world opens coloured by group, unless every group is one person', () => {
  const g = (...sizes) => sizes.map((n, id) => ({ id, members: Array.from({ length: n }, (_, k) => k) }));
  assert.equal(defaultColourMode(g(1, 3, 2), 1), 'group');
  assert.equal(defaultColourMode(g(1, 1, 1), 1), 'speed', 'loners, one population: speed shows the jam');
  assert.equal(defaultColourMode(g(1, 1, 1), 3), 'population');
  assert.equal(defaultColourMode([], 2), 'group', 'no groups known yet');
  assert.equal(defaultColourMode(undefined, 1), 'group');
});

test('the group legend lists groups with someone in them and says how colours are shared', () => {
  const groups = Array.from({ length: 23 }, (_, id) => ({ id, population: 'p', members: id === 2 ? [] : [id] }));
  const rows = legendOf('group', { groups });
  assert.deepEqual(rows.slice(0, 5).map((r) => r.label.split(' ')[1]), ['0', '1', '3', '4', '5'], 'group 2 has left');
  assert.match(rows[5].label, new RegExp(`22 groups in ${kGroupPalette.length} colours: groups that came side by side differ`));
  const shifted = legendOf('group', { groups, groupColour: (g) => (g + 1) % kGroupPalette.length });
  assert.equal(shifted[0].colour, kGroupPalette[1], 'the legend shows the colour the group wears');
  assert.equal(legendOf('group', { groups: groups.slice(0, 3) }).length, 2, 'no "more" row when all are listed');
});

/** n groups of three, group g's members at its centre (cx(g), cy(g)) ± 0.5 m; ids 3g, 3g+1, 3g+2. */
function crowdOf(n, cx, cy) {
  const ids = [], x = [], y = [], groupOf = new Map();
  for (let g = 0; g < n; ++g) {
    for (let k = 0; k < 3; ++k) {
      ids.push(3 * g + k); x.push(cx(g) + (k - 1) * 0.5); y.push(cy(g)); groupOf.set(3 * g + k, g);
    }
  }
  return { ids, x, y, n: ids.length, groupOf };
}
/** Pairs of groups with centres nearer than r wearing the same colour. */
function clashes(c, colours, r) {
  const centre = (g) => [c.x[3 * g + 1], c.y[3 * g + 1]];
  let count = 0;
  const groups = c.n / 3;
  for (let a = 0; a < groups; ++a) {
    for (let b = a + 1; b < groups; ++b) {
      const [ax, ay] = centre(a), [bx, by] = centre(b);
      if (Math.hypot(ax - bx, ay - by) < r && colours.index(a) === colours.index(b)) count++;
    }
  }
  return count;
}

test('groups side by side wear different colours, however many groups there are', () => {
  // 400 groups scattered over 80 × 80 m (a fixed pseudo-random layout): with colours by id modulo
  // the palette, many pairs side by side share one; handed out by GroupColours, none within 6 m does.
  let seed = 12345;
  const rand = () => { seed = (seed * 1103515245 + 12345) % 2147483648; return seed / 2147483648; };
  const px = Array.from({ length: 400 }, () => 80 * rand()), py = Array.from({ length: 400 }, () => 80 * rand());
  const c = crowdOf(400, (g) => px[g], (g) => py[g]);
  const byId = { index: (g) => g % kGroupPalette.length };
  assert.ok(clashes(c, byId, 6) > 20, `by id, ${clashes(c, byId, 6)} pairs within 6 m share colours`);
  const colours = new GroupColours();
  assert.equal(colours.update(c.ids, c.x, c.y, c.n, c.groupOf), 400, 'every group got a colour');
  assert.equal(clashes(c, colours, 6), 0, 'no two groups within 6 m share a colour');
  // The nearest group wearing one's colour: 7.7 m away on average (0.5 m at the least) by id, about
  // 11 m (6.6 m at the least) handed out.
  const nearestTwin = (colour) => {
    const d = px.map((_, a) => Math.min(...px.map((__, b) => (a !== b && colour.index(a) === colour.index(b)
      ? Math.hypot(px[a] - px[b], py[a] - py[b]) : Infinity))));
    return { mean: d.reduce((s, v) => s + v, 0) / d.length, min: Math.min(...d) };
  };
  const mine = nearestTwin(colours), theirs = nearestTwin(byId);
  assert.ok(mine.min >= 6 && mine.mean > 1.3 * theirs.mean, `nearest twin ${JSON.stringify(mine)} against ${JSON.stringify(theirs)} by id`);
  // The same positions again: nobody changes colour (no flicker).
  assert.equal(colours.update(c.ids, c.x, c.y, c.n, c.groupOf), 0);
});

test('a group keeps its colour for good; one arriving beside it takes another', () => {
  const colours = new GroupColours(12, 10);
  const groupOf = new Map([[0, 0], [1, 12]]);  // groups 0 and 12: the same default colour (12 colours)
  colours.update([0], [0], [0], 1, groupOf);
  const first = colours.index(0);
  assert.equal(colours.update([0, 1], [0, 3], [0, 0], 2, groupOf), 1, 'group 12 arrives 3 m away');
  assert.notEqual(colours.index(12), first, 'it does not take the colour of the group beside it');
  assert.equal(colours.index(0), first);
  const second = colours.index(12);
  assert.equal(colours.update([0, 1], [0, 50], [0, 0], 2, groupOf), 0, 'moving apart changes nothing');
  assert.equal(colours.update([0, 1], [0, 0.5], [0, 0], 2, groupOf), 0, 'nor coming closer');
  assert.deepEqual([colours.index(0), colours.index(12)], [first, second]);
});
