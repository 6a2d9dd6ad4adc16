// Colour modes (src/crowd/colour_by.js): local density from the grid equals a brute-force count;
// the ramp runs from its first to its last stop and clamps; states from clips, far-tier speed and
// group waiting; every mode has a legend (the ramp's labels up to its maximum).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { localDensity, rampColour, kRamp, stateOf, legendOf, kColourModes, kSpeedMax, defaultColourMode } from '../src/crowd/colour_by.js';

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
  assert.match(rows[5].label, /22 groups in 10 colours: groups 10 apart share one/);
  assert.equal(legendOf('group', { groups: groups.slice(0, 3) }).length, 2, 'no "more" row when all are listed');
});
