// Unit tests of web/editor/src/doc.js: JSON pointers ↔ elements for every collection the plan
// shows (vertices, fields, a whole collection, the document), anchors, ids, removal with the
// references to a removed point, renaming, and the undo/redo history.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  History, allVertices, anchorOf, elementForPointer, elementPointer, isClosed, mergePlan, removeElement, renamePoint, uniqueId,
  verticesOf,
} from '../src/doc.js';

const scenario = () => ({
  format: 'throng/1',
  walkable: [[[0, 0], [10, 0], [10, 6], [0, 6]]],
  obstacles: [[[4, 0], [5, 0], [5, 2], [4, 2]]],
  walls: [{ id: 'wall1', line: [[6, 0], [6, 2], [7, 2]], thickness: 0.2 }],
  measurements: [{ id: 'line1', line: [[8, 0], [8, 6]] }, { id: 'area1', polygon: [[1, 1], [2, 1], [2, 2]] }],
  points: [{ id: 'gap', kind: 'interest', position: [5, 4], radius: 0.5 },
           { id: 'exit', kind: 'exit', polygon: [[9, 2], [10, 2], [10, 4], [9, 4]] }],
  populations: [{ id: 'crowd', groups: 5, spawn: { polygon: [[0, 0], [2, 0], [2, 2], [0, 2]] }, goals: ['gap', 'exit'], exits: ['exit'] }],
});

test('pointers name elements, their vertices and their fields', () => {
  const doc = scenario();
  assert.deepEqual(elementForPointer(doc, '/walkable/0/2'), { layer: 'walkable', index: 0, vertex: 2 });
  assert.deepEqual(elementForPointer(doc, '/walkable/0/2/1'), { layer: 'walkable', index: 0, vertex: 2 });
  assert.deepEqual(elementForPointer(doc, '/obstacles/0'), { layer: 'obstacles', index: 0 });
  assert.deepEqual(elementForPointer(doc, '/walls/0/line/1'), { layer: 'walls', index: 0, vertex: 1 });
  assert.deepEqual(elementForPointer(doc, '/walls/0/thickness'), { layer: 'walls', index: 0, field: 'thickness' });
  assert.deepEqual(elementForPointer(doc, '/measurements/1/polygon/0'), { layer: 'measurements', index: 1, vertex: 0 });
  assert.deepEqual(elementForPointer(doc, '/points/1/polygon/3'), { layer: 'points', index: 1, vertex: 3 });
  assert.deepEqual(elementForPointer(doc, '/points/0/radius'), { layer: 'points', index: 0, field: 'radius' });
  assert.deepEqual(elementForPointer(doc, '/populations/0/spawn/polygon/1'), { layer: 'populations', index: 0, vertex: 1 });
  assert.deepEqual(elementForPointer(doc, '/populations/0/goals/1'), { layer: 'populations', index: 0, field: 'goals', item: 1 });
  assert.deepEqual(elementForPointer(doc, '/walkable'), { layer: 'walkable', index: null });
  assert.deepEqual(elementForPointer(doc, '/points/7'), { layer: 'points', index: null });  // no such point
  assert.equal(elementForPointer(doc, ''), null);
  assert.equal(elementForPointer(doc, '/steering/timeHorizon'), null);
});

test('element pointers round-trip through elementForPointer', () => {
  const doc = scenario();
  const sels = [{ layer: 'walkable', index: 0, vertex: 1 }, { layer: 'walls', index: 0, vertex: 2 },
                { layer: 'measurements', index: 0, vertex: 1 }, { layer: 'measurements', index: 1, vertex: 2 },
                { layer: 'points', index: 1, vertex: 0 }, { layer: 'populations', index: 0, vertex: 3 }, { layer: 'obstacles', index: 0 }];
  for (const sel of sels) assert.deepEqual(elementForPointer(doc, elementPointer(doc, sel)), sel, elementPointer(doc, sel));
  assert.equal(elementPointer(doc, { layer: 'points', index: 0, vertex: 0 }), '/points/0/position');
});

test('vertices, closedness and anchors', () => {
  const doc = scenario();
  assert.equal(verticesOf(doc, { layer: 'walls', index: 0 }), doc.walls[0].line);  // the document's own array
  assert.deepEqual(verticesOf(doc, { layer: 'points', index: 0 }), [[5, 4]]);
  assert.ok(isClosed(doc, { layer: 'obstacles', index: 0 }));
  assert.ok(!isClosed(doc, { layer: 'walls', index: 0 }));
  assert.ok(isClosed(doc, { layer: 'measurements', index: 1 }));
  assert.deepEqual(anchorOf(doc, { layer: 'walkable', index: 0 }), [5, 3]);
  assert.deepEqual(anchorOf(doc, { layer: 'walkable', index: 0, vertex: 2 }), [10, 6]);
  assert.deepEqual(anchorOf(doc, { layer: 'points', index: 0, field: 'radius' }), [5, 4]);
  assert.deepEqual(anchorOf(doc, { layer: 'walls', index: 0 }), [6, 1]);
  assert.equal(anchorOf(doc, { layer: 'walkable', index: null }), null);
  assert.equal(allVertices(doc).length, 4 + 4 + 3 + 2 + 3 + 1 + 4 + 4);
  assert.equal(allVertices(doc, { layer: 'walkable', index: 0 }).length, 25 - 4);
});

test('ids, removal and renaming keep references consistent', () => {
  const doc = scenario();
  assert.equal(uniqueId(doc, 'walls', 'wall'), 'wall2');
  assert.equal(uniqueId(doc, 'points', 'exit'), 'exit1');
  renamePoint(doc, 1, 'door');
  assert.deepEqual(doc.populations[0].goals, ['gap', 'door']);
  assert.deepEqual(doc.populations[0].exits, ['door']);
  removeElement(doc, { layer: 'points', index: 1 });
  assert.deepEqual(doc.populations[0].goals, ['gap']);
  assert.equal(doc.populations[0].exits, undefined);
  removeElement(doc, { layer: 'walls', index: 0 });
  assert.equal(doc.walls, undefined);  // an emptied optional key goes
  removeElement(doc, { layer: 'walkable', index: 0 });
  assert.deepEqual(doc.walkable, []);  // a required one stays
});

test('history: undo, redo, and a new edit dropping the redo list', () => {
  const doc = { a: 1 };
  const h = new History(doc);
  assert.equal(h.push(doc), false);  // nothing changed
  doc.a = 2;
  assert.equal(h.push(doc), true);
  doc.a = 3;
  h.push(doc);
  assert.deepEqual(h.undo(), { a: 2 });
  assert.deepEqual(h.undo(), { a: 1 });
  assert.equal(h.undo(), null);
  assert.deepEqual(h.redo(), { a: 2 });
  h.push({ a: 5 });
  assert.equal(h.redo(), null);
  assert.deepEqual(h.undo(), { a: 2 });
});

test('an imported plan joins the document, walls with fresh ids', () => {
  const doc = scenario();
  const added = mergePlan(doc, { walkable: [[[20, 0], [30, 0], [30, 5]]], obstacles: [], walls: [{ line: [[0, 0], [1, 0]], thickness: 0.2 },
    { id: 'wall1', line: [[2, 0], [3, 0]], thickness: 0.1 }] });
  assert.deepEqual(added, { walkable: 1, obstacles: 0, walls: 2 });
  assert.equal(doc.walkable.length, 2);
  assert.deepEqual(doc.walls.map((w) => w.id), ['wall1', 'wall2', 'wall3']);  // the clashing "wall1" renamed
  const empty = { format: 'throng/1', walkable: [], points: [], populations: [] };
  mergePlan(empty, { walkable: [[[0, 0], [1, 0], [1, 1]]], obstacles: [[[0.2, 0.2], [0.4, 0.2], [0.4, 0.4]]], walls: [] });
  assert.equal(empty.walkable.length, 1);
  assert.equal(empty.obstacles.length, 1);
  assert.equal(empty.walls, undefined);
});
