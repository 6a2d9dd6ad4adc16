// The adapter over web/protocol's decoder (src/net/protocol_adapter.js): golden server messages
// come out in viewer units (metres, radians, phases in [0, 1), BigInt tokens, parsed world).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { createDecoder } from '../src/net/protocol_adapter.js';

const golden = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../../tests/protocol/golden');
const read = (n) => new Uint8Array(fs.readFileSync(path.join(golden, `${n}.bin`)));

test('welcome: the world description is parsed', () => {
  const m = createDecoder().decode(read('welcome'));
  assert.equal(m.type, 'Welcome');
  assert.equal(m.world.name, 'museum');
});

test('joined: the token is a BigInt', () => {
  const m = createDecoder().decode(read('joined'));
  assert.equal(m.token, 0x0123456789abcdefn);
  assert.equal(m.participantId, 7);
});

test('move: metres and radians', () => {
  const m = createDecoder().decode(read('move'));
  assert.ok(Math.abs(m.x - 12.34) < 1e-9 && Math.abs(m.y + 5.67) < 1e-9 && Math.abs(m.z - 0.5) < 1e-9);
  assert.ok(Math.abs(m.yaw - 1.5) < 1e-4);
});

test('crowd key frame then delta: viewer frames with the header tier counts', () => {
  const d = createDecoder();
  for (const name of ['crowd_key', 'crowd_delta']) {
    const m = d.decode(read(name));
    if (m.type === 'Skip') continue;  // a delta whose base is not the key frame above
    assert.equal(m.type, 'CrowdFrame');
    const h = m.header;
    assert.equal(m.frame.count, h.nearCount + h.middleCount + h.farCount);
    for (let i = 1; i < m.frame.count; ++i) assert.ok(m.frame.ids[i] > m.frame.ids[i - 1]);
    for (let i = 0; i < m.frame.count; ++i) {
      assert.ok(m.frame.phase[i] >= 0 && m.frame.phase[i] < 1);
      assert.ok(m.frame.yaw[i] >= -Math.PI && m.frame.yaw[i] < Math.PI);
    }
  }
});
