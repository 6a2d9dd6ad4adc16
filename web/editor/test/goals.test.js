// Unit tests of web/editor/src/goals.js: a population's goals with waypoint choices — a goal turned
// into a choice and back, options added and removed with their shares, the split (shares belong to
// the shares split only), shares typed as text (one per option, ≥ 0, not all 0, the message naming
// what is wrong), labels, and that what the editor writes is what the scenario JSON Schema allows.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import {
  addOption, goalIds, goalLabel, isChoice, parseShares, removeOption, renameInGoal, setShares, setSplit,
} from '../src/goals.js';
import { removeElement, renamePoint } from '../src/doc.js';

const schema = JSON.parse(fs.readFileSync(new URL('../../../scenarios/schema/scenario.schema.json', import.meta.url), 'utf8'));

test('a goal becomes a choice, gains and loses options, and turns back into a goal', () => {
  let g = addOption('booth-a', 'booth-b');
  assert.deepEqual(g, { choose: ['booth-a', 'booth-b'] });
  assert.ok(isChoice(g) && !isChoice('booth-a'));
  assert.equal(addOption('booth-a', 'booth-a'), 'booth-a', 'a point is no choice with itself');
  g = addOption(g, 'booth-c');
  assert.deepEqual(goalIds(g), ['booth-a', 'booth-b', 'booth-c']);
  assert.equal(addOption(g, 'booth-b'), g, 'an option already there changes nothing');
  g = setShares(g, [2, 1, 1]);
  assert.deepEqual(addOption(g, 'booth-d').shares, [2, 1, 1, 1.333], 'a new option gets the mean share');
  const two = removeOption(g, 'booth-a');
  assert.deepEqual(two, { choose: ['booth-b', 'booth-c'], shares: [1, 1] }, 'its share goes with it');
  assert.equal(removeOption(two, 'booth-b'), 'booth-c', 'one option left: a plain goal');
  assert.equal(removeOption({ choose: ['a'] }, 'a'), null);
  assert.equal(removeOption('exit', 'exit'), null);
  assert.equal(removeOption('exit', 'other'), 'exit');
  assert.deepEqual(goalIds('exit'), ['exit']);
});

test('the split: shares belong to the shares split, which is the default', () => {
  const g = { choose: ['a', 'b'], shares: [3, 1] };
  const least = setSplit(g, 'leastTargeted');
  assert.deepEqual(least, { choose: ['a', 'b'], split: 'leastTargeted' });
  assert.deepEqual(setSplit(least, 'shares'), { choose: ['a', 'b'] }, 'the default split is not written');
  assert.deepEqual(setShares(g, undefined), { choose: ['a', 'b'] }, 'no shares: equal');
  assert.equal(goalLabel(g), 'one of a, b (shares 3 : 1)');
  assert.equal(goalLabel(least), 'one of a, b (least targeted)');
  assert.equal(goalLabel('exit'), 'exit');
});

test('shares typed as text: one per option, at least 0, not all 0', () => {
  const g = { choose: ['a', 'b', 'c'] };
  assert.deepEqual(parseShares(g, '2, 1, 1'), { value: [2, 1, 1] });
  assert.deepEqual(parseShares(g, '2:1:0.5'), { value: [2, 1, 0.5] });
  assert.deepEqual(parseShares(g, '  '), { value: undefined });
  assert.match(parseShares(g, '2, 1').error, /2 shares for 3 options/);
  assert.match(parseShares(g, '2, x, 1').error, /"x" is not a number/);
  assert.match(parseShares(g, '2, -1, 1').error, /-1 is below the minimum 0/);
  assert.match(parseShares(g, '0 0 0').error, /all 0/);
});

test('removing or renaming a point reaches into waypoint choices', () => {
  const doc = {
    points: [{ id: 'a', kind: 'interest', position: [1, 1] }, { id: 'b', kind: 'interest', position: [2, 1] },
             { id: 'c', kind: 'interest', position: [3, 1] }, { id: 'exit', kind: 'exit', position: [9, 1] }],
    populations: [{ id: 'crowd', goals: [{ choose: ['a', 'b', 'c'], shares: [1, 2, 3] }, { choose: ['a', 'b'] }, 'exit'] }],
  };
  renamePoint(doc, 1, 'booth');
  assert.deepEqual(doc.populations[0].goals[0].choose, ['a', 'booth', 'c']);
  assert.deepEqual(renameInGoal('a', 'a', 'z'), 'z');
  removeElement(doc, { layer: 'points', index: 0 });
  assert.deepEqual(doc.populations[0].goals, [{ choose: ['booth', 'c'], shares: [2, 3] }, 'booth', 'exit']);
});

test('what the editor writes is a goals entry the schema allows', () => {
  const def = schema.$defs.goalChoice;
  assert.deepEqual(def.required, ['choose']);
  const allowed = Object.keys(def.properties);
  assert.deepEqual(def.properties.split.enum, ['shares', 'leastTargeted']);
  let g = addOption('a', 'b');
  g = setShares(addOption(g, 'c'), parseShares(addOption(g, 'c'), '1 1 2').value);
  for (const written of [g, setSplit(g, 'leastTargeted'), setSplit(g, 'shares')]) {
    for (const k of Object.keys(written)) assert.ok(allowed.includes(k), `key ${k}`);
    assert.ok(written.choose.length >= def.properties.choose.minItems);
    assert.equal(new Set(written.choose).size, written.choose.length, 'each option once');
    if (written.split) assert.ok(def.properties.split.enum.includes(written.split));
    if (written.shares) assert.equal(written.shares.length, written.choose.length);
  }
});
