// The agent panel's words (src/ui/agent_panel.js): what an agent does and its state said so that
// someone new to throng follows them (a stand-in newcomer's check found "idle", "goal done" and
// "playing a Common Ground script" opaque), and its floor on a multi-level world.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { behaviourWords, stateWords, positionWords } from '../src/ui/agent_panel.js';

test('walk and idle read as walking and standing; other clips keep their names', () => {
  assert.equal(behaviourWords('walk'), 'walking');
  assert.equal(behaviourWords('idle'), 'standing');
  assert.equal(behaviourWords('point_toward'), 'point toward');
  assert.equal(behaviourWords(''), '—');
});

test("the server's states in plain words; unknown ones as the server says them", () => {
  assert.match(stateWords('done'), /every goal visited/);
  assert.match(stateWords('playing a Common Ground script'), /with its group/);
  assert.equal(stateWords('walking to its goal'), 'walking to its goal');
  assert.equal(stateWords(undefined), '');
});

test('the position says the floor height on a multi-level world only', () => {
  assert.equal(positionWords(1, 2), '(1.00, 2.00) m');
  assert.equal(positionWords(1, 2, 0), '(1.00, 2.00) m');
  assert.equal(positionWords(1, 2, 3.6), '(1.00, 2.00) m, 3.6 m up');
});
