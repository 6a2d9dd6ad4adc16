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
  assert.match(stateWords('walking to its goal'), /standing in a queue on the way/, 'not "walking" beside "standing"');
  assert.equal(stateWords('waiting for its group'), 'waiting for its group');
  assert.equal(stateWords(undefined), '');
});

test('the position says the floor height on a multi-level world only', () => {
  assert.equal(positionWords(1, 2), '(1.00, 2.00) m');
  assert.equal(positionWords(1, 2, 0), '(1.00, 2.00) m');
  assert.equal(positionWords(1, 2, 3.6), '(1.00, 2.00) m, 3.6 m up');
});

test('the agent panel moves aside when it would cover the agent clicked, and back once clear', async () => {
  const { panelSide } = await import('../src/ui/agent_panel.js');
  const right = { left: 1030, top: 205, right: 1270, bottom: 420 }, left = { left: 10, top: 160, right: 250, bottom: 375 };
  assert.equal(panelSide({ x: 600, y: 300 }, right, left), 'right', 'in the middle: stays');
  assert.equal(panelSide({ x: 1100, y: 300 }, right, left), 'left', 'under it: moves left');
  assert.equal(panelSide({ x: 1015, y: 300 }, right, left), 'left', 'within the margin: moves too');
  assert.equal(panelSide({ x: 1000, y: 300 }, right, left, 'left'), 'left', 'near its old place: stays left (no jumping)');
  assert.equal(panelSide({ x: 900, y: 300 }, right, left, 'left'), 'right', 'clear again: back');
  assert.equal(panelSide(null, right, left, 'left'), 'left', 'off screen: stays');
  const wide = { left: 10, top: 205, right: 1270, bottom: 420 };  // a view so narrow both places overlap
  assert.equal(panelSide({ x: 600, y: 300 }, wide, wide), 'right', 'covered either way: stays where it is');
});
