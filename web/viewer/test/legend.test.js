// The legend's fixed marks (src/ui/legend.js): exits that are also entrances say so (the mall: a
// newcomer could not tell whether people come in or leave there); a multi-level world explains the
// plan view's white rim.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { exitsAreEntrances, fixedEntries } from '../src/ui/legend.js';

const rect = (x0, y0, x1, y1) => [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];

test('exits are entrances when a population appears inside one', () => {
  const exit = { id: 'door', kind: 'exit', polygon: rect(0, 0, 4, 2) };
  const inside = { populations: [{ spawn: { polygon: rect(1, 0.5, 3, 1.5) } }], points: [exit] };
  const apart = { populations: [{ spawn: { polygon: rect(10, 10, 12, 12) } }], points: [exit] };
  assert.equal(exitsAreEntrances(inside), true);
  assert.equal(exitsAreEntrances(apart), false);
  assert.equal(exitsAreEntrances({ points: [{ kind: 'exit', position: [11, 11], radius: 2 }], populations: apart.populations }), true);
  assert.equal(exitsAreEntrances({}), false);
});

test('the exit row, the upper-floor row and the paintings row follow the world', () => {
  const labels = (o) => fixedEntries({ selected: 1, pickedGroup: 2, self: 3, other: 4, ...o }).map((e) => e.label);
  assert.ok(labels({}).includes('exit'));
  assert.ok(labels({ entrances: true }).some((l) => l.startsWith('exit (and entrance')));
  assert.ok(!labels({}).some((l) => l.includes('upper floor')));
  assert.ok(labels({ multiLevel: true }).some((l) => l.includes('white rim = on an upper floor')));
  assert.ok(!labels({}).some((l) => l.startsWith('painting')));
  assert.ok(labels({ exhibits: true }).some((l) => l.startsWith('painting: what visitors')));
});
