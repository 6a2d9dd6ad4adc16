// End-to-end test of the avatar's look (issue 20, "avatar choice") against a real `throng serve
// scenarios/museum.json` in Debian's headless chromium: the join form offers the looks of
// src/crowd/avatar_looks.js; the look picked before joining goes to the server as Join's avatar
// index (the WebSocket frame is decoded with web/protocol/decode.js); the avatar's chest is drawn in
// the chosen shirt colour, and changing the look while joined recolours it at once — for the other
// participants too (Join again, a new Presence); the red ring and pin that mark your own avatar stay
// whatever the look; the choice is remembered after a reload.
// Run: THRONG_EXE=build/apps/throng/throng node --test web/viewer/e2e/avatar.e2e.test.mjs
// (THRONG_E2E_SHOTS=DIR keeps a screenshot). Fails, like the other e2e tests, when something it needs is missing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { repo, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer, sleep } from './harness.mjs';
import { decodeAny } from '../../protocol/decode.js';

/** The avatar's chest colour [r, g, b] as drawn now: the median of 9 pixels around it. */
function chestColour(page) {
  return page.evaluate(() => {
    const { cameras, toScreen, rgbAt } = globalThis.__throng;
    const a = cameras.avatar;
    const p = toScreen(a.x, a.y, a.z + 1.25);
    const px = [];
    for (const dx of [-3, 0, 3]) for (const dy of [-3, 0, 3]) px.push(rgbAt(p.x + dx, p.y + dy));
    return [0, 1, 2].map((c) => px.map((q) => q[c]).sort((u, v) => u - v)[4]);
  });
}
const shotsDir = process.env.THRONG_E2E_SHOTS || '';
async function shot(page, name) {
  if (!shotsDir) return;
  fs.mkdirSync(shotsDir, { recursive: true });
  await page.screenshot({ path: path.join(shotsDir, name) });
}
const dominant = (rgb) => rgb.indexOf(Math.max(...rgb));

test('a participant picks how the avatar looks; it is sent in Join and drawn so', { timeout: 150000 }, async () => {
  requirePrerequisites('avatar.e2e');
  const server = await startServer(path.join(repo, 'scenarios/museum.json'));
  const browser = await launchBrowser();
  const errors = [];
  try {
    const page = await openViewer(browser, server.url, errors);
    const joins = [];
    page.on('websocket', (ws) => ws.on('framesent', (f) => {
      if (typeof f.payload === 'string') return;
      const m = decodeAny(new Uint8Array(f.payload));
      if (m.type === 'Join') joins.push(m);
    }));
    // Reloaded once the first load is done (its clips fetched), so the listener sees the connection from its start.
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 0, null, { timeout: 30000 });
    await page.reload();
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 0, null, { timeout: 30000 });
    const looks = await page.$$eval('#join-look option', (o) => o.map((x) => x.textContent));
    assert.ok(looks.length >= 4, `looks offered: ${looks.join(' | ')}`);

    await page.selectOption('#join-look', '2');  // blue coat, tall
    await page.fill('#join-name', 'e2e-look');
    await page.click('#join-button');
    await page.waitForFunction(() => globalThis.__throng.joined !== null, null, { timeout: 15000 });
    assert.equal(joins.length, 1, `Join messages sent: ${JSON.stringify(joins)}`);
    assert.deepEqual({ name: joins[0].name, avatar: joins[0].avatar }, { name: 'e2e-look', avatar: 2 });

    // Joined. Seen from 4 m with the world's walls and floors hidden (the avatar is placed where
    // the view was centred, maybe by a wall), the avatar's chest shows the look's shirt.
    await page.evaluate(() => {
      const { cameras, worldRoot } = globalThis.__throng;
      worldRoot().visible = false;
      cameras.lookAt(cameras.avatar.x, cameras.avatar.y, 4, 1.6);
    });
    await sleep(500);
    await shot(page, 'viewer_avatar_look.png');
    const blue = await chestColour(page);
    assert.equal(dominant(blue), 2, `blue coat: the chest is ${blue}`);
    await page.selectOption('#join-look', '3');  // green top: recoloured at once, still joined
    await sleep(300);
    const green = await chestColour(page);
    assert.equal(dominant(green), 1, `green top: the chest is ${green}`);
    await page.evaluate(() => globalThis.__throng.setLook(0));  // red jacket
    await sleep(300);
    const red = await chestColour(page);
    assert.equal(dominant(red), 0, `red jacket: the chest is ${red}`);
    assert.equal(await page.$eval('#join-look', (s) => s.value), '0', 'the menu follows a look set by a script');

    await page.evaluate(() => { globalThis.__throng.worldRoot().visible = true; });

    // Your own avatar stays unmistakable whatever its look: the red ring and pin.
    const marks = await page.evaluate(() => {
      const { markers, selfColour } = globalThis.__throng;
      return { visible: markers.self.visible, colours: markers.self.children.map((c) => c.material.color.getHex()), selfColour };
    });
    assert.ok(marks.visible, 'the ring and pin are shown');
    assert.ok(marks.colours.every((c) => c === marks.selfColour), `ring and pin colours ${marks.colours}`);

    // Remembered: a reload offers the look chosen last.
    await page.selectOption('#join-look', '4');
    await page.reload();
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 0, null, { timeout: 30000 });
    assert.equal(await page.evaluate(() => globalThis.__throng.look), 4);
    assert.equal(await page.$eval('#join-look', (s) => s.value), '4');
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
  }
});

/** The chest colour [r, g, b] of the other participant `name` as page draws it now (median of 9 pixels). */
function otherChestColour(page, name) {
  return page.evaluate((who) => {
    const { others, toScreen, rgbAt } = globalThis.__throng;
    const o = [...others.values()].find((x) => x.name === who);
    const p = toScreen(o.x, o.y, (o.z || 0) + 1.25);
    const px = [];
    for (const dx of [-3, 0, 3]) for (const dy of [-3, 0, 3]) px.push(rgbAt(p.x + dx, p.y + dy));
    return [0, 1, 2].map((c) => px.map((q) => q[c]).sort((u, v) => u - v)[4]);
  }, name);
}

test('two participants with different looks each see the other in theirs (Presence, protocol 2)', { timeout: 150000 }, async () => {
  requirePrerequisites('avatar.e2e');
  const server = await startServer(path.join(repo, 'scenarios/museum.json'));
  const browser = await launchBrowser();
  const errors = [];
  try {
    const pages = [];
    for (const [name, look] of [['e2e-blue', '2'], ['e2e-green', '3']]) {
      const page = await openViewer(browser, server.url, errors);
      await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 0, null, { timeout: 30000 });
      await page.selectOption('#join-look', look);
      await page.fill('#join-name', name);
      await page.click('#join-button');
      await page.waitForFunction(() => globalThis.__throng.joined !== null, null, { timeout: 15000 });
      pages.push(page);
    }
    // Both were placed where their views were centred: the second steps 3 m aside, so each body stands alone.
    await pages[1].evaluate(() => { globalThis.__throng.cameras.avatar.x += 3; });
    const [blue, green] = pages;
    const seen = async (page, other) => {
      await page.waitForFunction((o) => globalThis.__throng.otherLooks()[o] !== undefined, other, { timeout: 15000 });
      return page.evaluate(() => globalThis.__throng.otherLooks());
    };
    assert.deepEqual(await seen(blue, 'e2e-green'), { 'e2e-green': 'green top, short' });
    assert.deepEqual(await seen(green, 'e2e-blue'), { 'e2e-blue': 'blue coat, tall' });
    assert.equal(await blue.evaluate(() => globalThis.__throng.source.looks.get([...globalThis.__throng.source.names]
      .find(([, n]) => n === 'e2e-green')[0])), 3, 'the look index Presence carried');

    // And drawn so: seen from 4 m with the world hidden, the other's chest shows their shirt.
    for (const [page, other, channel] of [[blue, 'e2e-green', 1], [green, 'e2e-blue', 2]]) {
      // The body is drawn where the last rendered frame put it, and on a loaded machine a page
      // may render a frame a second (or reconnect and re-centre its view on its own avatar): aim
      // the camera and look again, up to 10 s, until the frame has caught up.
      let rgb = null;
      for (const until = Date.now() + 10000; Date.now() < until;) {
        await page.evaluate((who) => {
          const { cameras, worldRoot, others } = globalThis.__throng;
          worldRoot().visible = false;
          const o = [...others.values()].find((x) => x.name === who);
          cameras.lookAt(o.x, o.y, 4, 1.6);
        }, other);
        await sleep(300);
        rgb = await otherChestColour(page, other);
        if (dominant(rgb) === channel) break;
      }
      assert.equal(dominant(rgb), channel, `${other} seen with the chest ${rgb}`);
    }
    await shot(blue, 'viewer_avatar_looks_shared.png');

    // A look changed while joined reaches the others (Join again: the same participant, a new Presence).
    const id = await green.evaluate(() => globalThis.__throng.joined.participantId);
    await green.selectOption('#join-look', '0');  // red jacket
    await blue.waitForFunction(() => globalThis.__throng.otherLooks()['e2e-green'] === 'red jacket', null, { timeout: 15000 });
    assert.equal(await green.evaluate(() => globalThis.__throng.joined.participantId), id, 'still the same participant');
    assert.equal(await blue.evaluate(() => globalThis.__throng.source.present.size), 2, 'nobody joined or left');
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
  }
});
