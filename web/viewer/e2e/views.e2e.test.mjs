// End-to-end test of the viewer's cameras and picking (issue 20) against a real `throng serve
// scenarios/museum.json` in Debian's headless chromium: the 51 m museum opens in plan view
// (orthographic, top-down) with the whole walkable area on screen clear of the panels; clicking agents selects them in
// the zoomed-out plan, a close plan, a low oblique and a steep oblique orbit view (each click must
// select the agent under the pointer: the pick used to test only the side of a cylinder and missed
// every top-down click); F fits the world again after zooming; T follows the selected agent; C
// cycles plan → orbit → walk. Labels of points: a fixed screen size close up (12–22 px high, however
// near the camera), never overlapping each other or a panel, L hides and shows them. Colour by:
// B cycles group → population → speed → density → state, the legend follows, and the disc drawn at
// an agent has the colour its mode gives it; the legend names every mark of the world; ? opens the
// help with every key, Esc closes it; a participant's own avatar is marked by a ring and a pin in
// a colour no mode gives an agent. The HUD names the scenario and shows the simulated time (it
// advances) and the agents, the engineering figures only under "debug". R shows trails that end
// where the agents are. Run: THRONG_EXE=build/apps/throng/throng node --test
// web/viewer/e2e/views.e2e.test.mjs (THRONG_E2E_SHOTS=DIR keeps screenshots). Fails, like the other
// e2e tests, when something it needs is missing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { repo, requirePrerequisites, startServer, stopServer, launchBrowser, openViewer, sleep } from './harness.mjs';

const shotsDir = process.env.THRONG_E2E_SHOTS || '';
export async function shot(page, name) {
  if (!shotsDir) return;
  fs.mkdirSync(shotsDir, { recursive: true });
  await page.screenshot({ path: path.join(shotsDir, name) });
}

/** Up to `n` agents drawn on the bare canvas (no panel over them), clear of any other agent on
 * screen (by `gap` px, or in perspective by what 0.7 m spans on screen at the agent or at the
 * other, whichever is more: a body in front would hide it): [{id, x, y}] (screen px, the body's middle). */
export function clickable(page, n, gap = 5) {
  return page.evaluate(([n, gap]) => {
    const { state, toScreen } = globalThis.__throng;
    const pts = [];
    for (let i = 0; i < state.count; ++i) {
      const p = toScreen(state.x[i], state.y[i], state.z[i] + 0.9);
      const side = toScreen(state.x[i] + 0.7, state.y[i], state.z[i] + 0.9), up = toScreen(state.x[i], state.y[i], state.z[i] + 1.6);
      const span = !globalThis.__throng.camera.isPerspectiveCamera ? 0 : Math.max(side ? Math.hypot(side.x - p.x, side.y - p.y) : 0, up ? Math.hypot(up.x - p.x, up.y - p.y) : 0);
      if (p) pts.push({ id: state.ids[i], x: p.x, y: p.y, clear: Math.max(gap, span) });
    }
    const out = [];
    for (const p of pts) {
      if (p.x < 8 || p.y < 8 || p.x > innerWidth - 8 || p.y > innerHeight - 8) continue;
      if (document.elementFromPoint(p.x, p.y) !== document.querySelector('#app canvas')) continue;
      // Clear by the larger of the two spans: a body nearer the camera is larger on screen and
      // covers a farther one further from its own middle than the farther one's span.
      if (pts.some((q) => q !== p && Math.hypot(q.x - p.x, q.y - p.y) < Math.max(p.clear, q.clear))) continue;
      out.push({ id: p.id, x: p.x, y: p.y });
      if (out.length >= n) break;
    }
    return out;
  }, [n, gap]);
}

/** Clicks each agent where it is drawn now; returns [{want, got}] (got: the selected id, or null
 * when no panel opened within 5 s, polled every 100 ms: not per animation frame, which a loaded
 * software renderer may draw less than once a second).
 * `real`: with the mouse; otherwise pointer events dispatched on the canvas in the same task as
 * the agent's screen position is read (a walker on a busy software renderer moves a body's width
 * between a read and a real click's arrival). */
export async function clickAgents(page, n, real = false) {
  const results = [];
  for (let k = 0; k < n; ++k) {
    await page.evaluate(() => { document.querySelector('#agent-close').click(); });
    const [t] = await clickable(page, 1 + k).then((a) => a.slice(k));
    if (!t) break;
    if (real) {
      await page.mouse.click(t.x, t.y);
    } else {
      await page.evaluate((id) => {
        const { state, toScreen } = globalThis.__throng;
        const i = state.index.get(id);
        const p = toScreen(state.x[i], state.y[i], state.z[i] + 0.9);
        const canvas = document.querySelector('#app canvas');
        for (const type of ['pointerdown', 'pointerup']) {
          canvas.dispatchEvent(new PointerEvent(type, { clientX: p.x, clientY: p.y, bubbles: true, pointerId: 1, isPrimary: true, button: 0 }));
        }
      }, t.id);
    }
    const got = await page.waitForFunction(() => {
      const p = document.querySelector('#agent-panel');
      return !p.classList.contains('hidden') && document.querySelector('#agent-id').textContent;
    }, null, { timeout: 5000, polling: 100 }).then((h) => h.jsonValue(), () => null);
    results.push({ want: `#${t.id}`, got });
  }
  return results;
}

/** Screen rectangle covered by the world's walkable bounds in the current camera. */
function worldOnScreen(page) {
  return page.evaluate(() => {
    const { cameras, toScreen } = globalThis.__throng;
    const b = cameras.bounds;
    const c = [[b.minX, b.minY], [b.maxX, b.minY], [b.minX, b.maxY], [b.maxX, b.maxY]].map(([x, y]) => toScreen(x, y, 0));
    const panels = ['hud', 'controls', 'legend'].map((id) => document.getElementById(id).getBoundingClientRect())
      .filter((p) => p.width > 0).map((p) => ({ left: p.left, top: p.top, right: p.right, bottom: p.bottom }));
    return { left: Math.min(...c.map((p) => p.x)), right: Math.max(...c.map((p) => p.x)),
      top: Math.min(...c.map((p) => p.y)), bottom: Math.max(...c.map((p) => p.y)), w: innerWidth, h: innerHeight, panels };
  });
}

/** On screen, clear of the panels (fit frames it in the part they leave free: framing.e2e checks
 * that at 1280×720), and large: at 640×360 the panels leave a third of the view's area free. */
function assertFits(r, what) {
  assert.ok(r.left >= -1 && r.top >= -1 && r.right <= r.w + 1 && r.bottom <= r.h + 1, `${what}: the world is on screen ${JSON.stringify(r)}`);
  for (const p of r.panels) {
    assert.ok(!(r.left < p.right && p.left < r.right && r.top < p.bottom && p.top < r.bottom), `${what}: the world is clear of the panels ${JSON.stringify(r)}`);
  }
  assert.ok(r.right - r.left > 0.45 * r.w || r.bottom - r.top > 0.45 * r.h, `${what}: the world fills the view ${JSON.stringify(r)}`);
}

/** The point labels on screen: their rectangles, and the panels'. */
function labelBoxes(page) {
  return page.evaluate(() => {
    const box = (el) => { const r = el.getBoundingClientRect(); return { left: r.left, top: r.top, w: r.width, h: r.height, text: el.textContent }; };
    const labels = [...document.querySelectorAll('.point-label')].filter((d) => d.style.display !== 'none').map(box);
    const panels = ['hud', 'controls'].map((id) => box(document.getElementById(id)));
    return { labels, panels };
  });
}

function assertLabelsReadable({ labels, panels }, what) {
  const hit = (a, b) => a.left < b.left + b.w && b.left < a.left + a.w && a.top < b.top + b.h && b.top < a.top + a.h;
  for (const l of labels) {
    assert.ok(l.h >= 10 && l.h <= 22, `${what}: label "${l.text}" is ${l.h} px high (want 10–22)`);
    for (const p of panels) assert.ok(!hit(l, p), `${what}: label "${l.text}" lies over a panel ${JSON.stringify([l, p])}`);
  }
  for (let i = 0; i < labels.length; ++i) {
    for (let j = i + 1; j < labels.length; ++j) {
      assert.ok(!hit(labels[i], labels[j]), `${what}: labels overlap ${JSON.stringify([labels[i], labels[j]])}`);
    }
  }
}

function assertAllSelected(results, what, atLeast) {
  assert.ok(results.length >= atLeast, `${what}: ${results.length} agents to click (want ${atLeast})`);
  const wrong = results.filter((r) => r.got !== r.want);
  assert.deepEqual(wrong, [], `${what}: every click selects the agent under it (${results.length - wrong.length} of ${results.length})`);
}

test('plan view, fit, follow and picking from every angle', { timeout: 120000 }, async () => {
  requirePrerequisites('views e2e');
  const server = await startServer(path.join(repo, 'scenarios/museum.json'));
  const browser = await launchBrowser();
  const errors = [];
  try {
    const page = await openViewer(browser, server.url, errors);
    await page.waitForFunction(() => globalThis.__throng && globalThis.__throng.state.count > 12, null, { timeout: 45000 });
    const first = await page.evaluate(() => ({ mode: globalThis.__throng.cameras.mode, ortho: globalThis.__throng.camera.isOrthographicCamera }));
    assert.deepEqual(first, { mode: 'plan', ortho: true }, 'the 51 m museum opens in plan view');
    assert.ok(await page.evaluate(() => document.querySelector('#cam-plan').classList.contains('active')), 'the Plan button is lit');
    assertFits(await worldOnScreen(page), 'plan view at start');
    await shot(page, 'views_plan.png');

    // The HUD says what is shown: the scenario, the simulated time (advancing), the agents; the
    // engineering figures only once "debug" is opened.
    const hud0 = await page.evaluate(() => ({ text: globalThis.__throng.hud.text(), t: globalThis.__throngStats.simTime }));
    await sleep(1500);
    const hud1 = await page.evaluate(() => ({ text: globalThis.__throng.hud.text(), t: globalThis.__throngStats.simTime,
      agents: globalThis.__throng.state.count }));
    assert.match(hud1.text, /^museum\n/, `the HUD names the scenario: ${hud1.text}`);
    assert.match(hud1.text, /time +\d+:\d\d of 5:00/, `the HUD shows the simulated time of the scenario's 5 min: ${hud1.text}`);
    assert.ok(hud1.t > hud0.t + 0.5, `the simulated time advances (${hud0.t} → ${hud1.t} s)`);
    assert.match(hud1.text, /agents +\d+/, hud1.text);
    assert.doesNotMatch(hud1.text, /kbit|near|caps/, 'engineering figures folded away');
    await page.click('.hud-debug-toggle');
    await sleep(1100);
    assert.match(await page.evaluate(() => globalThis.__throng.hud.text()), /kbit\/s[\s\S]*plan discs/, 'debug opens them');
    await page.click('.hud-debug-toggle');
    const planLabels = await labelBoxes(page);
    assert.ok(planLabels.labels.length >= 3, `point labels in the plan view: ${planLabels.labels.map((l) => l.text)}`);
    assertLabelsReadable(planLabels, 'plan view');

    // Zoomed-out plan: each body a few pixels wide — the world as large as the whole 640×360 view
    // frames it (the part the panels leave free draws it at half that, the crowd bunched up).
    await page.evaluate(() => {
      const { cameras } = globalThis.__throng;
      const b = cameras.bounds;
      const high = 2 * 1.12 * Math.max((b.maxY - b.minY) / 2, (b.maxX - b.minX) / 2 / (innerWidth / innerHeight));
      cameras.planAt((b.minX + b.maxX) / 2, (b.minY + b.maxY) / 2, high);
    });
    await sleep(300);
    assertAllSelected(await clickAgents(page, 5, true), 'zoomed-out plan', 3);

    // Close plan around the crowd's centre.
    await page.evaluate(() => {
      const { state, cameras } = globalThis.__throng;
      let cx = 0, cy = 0;
      for (let i = 0; i < state.count; ++i) { cx += state.x[i]; cy += state.y[i]; }
      cameras.planAt(cx / state.count, cy / state.count, 14);
    });
    await sleep(300);
    assertAllSelected(await clickAgents(page, 4), 'close plan', 2);

    // The agent panel never covers the agent clicked: with the view moved so that the selected agent
    // is drawn where the panel stands (right), the panel moves to the left; centred again, it returns.
    const placeUnderPanel = (where) => page.evaluate((where) => {
      const { state, cameras } = globalThis.__throng;
      const id = Number(document.querySelector('#agent-id').textContent.slice(1));
      const i = state.index.get(id);
      const r = document.querySelector('#agent-panel').getBoundingClientRect();
      const high = 20, mpp = high / innerHeight;
      const c = where === 'panel' ? { x: (r.left + r.right) / 2, y: Math.min((r.top + r.bottom) / 2, innerHeight - 30) }
        : { x: innerWidth / 2, y: innerHeight / 2 };
      cameras.planAt(state.x[i] - (c.x - innerWidth / 2) * mpp, state.y[i] + (c.y - innerHeight / 2) * mpp, high);
      return id;
    }, where);
    const selected = await placeUnderPanel('panel');
    await page.waitForFunction(() => document.querySelector('#agent-panel').classList.contains('left'), null, { timeout: 5000, polling: 100 })
      .catch(() => assert.fail('the agent panel stayed over the agent clicked'));
    const cover = await page.evaluate((id) => {
      const { state, toScreen } = globalThis.__throng;
      const i = state.index.get(id);
      const p = toScreen(state.x[i], state.y[i], state.z[i] + 0.9), r = document.querySelector('#agent-panel').getBoundingClientRect();
      return { p, r: { left: r.left, right: r.right, top: r.top, bottom: r.bottom } };
    }, selected);
    assert.ok(!(cover.p.x >= cover.r.left && cover.p.x <= cover.r.right && cover.p.y >= cover.r.top && cover.p.y <= cover.r.bottom),
      `moved aside, the panel is clear of the agent: ${JSON.stringify(cover)}`);
    await shot(page, 'views-panel-aside.png');
    await placeUnderPanel('centre');
    await page.waitForFunction(() => !document.querySelector('#agent-panel').classList.contains('left'), null, { timeout: 5000, polling: 100 })
      .catch(() => assert.fail('the agent panel did not come back to the right'));

    // F fits the world again.
    await page.mouse.click(5, 355);
    await page.keyboard.press('KeyF');
    await sleep(200);
    assertFits(await worldOnScreen(page), 'plan view after F');

    // Low and steep oblique orbit views.
    for (const [distance, height, what] of [[9, 4, 'low oblique'], [6, 12, 'steep oblique']]) {
      // Look at one of the agents standing furthest from any other (in a low view a crowd hides
      // itself; groups walk side by side): the most isolated that shows clear of the others.
      const count = await page.evaluate(() => globalThis.__throng.state.count);
      for (let k = 0; k < count; ++k) {
        await page.evaluate(([d, h, rank]) => {
          const { state, cameras } = globalThis.__throng;
          const alone = [];
          for (let i = 0; i < state.count; ++i) {
            let near = Infinity;
            for (let j = 0; j < state.count; ++j) {
              if (j !== i) near = Math.min(near, Math.hypot(state.x[j] - state.x[i], state.y[j] - state.y[i]));
            }
            alone.push([near, i]);
          }
          alone.sort((a, b) => b[0] - a[0] || a[1] - b[1]);
          const i = alone[Math.min(rank, alone.length - 1)][1];
          cameras.lookAt(state.x[i], state.y[i], d, h);
        }, [distance, height, k]);
        await sleep(300);
        if ((await clickable(page, 1)).length > 0) break;
      }
      assert.equal(await page.evaluate(() => globalThis.__throng.camera.isPerspectiveCamera), true, `${what}: perspective camera`);
      assertAllSelected(await clickAgents(page, 3), what, 1);
      await shot(page, `views_${what.replace(' ', '_')}.png`);
    }

    // Colour by: B cycles the modes; the legend and the drawn discs follow.
    await page.evaluate(() => {
      const { state, cameras } = globalThis.__throng;
      let cx = 0, cy = 0;
      for (let i = 0; i < state.count; ++i) { cx += state.x[i]; cy += state.y[i]; }
      cameras.planAt(cx / state.count, cy / state.count, 14);
      document.querySelector('#agent-close').click();
      globalThis.__throng.crowd.selectedGroup = -1;
    });
    await page.evaluate(() => { if (globalThis.__throng.legend.folded) document.querySelector('#legend .fold').click(); });
    const modes = [];
    const palettes = {};
    for (let k = 0; k < 5; ++k) {
      const m = await page.evaluate(() => globalThis.__throng.crowd.colourMode);
      await sleep(250);
      // Sampled in an animation frame right after the viewer's own: the discs are drawn from the
      // state as that frame advanced it, and no server message can change the state (speeds, under
      // speed colouring) between the drawing and the colours wanted (a race seen on a busy machine).
      const seen = await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => {
        const { state, crowd, toScreen, rgbAt, legend } = globalThis.__throng;
        const out = [];
        for (let i = 0; i < state.count && out.length < 6; ++i) {
          const p = toScreen(state.x[i], state.y[i], 0);
          if (!p || document.elementFromPoint(p.x, p.y) !== document.querySelector('#app canvas')) continue;
          const want = crowd.colourAt(i, state).getHex();
          out.push({ want, got: [[0, 0], [2, 0], [-2, 0], [0, 2], [0, -2]].map(([dx, dy]) => rgbAt(p.x + dx, p.y + dy)) });
        }
        resolve({ out, legend: legend.labels(), select: document.querySelector('#colour-by').value });
      })));
      modes.push(m);
      palettes[m] = seen.out.map((o) => o.want);
      assert.equal(seen.select, m, 'the legend\'s menu shows the mode');
      assert.ok(seen.out.length >= 2, `${m}: agents to look at`);
      // The disc's middle (within 2 px: not its white heading wedge or dark rim) has the colour.
      const near = (o) => {
        const w = [(o.want >> 16) & 255, (o.want >> 8) & 255, o.want & 255];
        return o.got.some((g) => w.every((c, j) => Math.abs(c - g[j]) < 40));
      };
      assert.ok(seen.out.filter(near).length >= seen.out.length - 1, `${m}: the discs have the mode's colours ${JSON.stringify(seen.out)}`);
      const want = { group: /^group \d/, population: /school-class|family|couples|no population/, speed: /m\/s/, density: /persons\/m²/, state: /^walking$/ }[m];
      assert.ok(seen.legend.some((l) => want.test(l)), `${m}: the legend lists its colours: ${seen.legend}`);
      for (const mark of ['selected agent', 'you', 'interest point', 'action point', 'exit', 'wall', 'floor']) {
        assert.ok(seen.legend.some((l) => l.includes(mark)), `${m}: the legend explains "${mark}": ${seen.legend}`);
      }
      if (k === 4) await shot(page, 'views_colour_state.png');
      await page.keyboard.press('KeyB');
    }
    assert.deepEqual(modes, ['group', 'population', 'speed', 'density', 'state'], 'B cycles the colour modes');
    const selfColour = await page.evaluate(() => globalThis.__throng.selfColour);
    for (const [m, cs] of Object.entries(palettes)) assert.ok(!cs.includes(selfColour), `${m}: no agent has your avatar's colour`);

    // R: trails of the last seconds, ending where the agents are; in the legend; R again: gone.
    await page.keyboard.press('KeyR');
    await sleep(3000);
    const tr = await page.evaluate(() => {
      const { trails, state, legend } = globalThis.__throng;
      const ends = new Map();
      trails.buffer.forEachSegment((id, ax, ay, az, bx, by, bz, ageA, ageB) => {
        if (!ends.has(id) || ends.get(id)[2] > ageB) ends.set(id, [bx, by, ageB]);  // each trail's newest end
      });
      let near = 0;
      for (const [id, [x, y]] of ends) {
        const i = state.index.get(id);
        if (i !== undefined && Math.hypot(state.x[i] - x, state.y[i] - y) < 1.0) near++;
      }
      return { on: trails.enabled, visible: trails.lines.visible, segments: trails.segments, ends: ends.size, near,
        legend: legend.labels().some((l) => l.startsWith('trail')), box: document.querySelector('#trails-toggle').checked };
    });
    assert.ok(tr.on && tr.visible && tr.box && tr.legend, `trails on, drawn, ticked and in the legend: ${JSON.stringify(tr)}`);
    assert.ok(tr.segments >= 10 && tr.near >= Math.min(3, tr.ends) && tr.ends >= 2, `trails end at the agents: ${JSON.stringify(tr)}`);
    await shot(page, 'views_trails.png');
    await page.keyboard.press('KeyR');
    assert.equal(await page.evaluate(() => globalThis.__throng.trails.lines.visible), false, 'R again hides the trails');

    // ? opens the help with every key, Esc closes it.
    await page.keyboard.press('?');
    const helpRows = await page.evaluate(() => document.querySelector('#help').classList.contains('hidden') ? null
      : [...document.querySelectorAll('#help th')].map((t) => t.textContent));
    assert.ok(helpRows && ['C', 'P', 'O', 'F', 'T', 'L', 'B', 'R', 'Esc', '1 – 4', 'W/S or ↑/↓', 'click', 'wheel'].every((k) => helpRows.includes(k)),
      `the help lists every key: ${helpRows}`);
    await page.keyboard.press('Escape');
    assert.ok(await page.evaluate(() => document.querySelector('#help').classList.contains('hidden')), 'Esc closes the help');

    // Close up to a point (2.5 m away): its label keeps its screen size; L hides and shows labels.
    await page.evaluate(() => {
      const { description, cameras } = globalThis.__throng;
      const p = description.scenario.points.find((q) => q.position);
      cameras.lookAt(p.position[0], p.position[1], 2.5, 3);
    });
    await sleep(400);
    const close = await labelBoxes(page);
    assert.ok(close.labels.length >= 1, 'a point label close up');
    assertLabelsReadable(close, 'close up');
    await shot(page, 'views_labels_close.png');
    await page.keyboard.press('KeyL');
    const hidden = await page.waitForFunction(() => [...document.querySelectorAll('.point-label')].every((d) => d.style.display === 'none'),
      null, { timeout: 3000 }).then(() => true, () => false);
    assert.ok(hidden, 'L hides the point labels');
    await page.keyboard.press('KeyL');
    const back = await page.waitForFunction(() => [...document.querySelectorAll('.point-label')].some((d) => d.style.display !== 'none'),
      null, { timeout: 3000 }).then(() => true, () => false);
    assert.ok(back, 'L again shows them');

    // T follows the selected agent: the view closes in on it (from 40 m to 24 m high) and, after
    // it walks, is still centred on it.
    await page.evaluate(() => {
      const { state, cameras } = globalThis.__throng;
      cameras.planAt(state.x[0], state.y[0], 40);
    });
    await sleep(300);
    const [t] = await clickable(page, 1);
    assert.ok(t, 'an agent to click and follow');
    await page.mouse.click(t.x, t.y);
    await page.waitForFunction(() => !document.querySelector('#agent-panel').classList.contains('hidden'), null, { timeout: 2000 });
    await page.keyboard.press('KeyT');
    await sleep(2500);
    const follow = await page.evaluate((id) => {
      const { state, cameras } = globalThis.__throng;
      const i = state.index.get(id);
      const tg = cameras.plan.target;
      return { following: !!cameras.following, off: i === undefined ? null : Math.hypot(tg.x - state.x[i], -tg.z - state.y[i]),
        status: document.querySelector('#camera-status').textContent,
        high: (cameras.ortho.top - cameras.ortho.bottom) / cameras.ortho.zoom };
    }, t.id);
    assert.ok(follow.following && follow.off !== null && follow.off < 0.6, `the camera follows agent ${t.id}: ${JSON.stringify(follow)}`);
    assert.ok(follow.high <= 24.5, `following closes in: the plan view is ${follow.high.toFixed(1)} m high`);
    await page.keyboard.press('KeyT');
    assert.equal(await page.evaluate(() => !!globalThis.__throng.cameras.following), false, 'T again stops following');

    // Your own avatar: a ring and a pin no agent shares.
    await page.fill('#join-name', 'e2e-views');
    await page.click('#join-button');
    await page.waitForFunction(() => globalThis.__throng.joined !== null, null, { timeout: 15000 });
    await page.click('#cam-plan');
    await sleep(300);
    const me = await page.evaluate(() => {
      const { cameras, toScreen, rgbAt, markers } = globalThis.__throng;
      cameras.planAt(cameras.avatar.x, cameras.avatar.y, 12);
      const p = toScreen(cameras.avatar.x, cameras.avatar.y, 0);
      return { ring: markers.self.visible, pin: rgbAt(p.x, p.y) };
    });
    assert.ok(me.ring, 'your avatar is marked');
    assert.ok(me.pin[0] > 180 && me.pin[1] < 90 && me.pin[2] < 90, `the pin over your avatar is red from above: ${me.pin}`);
    await shot(page, 'views_self.png');
    await page.click('#cam-orbit');

    // C cycles the cameras.
    const cams = [];
    for (let k = 0; k < 3; ++k) { await page.keyboard.press('KeyC'); cams.push(await page.evaluate(() => globalThis.__throng.cameras.mode)); }
    assert.deepEqual(cams, ['walk', 'plan', 'orbit'], 'C: orbit → walk → plan → orbit');
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    await stopServer(server);
  }
});
