// The viewer's entry point: reads the URL options, picks the data source (live server, ?demo, or
// ?demo&replay), builds the scene once the world description arrives (world_view, clips, crowd
// view, cameras) and runs the frame loop: interpolate the crowd, choose levels of detail, draw,
// update the HUD; wires the join form, picking, guide/release, the cameras (plan, orbit, walk, fit,
// follow: buttons and keys, ui/keys.js), the LOD toggle, export (PNG, WebM: ui/export.js), the banner and
// the avatar's look (the join form's menu: crowd/avatar_looks.js, remembered in localStorage) and a
// glTF world's own meshes with their materials (world/gltf_materials.js, live worlds).
// URL options: demo, agents=N, lod=on|off, ws=URL, replay (with demo), target=FPS, shot=1 (no
// panels: screenshots), aa=0 (no antialiasing), camera=plan|orbit|walk (the first camera).
import * as THREE from 'three';
import { CrowdState } from './interpolate.js';
import { DemoSource } from './sources/demo_source.js';
import { ReplaySource, MemoryReplayBackend } from './sources/replay_source.js';
import { LiveSource, reasonText } from './net/live_source.js';
import { buildWorld, addLights, worldBounds, pointLabels } from './world/world_view.js';
import { ClipLibrary } from './crowd/clip_library.js';
import { kHanimSkeleton } from './crowd/procedural_clips.js';
import { CrowdView } from './crowd/crowd_view.js';
import { NearBodies } from './crowd/near_bodies.js';
import { Cameras } from './camera/cameras.js';
import { Hud } from './ui/hud.js';
import { Banner } from './ui/banner.js';
import { AgentPanel, stateWords } from './ui/agent_panel.js';
import { Timeline } from './ui/timeline.js';
import { GroupList } from './ui/group_list.js';
import { ScreenLabels } from './ui/screen_labels.js';
import { GesturePlayer, RemoteJoints, gestureClip, kGestures } from './crowd/gestures.js';
import { bindKeys } from './ui/keys.js';
import { Legend, exitsAreEntrances } from './ui/legend.js';
import { Help } from './ui/help.js';
import { Markers, kSelfColour } from './crowd/markers.js';
import { Trails } from './crowd/trails.js';
import { Heatmap, DensityGrid, SpeedGrid } from './crowd/heatmap.js';
import { VoronoiDensityGrid, VoronoiSpeedGrid } from './crowd/voronoi.js';
import { Measurements } from './crowd/measure.js';
import { MeasurePanel } from './ui/measure_panel.js';
import { Exporter } from './ui/export.js';
import { RecordingsPanel } from './ui/recordings.js';
import { kSelectedColour, kPickedGroupColour } from './crowd/crowd_view.js';
import { kColourModes, defaultColourMode } from './crowd/colour_by.js';
import { kAvatarLooks, lookAt, loadLookChoice, saveLookChoice } from './crowd/avatar_looks.js';
import { loadWorldModel, showWorldModel } from './world/gltf_materials.js';

const params = new URLSearchParams(location.search);
const demo = params.has('demo');
const agentsN = Math.max(1, Math.min(100000, Number(params.get('agents') || 300)));
const lodOn = params.get('lod') !== 'off';
const shot = params.get('shot') === '1';
const $ = (id) => document.getElementById(id);

function makeSource() {
  if (demo && params.has('replay')) {
    const live = new DemoSource(agentsN);
    const frames = [];
    let t = 0;
    live.on('world', (w) => { live.world = w; });
    live.on('frame', (f) => frames.push({ time: t, frame: f }));
    live.start();
    live.stop();
    for (let k = 0; k < 600; ++k) { t += 0.1; live.step(0.1); }  // one minute of demo, recorded
    return new ReplaySource(new MemoryReplayBackend(live.world, frames));
  }
  if (demo) return new DemoSource(agentsN);
  return new LiveSource(params.get('ws') || undefined);
}

const renderer = new THREE.WebGLRenderer({ antialias: params.get('aa') !== '0', preserveDrawingBuffer: shot });
const basePixelRatio = Math.min(devicePixelRatio, 2);
renderer.setPixelRatio(basePixelRatio);
renderer.setSize(innerWidth, innerHeight);
$('app').appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xeef2f5);
const camera = new THREE.PerspectiveCamera(55, innerWidth / innerHeight, 0.1, 2000);
addEventListener('resize', () => {
  camera.aspect = innerWidth / innerHeight;
  camera.updateProjectionMatrix();
  if (cameras) cameras.resize(innerWidth / innerHeight);
  renderer.setSize(innerWidth, innerHeight);
});
/** The panels that stay on screen over the canvas (HUD, controls, legend, measurements, timeline):
 * their screen rectangles [px], those shown. Fit frames the world in the part they leave free
 * (camera/framing.js); the agent panel and the help come and go, and are left out. */
const kFramePanels = ['hud', 'controls', 'legend', 'measure', 'timeline'];
function panelRects() {
  return kFramePanels.map((id) => $(id).getBoundingClientRect()).filter((r) => r.width > 0 && r.height > 0)
    .map((r) => ({ left: r.left, top: r.top, right: r.right, bottom: r.bottom }));
}
/** The panels grow and shrink after the world arrives (the group list, the recordings row, the
 * legend folding, the timeline of a replay): checked four times a second, and a camera that still
 * shows the world as Fit framed it is framed again when they moved. */
let panelKey = '', panelCheckAt = 0;
function refitForPanels(nowMs) {
  if (!cameras || nowMs < panelCheckAt) return;
  panelCheckAt = nowMs + 250;
  const key = panelRects().map((r) => [r.left, r.top, r.right, r.bottom].map(Math.round).join(',')).join(';');
  if (key === panelKey) return;
  panelKey = key;
  cameras.refit();
}
/** The camera drawing now: the plan view's orthographic one, or the perspective one. */
const view = () => (cameras ? cameras.camera : camera);
if (shot) for (const id of ['hud', 'controls']) $(id).classList.add('hidden');

const source = makeSource();
const banner = new Banner($('banner'));
const hud = new Hud($('hud'));
const state = new CrowdState();
let crowd = null, cameras = null, clips = null, avatars = null, description = null;
let selectedId = -1;
let joined = null;
const others = new Map();  // participant id → {x, y, yaw, moving, phase}
const localPhase = { phase: 0 };
const gesture = new GesturePlayer();     // the local avatar's gesture (buttons, keys 1–4)
const remoteJoints = new RemoteJoints(); // other participants' latest relayed Joints
const labels = new ScreenLabels($('labels'));
let worldLabels = [];  // the points' name labels (world_view.js pointLabels)
const kOtherColour = 0xd02090;  // other participants' avatars
let lookIndex = loadLookChoice(globalThis.localStorage);  // your avatar's look (the join form's menu)
let worldModel = null;  // a glTF world's meshes with their materials, drawn instead of the flat floors
let markers = null;
let heatmap = null;  // density heatmap overlay (key M)
// The maps' definitions (the menus beside them): the URL's at first, then the person's, kept across worlds.
// One menu sets both maps' definition (the controls have room for one).
const initialMapMethod = params.get('heatmap') === 'voronoi' || params.get('speedmap') === 'voronoi' ? 'voronoi' : 'classic';
let heatmapMethod = initialMapMethod, heatmapScenario = {}, heatmapBounds = null;
let measurements = null;  // the scenario's measurement lines and areas, measured live
let measurePanel = null;
let speedmap = null;  // speed heatmap overlay (key G)
let speedmapMethod = initialMapMethod;
let trails = null, trailsStale = false;  // trajectory trails (key R), rebuilt after a frame added samples
const legend = new Legend($('legend'), { selected: kSelectedColour, pickedGroup: kPickedGroupColour, self: kSelfColour, other: kOtherColour },
  (m) => setColourMode(m));
const help = new Help($('help'));
$('help-button').onclick = () => help.show();
function setColourMode(m) {
  if (!crowd || !kColourModes.includes(m)) return;
  crowd.colourMode = m;
  refreshLegend();
}
function refreshLegend() {
  if (crowd) {
    legend.update(crowd.colourMode, { populations: crowd.populations, groups: description.groups || [],
      groupColour: (g) => crowd.groupColours.index(g) });
  }
}
globalThis.__throngStats = globalThis.__throngStats || {};

source.on('status', (s) => banner.show(s));
// Another world after a reconnect (a viewer opened another recording: throng serve --recordings):
// everything built from the old one goes, so the page starts again.
source.on('worldChanged', () => globalThis.location.reload());
const recordings = source.kind === 'live' ? new RecordingsPanel({ row: $('recordings-row'), list: $('rec-list'),
  open: $('rec-open'), upload: $('rec-upload'), status: $('rec-status'), live: $('rec-live') }) : null;
if (recordings) recordings.refresh();
source.on('frame', (f) => {
  state.applyFrame(f, performance.now() / 1000);
  hud.frame(f);
  if (trails && trails.enabled && trails.record(f, hud.simTime)) trailsStale = true;
  if (heatmap) heatmap.record(f, hud.simTime);
  if (speedmap) speedmap.record(f, hud.simTime);
  if (measurements) measurements.record(f, hud.simTime);
});
source.on('participant', (m) => {
  const o = others.get(m.participantId) || { phase: 0, name: source.names.get(m.participantId) };
  o.moving = o.x !== undefined && Math.hypot(m.x - o.x, m.y - o.y) > 0.02;
  Object.assign(o, { x: m.x, y: m.y, z: m.z || 0, yaw: m.yaw, at: performance.now() });
  others.set(m.participantId, o);
});
source.on('joints', (m) => remoteJoints.set(m.participantId, Float32Array.from(m.angles), performance.now()));
source.on('world', async (w) => {
  if (!w.skeleton || !Array.isArray(w.skeleton.joints) || w.skeleton.joints.length === 0) {
    // The server found no motion files (a recording replayed away from its scenario's motions/):
    // the bundled library's skeleton, with procedural walk and idle clips.
    console.info('throng: no skeleton in the world description; using the built-in H-Anim skeleton');
    w.skeleton = { joints: kHanimSkeleton };
  }
  description = w;
  hud.setWorld(w);
  const bounds = worldBounds(w.scenario || {});
  const world = buildWorld(w.scenario || {});
  scene.add(world);
  legend.exhibits = !!world.getObjectByName('exhibits');
  if (source.kind === 'live') loadModel();
  worldLabels = pointLabels(w.scenario || {});
  addLights(scene, bounds);
  clips = new ClipLibrary(w);
  await clips.load('');
  state.setClips(w.clips || []);
  state.interval = 1 / (w.tickRate || 10);
  state.dt = Number(w.dt) > 0 ? Number(w.dt) : 0;  // speeds from simulated time (replays at any speed, seeks)
  crowd = new CrowdView(scene, renderer, w, clips, { adaptive: lodOn, targetFrameMs: 1000 / Number(params.get('target') || 30) });
  crowd.setGround(bounds.minZ || 0);
  crowd.onGroupColours = () => { refreshLegend(); trailsStale = true; };
  legend.multiLevel = crowd.multiLevel;
  legend.entrances = exitsAreEntrances(w.scenario);
  avatars = new NearBodies(scene, w.skeleton.joints, clips);
  markers = new Markers(scene, kSelectedColour);
  trails = new Trails(scene, undefined, bounds);
  heatmap = new Heatmap(scene, bounds);
  heatmapScenario = w.scenario || {};
  heatmapBounds = bounds;
  setHeatmapMethod(heatmapMethod);
  if (params.get('heatmap') === '1' || params.get('heatmap') === 'voronoi') toggleHeatmap(true);
  measurements = new Measurements((w.scenario || {}).measurements || []);
  measurePanel = new MeasurePanel($('measure'), measurements);
  speedmap = new Heatmap(scene, bounds, 'speed');
  setSpeedmapMethod(speedmapMethod);
  if (params.get('speedmap') === '1' || params.get('speedmap') === 'voronoi') toggleSpeedmap(true);
  if (params.get('trails') === '1') toggleTrails(true);
  const colourParam = params.get('colour');
  setColourMode(kColourModes.includes(colourParam) ? colourParam
    : defaultColourMode(w.groups, crowd.populations.length));
  const camParam = params.get('camera');
  cameras = new Cameras(camera, renderer.domElement, bounds, (w.scenario || {}).terrain || null,
    ['plan', 'orbit', 'walk'].includes(camParam) ? camParam : null, panelRects);
  setMode(cameras.mode);
  cameras.onFollowEnd = () => followNote('stopped following: it is no longer in the world');
  $('lod-toggle').checked = lodOn;
  groupList.setGroups(w.groups || []);
  globalThis.__throng = testHooks(w);
});
/** A glTF world's own meshes (GET /api/world/model gives the file's URL — a live glTF world's, or the
 * one a recording names when the server finds it again — null for a scenario JSON, with `missing`
 * saying why for a recording: shown in the HUD's debug panel): drawn, with their materials, instead
 * of the flat floors and obstacles. */
function loadModel() {
  fetch('/api/world/model').then((r) => (r.ok ? r.json() : null))
    .then((j) => {
      if (j && j.missing) { hud.modelMissing = j.missing; console.info(`throng: the world's glTF materials are not drawn (${j.missing})`); }
      return j && j.url ? loadWorldModel(j.url) : null;
    })
    .then((model) => {
      const root = scene.getObjectByName('world');
      if (!model || !root) return;
      root.add(model);
      showWorldModel(root, model, true);
      worldModel = model;
    })
    .catch((e) => console.info(`throng: the world's glTF materials are not drawn (${e.message})`));
}
/** What scripts and the tests reach through window.__throng: the parts, and screen helpers. */
function testHooks(w) {
  return {
    cameras, crowd, state, get camera() { return view(); }, source, panelRects, legend, help, hud, setColourMode, recordings,
    get trails() { return trails; }, get heatmap() { return heatmap; }, setHeatmapMethod, get measurements() { return measurements; }, get speedmap() { return speedmap; }, setSpeedmapMethod, get markers() { return markers; }, selfColour: kSelfColour,
    renderer, exporter, description: w, others, groupList, remoteJoints, gesture, setLook,
    get look() { return lookIndex; },
    /** Other participants as drawn last frame: name → the name of their look, null when drawn plainly. */
    otherLooks: () => Object.fromEntries([...others.values()].filter((o) => 'drawnLook' in o)
      .map((o) => [o.name ?? '?', o.drawnLook])),
    get worldModel() { return worldModel; },
    /** Draws the glTF world's own meshes (`on`) or the flat floors and obstacles; false without a model. */
    showWorldModel: (on) => { if (!worldModel) return false; showWorldModel(scene.getObjectByName('world'), worldModel, on); return true; },
    get joined() { return joined; },
    /** The world's named parts and how many segments each has (walls, railings, risers; 1 for others). */
    worldPart: (name) => scene.getObjectByName('world')?.getObjectByName(name) || null,
    /** The world's drawing (floors, walls, …): a test hides it to see a body alone. */
    worldRoot: () => scene.getObjectByName('world'),
    worldParts: () => Object.fromEntries((scene.getObjectByName('world')?.children || []).filter((c) => c.name)
      .map((c) => [c.name, c.userData.segments ?? 1])),
    /** Texts of the participants' name labels on screen. */
    labels: () => labels.visible('name-label'),
    screenLabels: labels,
    playGesture,
    /** Renders now and reads the canvas back: grey levels (0–255) every `step` px, for tests; with
     * `rgb`, also each sample's [r, g, b]. */
    pixels(step = 4, rgb = false) {
      renderer.render(scene, view());
      const gl = renderer.getContext();
      const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
      const buf = new Uint8Array(w * h * 4);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, buf);
      const grey = [], colours = [];
      for (let y = 0; y < h; y += step) {
        for (let x = 0; x < w; x += step) {
          const o = (y * w + x) * 4;
          grey.push(Math.round(0.299 * buf[o] + 0.587 * buf[o + 1] + 0.114 * buf[o + 2]));
          if (rgb) colours.push([buf[o], buf[o + 1], buf[o + 2]]);
        }
      }
      return rgb ? { width: w, height: h, step, grey, rgb: colours } : { width: w, height: h, step, grey };
    },
    /** Colour [r, g, b] (0–255) of the drawn pixel at screen point (x, y) [px], for tests. */
    rgbAt(x, y) {
      renderer.render(scene, view());
      const gl = renderer.getContext();
      const r = renderer.getPixelRatio();
      const buf = new Uint8Array(4);
      gl.readPixels(Math.round(x * r), gl.drawingBufferHeight - 1 - Math.round(y * r), 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, buf);
      return [buf[0], buf[1], buf[2]];
    },
    /** Screen position [px] of world point (x, y, z) in the current camera, or null behind it. */
    toScreen(x, y, z = 0.9) {
      view().updateMatrixWorld();  // a camera moved since the last frame projects where it is now
      return screenPoint(x, y, z);
    },
  };
}
// Groups formed after the start (populations that spawn later) are not in the world description:
// a live viewer asks /api/groups ([{id, population, members}], current membership) every 3 s, and
// stops asking when the server does not have it.
function pollGroups() {
  if (source.kind !== 'live' || !crowd) return;
  fetch('/api/groups').then((r) => (r.ok ? r.json() : Promise.reject(new Error(`HTTP ${r.status}`)))).then((j) => {
    const groups = Array.isArray(j) ? j : j.groups;
    if (!Array.isArray(groups)) return;
    crowd.setGroups(groups);
    groupList.setGroups(groups);
    description.groups = groups;
    refreshLegend();
    setTimeout(pollGroups, 3000);
  }).catch(() => {});
}
source.on('world', () => setTimeout(pollGroups, 1000));
source.on('presence', (p) => {
  if (!p.present) { others.delete(p.participantId); remoteJoints.delete(p.participantId); }
  else if (others.has(p.participantId)) others.get(p.participantId).name = p.name;
});

const panel = new AgentPanel($('agent-panel'), {
  onGuide: (g) => source.guide(g),
  onRelease: (g) => source.release(g),
  onClose: () => { selectedId = -1; if (crowd) crowd.selectedId = -1; },
});
const groupList = new GroupList($('controls'), {
  onSelect: (g) => { if (crowd) crowd.selectedGroup = g; },
  onGuide: (g) => source.guide(g),
  onRelease: (g) => source.release(g),
});
source.on('guide', (r) => {
  const what = r.guiding ? 'follows you' : 'released';
  const text = r.ok ? `group ${r.groupId} ${what}` : `group ${r.groupId}: ${reasonText(r.reason)}`;
  panel.guideResult(r, text);
  groupList.guideResult(r, text);
});
source.on('joined', (j) => {
  const again = joined !== null;  // re-joined after a reconnect: keep the avatar where it is
  joined = j;
  $('join-status').textContent = `joined as ${j.name || 'participant'} (#${j.participantId}); walk with W/S A/D, drag to turn`;
  $('join-button').textContent = 'Leave';
  panel.setJoined(true);
  groupList.setJoined(true);
  $('gesture-row').classList.remove('hidden');
  if (cameras && !again) {
    const t = cameras.mode === 'plan' ? cameras.plan.target : cameras.orbit.target;  // where the view is centred
    cameras.placeAvatar(t.x, -t.z, Math.PI / 2, t.y);
    setMode('walk');
  }
});
$('join-form').addEventListener('submit', (e) => {
  e.preventDefault();
  if (joined) {
    source.leave();
    joined = null;
    $('join-button').textContent = 'Join';
    $('join-status').textContent = 'left';
    panel.setJoined(false);
    groupList.setJoined(false);
    $('gesture-row').classList.add('hidden');
    return;
  }
  const name = $('join-name').value.trim() || 'visitor';
  $('join-status').textContent = `joining as ${name}…`;
  source.join(name, lookIndex);
});
// The avatar's look: the menu lists crowd/avatar_looks.js's; a change shows at once (also once joined).
for (const [i, l] of kAvatarLooks.entries()) $('join-look').add(new Option(l.name, String(i)));
/** Draws your avatar in look `i` (an index of kAvatarLooks) from now on, and remembers it. */
function setLook(i) {
  lookIndex = kAvatarLooks.indexOf(lookAt(i));
  $('join-look').value = String(lookIndex);
  saveLookChoice(globalThis.localStorage, lookIndex);
  if (joined) source.changeLook?.(lookIndex);  // others see it too (Join again: same participant)
}
setLook(lookIndex);
$('join-look').onchange = (e) => setLook(e.target.value);
function setMode(m) {
  if (!cameras) return;
  cameras.setMode(m);
  showMode();
}
/** Lights the current camera's button (also after a mode set by a script: cameras.lookAt). */
let shownMode = null;
function showMode() {
  if (shownMode === cameras.mode) return;
  shownMode = cameras.mode;
  for (const k of ['plan', 'orbit', 'walk']) $(`cam-${k}`).classList.toggle('active', shownMode === k);
}
/** Follows the selected agent, else the highlighted group's centre (its members in view), or
 * stops following; says which in the camera status line. */
function toggleFollow() {
  if (!cameras) return;
  if (cameras.following) { cameras.follow(null); followNote('stopped following'); return; }
  if (cameras.mode === 'walk') setMode('orbit');
  if (selectedId >= 0) {
    const id = selectedId;
    cameras.follow(() => {
      const i = state.index.get(id);
      return i === undefined ? null : { x: state.x[i], y: state.y[i], z: state.z[i] };
    });
    cameras.closeIn();
    followNote(`following agent #${id} (T stops)`);
  } else if (crowd && crowd.selectedGroup >= 0) {
    const g = crowd.selectedGroup;
    cameras.follow(() => groupCentre(g));
    cameras.closeIn();
    followNote(`following group ${g} (T stops)`);
  } else {
    followNote('select an agent (click) or a group first, then T follows it');
  }
}
function groupCentre(g) {
  const group = (description.groups || []).find((x) => x.id === g);
  let sx = 0, sy = 0, sz = 0, n = 0;
  for (const id of (group && group.members) || []) {
    const i = state.index.get(id);
    if (i === undefined) continue;
    sx += state.x[i]; sy += state.y[i]; sz += state.z[i]; n++;
  }
  return n ? { x: sx / n, y: sy / n, z: sz / n } : null;
}
function followNote(text) { $('camera-status').textContent = text; }
// Gestures of the local avatar: buttons, or keys 1–4 (not while typing in a field).
function playGesture(name) {
  if (!joined || !clips) return false;
  gesture.start(name, gestureClip(clips, name, description.skeleton.joints), performance.now());
  return true;
}
for (const b of document.querySelectorAll('#gesture-row button')) b.onclick = () => playGesture(b.dataset.gesture);
bindKeys({
  gesture: (e) => { const g = kGestures.find((x) => x.key === e.key); if (g) playGesture(g.name); },
  nextCamera: () => cameras && setMode(cameras.nextMode()),
  plan: () => setMode('plan'),
  orbit: () => setMode('orbit'),
  fit: () => fitView(),
  follow: () => toggleFollow(),
  labels: () => toggleLabels(),
  colourBy: () => crowd && setColourMode(kColourModes[(kColourModes.indexOf(crowd.colourMode) + 1) % kColourModes.length]),
  help: () => help.show(),
  trails: () => toggleTrails(),
  heatmap: () => toggleHeatmap(),
  speedmap: () => toggleSpeedmap(),
  screenshot: () => exporter.screenshot(),
  record: () => exporter.toggleRecording(),
  escape: () => { help.show(false); if (cameras && cameras.following) { cameras.follow(null); followNote('stopped following'); } select(-1); },
});
function fitView() {
  if (!cameras) return;
  if (cameras.mode === 'walk') setMode('orbit');
  cameras.follow(null);
  cameras.fit();
}
$('cam-plan').onclick = () => setMode('plan');
$('cam-orbit').onclick = () => setMode('orbit');
$('cam-walk').onclick = () => setMode('walk');
$('cam-fit').onclick = () => fitView();
$('agent-follow').onclick = () => { if (cameras) cameras.follow(null); toggleFollow(); };
$('lod-toggle').onchange = (e) => { if (crowd) crowd.adaptive = e.target.checked; };
// Replay: the in-memory demo recording, or a server replaying a recording (its first ReplayStatus).
let timeline = source.kind === 'replay' ? new Timeline($('timeline'), source) : null;
let recordingMarked = false;  // markRecording ran
source.on('timeline', (s) => {
  if (!timeline) { timeline = new Timeline($('timeline'), source); timeline.update(s); }
  markRecording();
});
if (timeline) markRecording();
/** A recording plays: the controls say what joining, editing and guiding do on one (a stand-in
 * newcomer took Join and Edit for ways to change what the crowd does). Served (throng serve), one
 * may join to walk among the recorded crowd with others watching it — the recorded people do not
 * react; played in the page alone there is nobody to join. Edit opens the scenario the recording
 * was made from. No group of a recording can be guided. */
function markRecording() {
  if (recordingMarked) return;  // ReplayStatus comes once a second: the controls are set once
  recordingMarked = true;
  const served = source instanceof LiveSource;  // a recording throng serve plays (kind 'replay' once it says so)
  $('join-button').disabled = !served;
  $('join-button').title = served ? 'walk among the recorded crowd, seen by others watching it (the recorded people do not react to you)'
    : 'nothing to join: this recording plays in this page alone (throng serve RECORDING lets others watch it with you)';
  if (!joined) {
    $('join-status').textContent = served ? 'a recording: joining lets you walk among it; the crowd does not react'
      : 'a recording played in this page: nobody to join';
  }
  $('edit-link').title = 'open the scenario this recording was made from in the editor (a new tab): change it, check it, preview it';
  panel.setRecording(true);
  groupList.setRecording(true);
}

// The selected agent's goal, state and Common Ground script: GET /api/agent/<id> (live server),
// once a second while its panel is open.
let agentInfo = null, agentInfoTimer = null;
function describeScript(script) {
  if (!script || !script.length) return '—';
  const role = ['A', 'B', 'companion'];
  return script.slice(-4).map((r) => `${role[r.role] ?? r.role}: step ${r.step} ${r.behaviour || r.motion || ''}`.trim()).join(' → ');
}
function fetchAgentInfo(id) {
  clearTimeout(agentInfoTimer);
  agentInfo = null;
  if (source.kind !== 'live' || id < 0) return;
  fetch(`/api/agent/${id}`).then((r) => (r.ok ? r.json() : r.status === 404 ? { gone: true } : null)).then((j) => {
    if (id !== selectedId) return;
    if (j && j.gone) { agentInfo = { goal: stateWords('left'), script: '—' }; return; }  // no more asking
    agentInfo = j && {
      goal: j.goal ? `${j.goal.point}${j.guided ? ' (guided)' : ''} — ${stateWords(j.state)}`.trim()
        : (j.guided ? 'guided' : stateWords(j.state) || '—'),
      script: describeScript(j.script),
    };
    agentInfoTimer = setTimeout(() => fetchAgentInfo(id), 1000);
  }).catch(() => {});
}

// Picking: a click (not a drag) selects the agent under the pointer.
const raycaster = new THREE.Raycaster();
let downAt = null;
renderer.domElement.addEventListener('pointerdown', (e) => { downAt = [e.clientX, e.clientY]; });
renderer.domElement.addEventListener('pointerup', (e) => {
  if (!downAt || !crowd || Math.hypot(e.clientX - downAt[0], e.clientY - downAt[1]) > 4) return;
  const ndc = new THREE.Vector2((e.clientX / innerWidth) * 2 - 1, -(e.clientY / innerHeight) * 2 + 1);
  raycaster.setFromCamera(ndc, view());
  // A zoomed-out plan view draws a body a few pixels wide: a click within 6 px of it still counts.
  const radius = cameras.mode === 'plan' ? Math.max(0.4, 6 * cameras.planMetresPerPixel(innerHeight)) : 0.4;
  const i = crowd.pick(raycaster.ray, state, radius);
  select(i >= 0 ? state.ids[i] : -1);
});
/** Selects agent `id` (−1: none): its panel, its goal from the server, its group in the list. */
function select(id) {
  if (!crowd) return;
  const i = id >= 0 ? state.index.get(id) : undefined;
  selectedId = i !== undefined ? id : -1;
  crowd.selectedId = selectedId;
  if (selectedId >= 0) {
    const g = crowd.groupOf.get(selectedId);
    panel.show(selectedId, g);
    fetchAgentInfo(selectedId);
    groupList.pick(g);
  } else {
    panel.hide();
  }
}

/** Participants' names (`tags`) and the points' labels, at their anchors on screen. Far labels
 * thin out: none beyond kLabelRange in 3D; a plan zoomed out under 2.5 px/m keeps the exits only. */
const kLabelRange = 80;  // [m]
function updateLabels(tags) {
  const cam = view();
  const { toScreen } = globalThis.__throng;
  const entries = tags.map((t) => ({ key: t.key, name: t.name, kind: 'name', importance: 10, screen: toScreen(t.at[0], t.at[1], (t.at[2] || 0) + 2.0) }));
  const plan = cam.isOrthographicCamera;
  const minImportance = plan && 1 / cameras.planMetresPerPixel(innerHeight) < 2.5 ? 3 : 0;
  for (const l of worldLabels) {
    if (l.importance < minImportance) continue;
    const distance = plan ? 0 : Math.hypot(cam.position.x - l.at[0], cam.position.y - l.at[2], cam.position.z + l.at[1]);
    if (distance > kLabelRange) continue;
    entries.push({ ...l, distance, screen: toScreen(l.at[0], l.at[1], l.at[2]) });
  }
  labels.update(entries);
}
function toggleLabels(on = !labels.showPoints) {
  labels.showPoints = on;
  $('labels-toggle').checked = on;
}
$('labels-toggle').onchange = (e) => toggleLabels(e.target.checked);
function toggleTrails(on = !(trails && trails.enabled)) {
  if (!trails) return;
  trails.enabled = on;
  $('trails-toggle').checked = on;
  legend.trails = on;
  refreshLegend();
}
$('trails-toggle').onchange = (e) => toggleTrails(e.target.checked);
function toggleHeatmap(on = !(heatmap && heatmap.enabled)) {
  if (!heatmap) return;
  heatmap.enabled = on;
  $('heatmap-toggle').checked = on;
  legend.heatmap = on && heatmapMethod;
  refreshLegend();
}
/** The density map's definition: 'classic' (DensityGrid) or 'voronoi' (VoronoiDensityGrid). */
function setHeatmapMethod(method) {
  if (!heatmap || (method !== 'classic' && method !== 'voronoi')) return;
  heatmapMethod = method;
  $('heatmap-method').value = method;
  heatmap.setGrid(method === 'voronoi' ? new VoronoiDensityGrid(heatmapBounds, heatmapScenario) : new DensityGrid(heatmapBounds));
  if (heatmap.enabled) { legend.heatmap = method; refreshLegend(); }
}
$('heatmap-method').onchange = (e) => { setHeatmapMethod(e.target.value); setSpeedmapMethod(e.target.value); };
$('heatmap-toggle').onchange = (e) => toggleHeatmap(e.target.checked);
function toggleSpeedmap(on = !(speedmap && speedmap.enabled)) {
  if (!speedmap) return;
  speedmap.enabled = on;
  $('speedmap-toggle').checked = on;
  legend.speedmap = on && speedmapMethod;
  refreshLegend();
}
$('speedmap-toggle').onchange = (e) => toggleSpeedmap(e.target.checked);
/** The speed map's definition: 'classic' (SpeedGrid) or 'voronoi' (VoronoiSpeedGrid). */
function setSpeedmapMethod(method) {
  if (!speedmap || (method !== 'classic' && method !== 'voronoi')) return;
  speedmapMethod = method;
  speedmap.setGrid(method === 'voronoi' ? new VoronoiSpeedGrid(heatmapBounds, heatmapScenario) : new SpeedGrid(heatmapBounds));
  if (speedmap.enabled) { legend.speedmap = method; refreshLegend(); }
}

// Export (ui/export.js): the view as PNG (K) or WebM (V starts / stops; the indicator shows meanwhile).
const exporter = new Exporter(renderer.domElement, () => renderer.render(scene, view()), () => hud.world?.name || '',
  $('rec-indicator'), (on) => { $('export-rec').classList.toggle('active', on); $('export-rec').textContent = on ? 'Stop' : 'Rec'; });
$('export-png').onclick = () => exporter.screenshot();
$('export-rec').onclick = () => exporter.toggleRecording();

let last = performance.now();
function frame() {
  requestAnimationFrame(frame);
  const nowMs = performance.now();
  const frameMs = nowMs - last;
  last = nowMs;
  if (!crowd) { renderer.render(scene, view()); return; }
  const dt = Math.min(frameMs / 1000, 0.1);
  refitForPanels(nowMs);
  cameras.update(dt);
  showMode();
  state.advance(nowMs / 1000);
  // Levels from the full-resolution height; the budget's render scale (dynamic resolution) is
  // applied after, for the next frame's drawing buffer (only when it moved by 5 % or more).
  const counts = crowd.update(state, view(), innerHeight * basePixelRatio, frameMs, renderer.domElement.height);
  const wantRatio = basePixelRatio * (crowd.adaptive && !shot ? crowd.params.renderScale : 1);  // screenshots: full resolution
  if (Math.abs(wantRatio - renderer.getPixelRatio()) > 0.05 * basePixelRatio || (wantRatio === basePixelRatio && renderer.getPixelRatio() !== basePixelRatio)) {
    renderer.setPixelRatio(wantRatio);
  }
  avatars.begin();
  const walk = clips.walkClipId(), idle = clips.idleClipId();
  const tags = [];
  if (joined) {
    const a = cameras.avatar;
    localPhase.phase = (localPhase.phase + (a.speed * dt) / 1.5) % 1;
    const g = gesture.sample(nowMs);
    avatars.add(a.x, a.y, a.z, a.yaw, a.moving ? walk : idle, a.moving ? localPhase.phase : (nowMs / 2000) % 1, lookAt(lookIndex),
      g ? g.angles : null);
    source.sendMove(a.x, a.y, a.z, a.yaw);  // z: the floor it stands on (0 in a flat world)
    if (g && g.send && source.sendJoints) source.sendJoints(g.angles);
    tags.push({ key: 'self', name: joined.name || 'you', at: [a.x, a.y, a.z] });
  }
  // Every participant present is drawn, however long since it last moved: a viewer in a background
  // tab sends no moves (no animation frames) but its heartbeats keep it present, and the server
  // announces whoever leaves or falls silent (Presence, its heartbeat timeout).
  for (const [id, o] of others) {
    o.phase = (o.phase + (o.moving ? dt / 1.12 : dt / 2)) % 1;
    const look = source.looks?.get(id);  // the look they chose (Presence); magenta when the server did not say
    o.drawnLook = look === undefined ? null : lookAt(look).name;
    avatars.add(o.x, o.y, o.z, o.yaw, o.moving ? walk : idle, o.phase, look === undefined ? kOtherColour : lookAt(look),
      remoteJoints.get(id, nowMs));
    tags.push({ key: id, name: o.name || source.names?.get(id) || `participant ${id}`, at: [o.x, o.y, o.z] });
  }
  avatars.end();
  if (trailsStale) {
    trailsStale = false;
    trails.rebuild((id) => { const i = state.index.get(id); return i === undefined ? crowd.colour(0x9a9a9a) : crowd.colourAt(i, state); });
  }
  if (heatmap) heatmap.update();
  if (speedmap) speedmap.update();
  if (measurePanel) measurePanel.update(nowMs);
  const sel = selectedId >= 0 ? state.index.get(selectedId) : undefined;
  markers.update(joined ? cameras.avatar : null, sel === undefined ? null : { x: state.x[sel], y: state.y[sel], z: state.z[sel] },
    cameras.mode === 'plan' ? cameras.planMetresPerPixel(innerHeight) : 0);
  updateLabels(tags);
  renderer.render(scene, view());
  hud.tick(source, counts, state.count, crowd.adaptive ? crowd.params : { adaptive: false });
  globalThis.__throngStats.crowdFrames = state.frames;
  globalThis.__throngStats.others = others.size;
  globalThis.__throngStats.jointsReceived = remoteJoints.received;
  let legendRoom = '';
  if (selectedId >= 0) {
    const i = state.index.get(selectedId);
    if (i !== undefined) {
      panel.update({ clipName: clips.name(state.clip[i]), x: state.x[i], y: state.y[i], z: state.z[i], tier: state.tier[i],
        goal: agentInfo ? agentInfo.goal : undefined, script: agentInfo ? agentInfo.script : undefined });
      const side = panel.keepClear(screenPoint(state.x[i], state.y[i], state.z[i] + 0.9), $('hud').getBoundingClientRect().bottom, innerWidth);
      // Moved to the left, the panel stands over the legend's corner: the legend keeps to the room below it.
      if (side === 'left') legendRoom = `${Math.max(60, innerHeight - $('agent-panel').getBoundingClientRect().bottom - 20)}px`;
    } else {
      panel.gone();
    }
  }
  if ($('legend').style.maxHeight !== legendRoom) $('legend').style.maxHeight = legendRoom;
}
/** Screen position [px] of world point (x, y, z) in the current view, or null behind the camera. */
const screenScratch = new THREE.Vector3();
function screenPoint(x, y, z) {
  const v = screenScratch.set(x, z, -y).project(view());
  return v.z > 1 ? null : { x: (v.x + 1) / 2 * innerWidth, y: (1 - v.y) / 2 * innerHeight };
}
requestAnimationFrame(frame);
source.start();
