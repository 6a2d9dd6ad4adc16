// The crowd on screen: each frame, from the interpolated crowd state (interpolate.js) and the
// camera, computes every agent's projected size, asks the global LOD function (lod.js) for its
// level within the frame-time budget, and fills the three renderers: skinned bodies (near),
// instanced low-polygon bodies (middle), billboards (far), dots (a few pixels high). Seen from an
// orthographic plan camera, every agent is a disc with its heading instead (plan_discs.js). Also:
// colours by group, picking (camera/pick.js: a ray against an upright capsule per agent, from any
// angle), and the counts for the HUD.
import * as THREE from 'three';
import { Level, assignLevels, makeLodScratch, projectedHeight, LodBudget, defaultLodParams } from '../lod.js';
import { NearBodies } from './near_bodies.js';
import { MiddleBodies } from './middle_bodies.js';
import { Billboards, renderAtlas, kWalkFrames } from './billboards.js';
import { Dots } from './dots.js';
import { PlanDiscs } from './plan_discs.js';
import { pickAgent } from '../camera/pick.js';
import { sceneYaw } from '../coords.js';

const kPalette = [0x3f7fbf, 0xbf5f3f, 0x4f9f5f, 0x9f4fa0, 0xc0a040, 0x40a0a8, 0x8f6f4f, 0x707fa0, 0xb0607a, 0x6a8f30];

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
    this.setGroups(description.groups || []);
    this.colors = kPalette.map((c) => new THREE.Color(c));
    this.highlight = new THREE.Color(0xffe040);
    this.adaptive = options.adaptive !== false;
    this.budget = new LodBudget({ targetFrameMs: options.targetFrameMs || 1000 / 30 });
    this.levels = new Uint8Array(0);
    this.prevLevels = new Uint8Array(0);
    this.prevIds = new Uint32Array(0);
    this.sizes = new Float32Array(0);
    this.scratch = makeLodScratch(1024);
    this.counts = { near: 0, middle: 0, far: 0, dot: 0, hidden: 0 };
    this.selectedId = -1;
    this.selectedGroup = -1;  // group picked in the group list: its members are highlighted
    this.groupHighlight = new THREE.Color(0xff9a20);
    this.guidedGroups = new Set();
    this.frustum = new THREE.Frustum();
    this.m = new THREE.Matrix4();
    this.sphere = new THREE.Sphere(new THREE.Vector3(), 1.1);
  }

  /** Group membership: [{id, members}] (agent ids). */
  setGroups(groups) {
    this.groupOf = new Map();
    for (const g of groups) for (const m of g.members || []) this.groupOf.set(m, g.id);
  }

  colorOf(id) {
    if (id === this.selectedId) return this.highlight;
    const g = this.groupOf.get(id);
    if (g !== undefined && g === this.selectedGroup) return this.groupHighlight;
    return this.colors[(g === undefined ? id : g) % this.colors.length];
  }

  /** Draws `state` (CrowdState, already advanced) from `camera` in a viewport `height` px high
   * (at full resolution: the levels do not change with the render scale); `bufferHeight`: the
   * drawing buffer's height [px] (for the dots' size), `height` when omitted. */
  update(state, camera, height, frameMs, bufferHeight = height) {
    const n = state.count;
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
    this.counts = assignLevels(this.sizes, n, prev, this.levels, params, this.scratch);
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
      const color = this.colorOf(id);
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
      this.discs.add(state.x[i], state.z[i], -state.y[i], state.yaw[i], this.colorOf(state.ids[i]));
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
