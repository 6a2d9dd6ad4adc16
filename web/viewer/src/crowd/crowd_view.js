// The crowd on screen: each frame, from the interpolated crowd state (interpolate.js) and the
// camera, computes every agent's projected size, asks the global LOD function (lod.js) for its
// level within the frame-time budget (the selected agent and the nearest few always full bodies), and fills the three renderers: skinned bodies (near),
// instanced low-polygon bodies (middle), billboards (far), dots (a few pixels high). Seen from an
// orthographic plan camera, every agent is a disc with its heading instead (plan_discs.js). Also:
// each agent's colour by the chosen mode (colour_by.js: group, population, speed, local density,
// state; the selected agent yellow, the picked group lime, over any mode), picking (camera/pick.js: a ray against an upright capsule per agent, from any
// angle), and the counts for the HUD.
import * as THREE from 'three';
import { Level, assignLevels, makeLodScratch, projectedHeight, LodBudget, defaultLodParams } from '../lod.js';
import { NearBodies } from './near_bodies.js';
import { MiddleBodies } from './middle_bodies.js';
import { Billboards, renderAtlas, kWalkFrames } from './billboards.js';
import { Dots } from './dots.js';
import { PlanDiscs, kUpperFloor } from './plan_discs.js';
import { pickAgent } from '../camera/pick.js';
import { sceneYaw } from '../coords.js';
import { kGroupPalette, kNoGroup, kSpeedMax, kDensityMax, kStateColours, rampColour, stateOf, localDensity, GroupColours } from './colour_by.js';

export const kSelectedColour = 0xffe040;  // the clicked agent (and its ring)
export const kPickedGroupColour = 0xb4f000;  // the members of the group picked in the list

export class CrowdView {
  constructor(scene, renderer, description, clips, options = {}) {
    this.scene = scene;
    this.clips = clips;
    this.joints = description.skeleton.joints;
    this.near = new NearBodies(scene, this.joints, clips);
    this.middle = new MiddleBodies(scene, this.joints);
    this.atlas = renderAtlas(renderer, this.joints, this.near.geometry, clips);
    this.far = new Billboards(scene, this.atlas.texture);
    this.dots = new Dots(scene);
    this.discs = new PlanDiscs(scene);
    // A multi-level world (terrain): the plan marks who is on an upper floor (plan_discs.js).
    this.multiLevel = !!(description.scenario && description.scenario.terrain);
    this.groundZ = 0;  // the lowest floor's height [m] (setGround)
    this.populations = ((description.scenario || {}).populations || []).map((p) => p.id).filter(Boolean);
    this.groupColours = new GroupColours();  // groups side by side wear different colours (colour_by.js)
    this.groupColoursAt = -1;  // the crowd frame they were last handed out at
    this.onGroupColours = null;  // called when a group's colour changed (the legend, the trails)
    this.setGroups(description.groups || []);
    this.colourMode = 'group';
    this.colourCache = new Map();  // 0xRRGGBB → THREE.Color
    this.density = new Float32Array(0);
    this.densityFrame = -1;
    this.highlight = this.colour(kSelectedColour);
    this.adaptive = options.adaptive !== false;
    this.budget = new LodBudget({ targetFrameMs: options.targetFrameMs || 1000 / 30 });
    this.levels = new Uint8Array(0);
    this.prevLevels = new Uint8Array(0);
    this.prevIds = new Uint32Array(0);
    this.sizes = new Float32Array(0);
    this.scratch = makeLodScratch(1024);
    this.pinned = [-1];  // agent indices always Near when on screen: the selected one
    this.counts = { near: 0, middle: 0, far: 0, dot: 0, hidden: 0 };
    this.selectedId = -1;
    this.selectedGroup = -1;  // group picked in the group list: its members are highlighted
    this.groupHighlight = this.colour(kPickedGroupColour);
    this.guidedGroups = new Set();
    this.frustum = new THREE.Frustum();
    this.m = new THREE.Matrix4();
    this.sphere = new THREE.Sphere(new THREE.Vector3(), 1.1);
  }

  /** Group membership: [{id, members, population, waiting}] (agent ids; population and waiting
   * as /api/groups gives them, when known). */
  setGroups(groups) {
    this.groupOf = new Map();
    this.populationOfGroup = new Map();
    this.waitingGroups = new Set();
    for (const g of groups) {
      for (const m of g.members || []) this.groupOf.set(m, g.id);
      if (g.population) {
        this.populationOfGroup.set(g.id, g.population);
        if (!this.populations.includes(g.population)) this.populations.push(g.population);
      }
      if (g.waiting) this.waitingGroups.add(g.id);
    }
  }

  /** The shared THREE.Color of 0xRRGGBB. */
  colour(hex) {
    let c = this.colourCache.get(hex);
    if (!c) { c = new THREE.Color(hex); this.colourCache.set(hex, c); }
    return c;
  }

  /** Colour of agent i of `state` in the current mode (the selection and the picked group first). */
  colourAt(i, state) {
    const id = state.ids[i];
    if (id === this.selectedId) return this.highlight;
    const g = this.groupOf.get(id);
    if (g !== undefined && g === this.selectedGroup) return this.groupHighlight;
    switch (this.colourMode) {
      case 'population': {
        const k = g === undefined ? -1 : this.populations.indexOf(this.populationOfGroup.get(g));
        return this.colour(k < 0 ? kNoGroup : kGroupPalette[k % kGroupPalette.length]);
      }
      case 'speed': return this.colour(rampColour(state.speed[i] / kSpeedMax));
      case 'density': return this.colour(rampColour(this.density[i] / kDensityMax));
      case 'state': {
        const clip = state.tier[i] === 2 ? '' : this.clips.name(state.clip[i]);
        return this.colour(kStateColours[stateOf(clip, state.speed[i], g !== undefined && this.waitingGroups.has(g))]);
      }
      default: return this.colour(g === undefined ? kGroupPalette[id % kGroupPalette.length] : kGroupPalette[this.groupColours.index(g)]);
    }
  }

  /** Per frame, before colourAt: local densities once per received crowd frame (density mode). */
  prepareColours(state) {
    // Groups first seen get their colours with each crowd frame received (kept for good after).
    if (state.count > 0 && state.frames !== this.groupColoursAt) {
      this.groupColoursAt = state.frames;
      if (this.groupColours.update(state.ids, state.toX, state.toY, state.count, this.groupOf) > 0 && this.onGroupColours) {
        this.onGroupColours();
      }
    }
    if (this.colourMode !== 'density' || this.densityFrame === state.frames) return;
    this.densityFrame = state.frames;
    this.density = localDensity(state.toX, state.toY, state.count);
  }

  /** Draws `state` (CrowdState, already advanced) from `camera` in a viewport `height` px high
   * (at full resolution: the levels do not change with the render scale); `bufferHeight`: the
   * drawing buffer's height [px] (for the dots' size), `height` when omitted. */
  update(state, camera, height, frameMs, bufferHeight = height) {
    const n = state.count;
    this.prepareColours(state);
    if (camera.isOrthographicCamera) return this.updatePlan(state, camera, bufferHeight);
    this.discs.begin(0, 1); this.discs.end();
    if (this.sizes.length < n) {
      this.sizes = new Float32Array(n * 2); this.levels = new Uint8Array(n * 2);
    }
    // Previous levels, re-indexed to this frame's agent order (agents come and go).
    const prev = new Uint8Array(n).fill(Level.Far);
    if (this.prevIds.length) {
      const pi = this.prevIndex || new Map();
      for (let i = 0; i < n; ++i) { const j = pi.get(state.ids[i]); if (j !== undefined) prev[i] = this.prevLevels[j]; }
    }
    camera.updateMatrixWorld();
    this.m.multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
    this.frustum.setFromProjectionMatrix(this.m);
    const fov = THREE.MathUtils.degToRad(camera.fov);
    const cx = camera.position.x, cy = camera.position.y, cz = camera.position.z;
    for (let i = 0; i < n; ++i) {
      const sx = state.x[i], sy = state.z[i], sz = -state.y[i];
      this.sphere.center.set(sx, sy + 0.9, sz);
      if (!this.frustum.intersectsSphere(this.sphere)) { this.sizes[i] = -1; continue; }
      const d = Math.hypot(sx - cx, sy + 0.9 - cy, sz - cz);
      this.sizes[i] = projectedHeight(d, fov, height);
    }
    const params = this.adaptive ? this.budget.update(frameMs, this.counts) : { ...defaultLodParams, adaptive: false };
    this.params = params;
    // The selected agent stays a full body whatever the budget (as do the nearest few: lod.js).
    const selected = this.selectedId >= 0 && state.index ? state.index.get(this.selectedId) : undefined;
    this.pinned[0] = selected === undefined ? -1 : selected;
    this.counts = assignLevels(this.sizes, n, prev, this.levels, params, this.scratch, this.pinned);
    const walkClip = this.clips.walkClipId(), idleClip = this.clips.idleClipId();
    this.near.begin();
    this.middle.begin(n);
    this.far.begin(n);
    this.dots.begin(n, bufferHeight / (2 * Math.tan(fov / 2)));
    for (let i = 0; i < n; ++i) {
      const l = this.levels[i];
      if (l === Level.Hidden) continue;
      const id = state.ids[i];
      // Far-tier data has no clip: walk when it moves, idle when it stands (see interpolate.js).
      const c = state.tier[i] === 2 ? (state.speed[i] > 0.25 ? walkClip : idleClip) : state.clip[i];
      const color = this.colourAt(i, state);
      if (l === Level.Near) {
        this.near.add(state.x[i], state.y[i], state.z[i], state.yaw[i], c, state.phase[i], color.getHex(), state.tier[i] === 0 ? state.joints.get(id) : null);
      } else if (l === Level.Middle) {
        this.middle.add(state.x[i], state.y[i], state.z[i], state.yaw[i], state.phase[i], this.clips.isWalk(c), color);
      } else if (l === Level.Dot) {
        this.dots.add(state.x[i], state.z[i], -state.y[i], color);
      } else {
        const row = this.clips.isWalk(c) ? Math.floor(state.phase[i] * kWalkFrames) % kWalkFrames : kWalkFrames;
        this.far.add(state.x[i], state.z[i], -state.y[i], sceneYaw(state.yaw[i]), row, color);
      }
    }
    this.near.end(); this.middle.end(); this.far.end(); this.dots.end();
    this.prevLevels = this.levels.slice(0, n);
    this.prevIds = state.ids;
    this.prevIndex = state.index;
    return this.counts;
  }

  /** The lowest floor's height [m]: agents kUpperFloor above it are on an upper floor. */
  setGround(z) { this.groundZ = Number.isFinite(z) ? z : 0; }

  /** Plan view: every agent in the orthographic camera's view as a disc; no levels of detail. */
  updatePlan(state, camera, bufferHeight) {
    const n = state.count;
    this.near.begin(); this.near.end();
    this.middle.begin(0); this.middle.end();
    this.far.begin(0); this.far.end();
    this.dots.begin(0, 1); this.dots.end();
    const pxPerMetre = bufferHeight * camera.zoom / (camera.top - camera.bottom);
    this.discs.begin(n, pxPerMetre);
    for (let i = 0; i < n; ++i) {
      const upper = this.multiLevel && state.z[i] > this.groundZ + kUpperFloor;
      this.discs.add(state.x[i], state.z[i], -state.y[i], state.yaw[i], this.colourAt(i, state), upper);
    }
    this.discs.end();
    this.prevIds = new Uint32Array(0);  // the next perspective frame chooses its levels afresh
    this.params = this.adaptive ? this.budget.params() : { ...defaultLodParams, adaptive: false };
    this.counts = { near: 0, middle: 0, far: 0, dot: 0, plan: n, hidden: 0 };
    return this.counts;
  }

  /** Agent index under the ray (an upright capsule per agent, `radius` [m] around its axis), or −1. */
  pick(ray, state, radius = 0.4) { return pickAgent(ray, state, radius); }
}
