// The recordings row's text (src/ui/recordings.js): sizes in decimal units, one line per recording
// with its scenario, duration, agents and size, or why the server could not read it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { describeRecording, formatBytes } from '../src/ui/recordings.js';

test('formatBytes uses decimal units', () => {
  assert.equal(formatBytes(512), '512 B');
  assert.equal(formatBytes(229376), '229 kB');
  assert.equal(formatBytes(815104), '815 kB');
  assert.equal(formatBytes(2.5e6), '2.5 MB');
  assert.equal(formatBytes(3.21e9), '3.2 GB');
  assert.equal(formatBytes(undefined), '0 B');
});

test('describeRecording names the scenario, duration, agents and size', () => {
  assert.equal(describeRecording({ name: 'museum.sqlite', scenario: 'museum', duration: 20, agents: 14, size: 229376 }),
    'museum.sqlite — museum, 0:20, 14 agents, 229 kB');
  assert.equal(describeRecording({ name: 'a.sqlite', scenario: 'solo', duration: 125.4, agents: 1, size: 900 }),
    'a.sqlite — solo, 2:05, 1 agent, 900 B');
  assert.equal(describeRecording({ name: 'b.sqlite', scenario: '', duration: 0, agents: 0, size: 10, error: 'not SQLite' }),
    'b.sqlite — unreadable: not SQLite');
});
