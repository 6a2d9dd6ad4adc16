// Export helpers (src/ui/export.js): the downloaded file's name and the WebM type chosen.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { exportName, videoMime } from '../src/ui/export.js';

test('export names carry the scenario and the UTC time', () => {
  const d = new Date(Date.UTC(2026, 10, 27, 4, 5, 9));
  assert.equal(exportName('museum', d, 'png'), 'throng-museum-20261127-040509.png');
  assert.equal(exportName('Two floors / gallery', d, 'webm'), 'throng-Two_floors_gallery-20261127-040509.webm');
  assert.equal(exportName('', d, 'png'), 'throng-view-20261127-040509.png');
  assert.equal(exportName(undefined, d, 'png'), 'throng-view-20261127-040509.png');
});

test('the video type is the first WebM codec the browser records', () => {
  assert.equal(videoMime(() => true), 'video/webm;codecs=vp9');
  assert.equal(videoMime((m) => m !== 'video/webm;codecs=vp9'), 'video/webm;codecs=vp8');
  assert.equal(videoMime((m) => m === 'video/webm'), 'video/webm');
  assert.equal(videoMime(() => false), null);
});
