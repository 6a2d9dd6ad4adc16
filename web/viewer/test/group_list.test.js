// The group list's search (src/ui/group_list.js filterGroups): population names, ids, sizes.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { filterGroups } from '../src/ui/group_list.js';

const groups = [
  { id: 0, population: 'visitors', members: [1, 2, 3] },
  { id: 1, population: 'visitors', members: [4] },
  { id: 2, population: 'Guides', members: [5, 6] },
  { id: 12, population: 'staff', members: [7, 8, 9, 10] },
];
const ids = (q) => filterGroups(groups, q).map((g) => g.id);

test('an empty query keeps every group', () => {
  assert.deepEqual(ids(''), [0, 1, 2, 12]);
  assert.deepEqual(ids('   '), [0, 1, 2, 12]);
});

test('words match population names (any case, any part), ids and sizes; all must match', () => {
  assert.deepEqual(ids('visit'), [0, 1]);
  assert.deepEqual(ids('GUIDE'), [2]);
  assert.deepEqual(ids('12'), [12]);
  assert.deepEqual(ids('#2'), [2]);
  assert.deepEqual(ids('>=3'), [0, 12]);
  assert.deepEqual(ids('<2'), [1]);
  assert.deepEqual(ids('=2'), [2]);
  assert.deepEqual(ids('visitors >1'), [0]);
  assert.deepEqual(ids('nobody'), []);
});
