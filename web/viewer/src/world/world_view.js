// The static world from the scenario JSON (docs/scenario-format.md) as the world description
// carries it: walkable polygons as floors, obstacles and the scenario's `walls` (wallRectangles)
// extruded as solid blocks, its `measurements` as purple lines and outlines on the floor, walls along the
// walkable area's boundary (walls.js: kBoundaryWallHeight high, semi-transparent, with a dark line
// along their top that reads as the wall in plan view), points as markers —
// interest (blue ring), action (orange disc with an arrow along its orientation), exit (green
// area); where their name labels go (pointLabels: drawn at a fixed screen size by
// ui/screen_labels.js); lights. World (x, y) → scene (x, 0, −y).
// A multi-level world (`scenario.terrain`: vertices [x, y, z], walkable and obstacle triangles)
// is drawn from its triangles instead — walkable ones as the floor, obstacle ones as walls, stair
// risers where a step drops to the one below, railings where a floor, gallery or stair ends — with
// world (x, y, z) → scene (x, z, −y); points stand at their height (`position[2]`, or `height`).
// Lifts and escalators (`scenario.transports`) are drawn between their stops: a belt with handrails,
// a glass shaft.
// Floors and obstacles carry userData.flat: a glTF world's own meshes, with their materials, replace
// them (gltf_materials.js).
import * as THREE from 'three';
import { terrainBounds } from './terrain.js';
import { exhibitsOnWalls, polygonEdges, terrainWalls, walkableWalls, wallRectangles } from './walls.js';

const kWallHeight = 2.4;  // [m] obstacles (shops' blocks, pillars, kiosks)
/** Height [m] of the walls along the walkable boundary and of railings: waist to chest high, so
 * that an oblique view sees the crowd over them (Neufert: railings 0.9–1.1 m; a low wall). */
export const kBoundaryWallHeight = 1.2;
const kBoundaryWallColour = 0x9c8f7a;
const kBoundaryTopColour = 0x5a5145;
const kRiserColour = 0xa8a296;

function shapeOf(polygon) {
  const s = new THREE.Shape();
  polygon.forEach(([x, y], i) => (i === 0 ? s.moveTo(x, y) : s.lineTo(x, y)));
  return s;
}

function centroid(polygon) {
  let x = 0, y = 0;
  for (const p of polygon) { x += p[0]; y += p[1]; }
  return [x / polygon.length, y / polygon.length];
}

/** Height [m] a point of the scenario stands at: `position[2]`, else `height`, else the mean z of
 * its polygon's [x, y, z] vertices, else 0. */
export function pointHeight(p) {
  if (p.position && Number.isFinite(p.position[2])) return p.position[2];
  if (Number.isFinite(p.height)) return p.height;
  if (Array.isArray(p.polygon) && p.polygon.length && p.polygon.every((q) => Number.isFinite(q[2]))) {
    return p.polygon.reduce((s, q) => s + q[2], 0) / p.polygon.length;
  }
  return 0;
}

/** Bounds of the walkable area and the terrain's vertices: {minX, minY, maxX, maxY, minZ, maxZ}
 * [m] (minZ = maxZ = 0 in a flat world; −10 … 10 on the ground when the scenario has neither). */
export function worldBounds(scenario) {
  const b = { minX: Infinity, minY: Infinity, maxX: -Infinity, maxY: -Infinity, minZ: 0, maxZ: 0 };
  for (const poly of scenario.walkable || []) {
    for (const [x, y] of poly) {
      b.minX = Math.min(b.minX, x); b.minY = Math.min(b.minY, y);
      b.maxX = Math.max(b.maxX, x); b.maxY = Math.max(b.maxY, y);
    }
  }
  const t = terrainBounds(scenario.terrain);
  if (t) {
    b.minX = Math.min(b.minX, t.minX); b.minY = Math.min(b.minY, t.minY);
    b.maxX = Math.max(b.maxX, t.maxX); b.maxY = Math.max(b.maxY, t.maxY);
    b.minZ = Math.min(b.minZ, t.minZ); b.maxZ = Math.max(b.maxZ, t.maxZ);
    if (!(scenario.walkable || []).length) { b.minZ = t.minZ; b.maxZ = t.maxZ; }
  }
  if (!Number.isFinite(b.minX)) Object.assign(b, { minX: -10, minY: -10, maxX: 10, maxY: 10 });
  return b;
}

/** Non-indexed scene geometry of the triangles `faces` ([[i, j, k]] into the terrain's vertices),
 * with flat normals; null when there are none. */
function triangleGeometry(vertices, faces) {
  const pos = [];
  for (const f of faces || []) {
    const a = vertices[f[0]], b = vertices[f[1]], c = vertices[f[2]];
    if (!a || !b || !c) continue;
    for (const v of [a, b, c]) pos.push(v[0], v[2] ?? 0, -v[1]);
  }
  if (!pos.length) return null;
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(pos, 3));
  g.computeVertexNormals();
  return g;
}

/** Line segments (scene positions) along the edges used by exactly one walkable triangle. */
function boundaryEdges(vertices, faces) {
  const count = new Map();
  for (const f of faces || []) {
    for (let e = 0; e < 3; ++e) {
      const i = f[e], j = f[(e + 1) % 3];
      if (!vertices[i] || !vertices[j]) continue;
      const key = i < j ? `${i},${j}` : `${j},${i}`;
      count.set(key, (count.get(key) || 0) + 1);
    }
  }
  const pos = [];
  for (const [key, n] of count) {
    if (n !== 1) continue;
    for (const i of key.split(',').map(Number)) {
      const v = vertices[i];
      pos.push(v[0], (v[2] ?? 0) + 0.01, -v[1]);
    }
  }
  return pos;
}

/** Non-indexed scene geometry of vertical quads: each of `quads` is [x0, y0, x1, y1, zBottom0,
 * zBottom1, zTop0, zTop1] (world metres). */
function quadGeometry(quads) {
  const pos = new Float32Array(quads.length * 18);
  let o = 0;
  for (const [x0, y0, x1, y1, b0, b1, t0, t1] of quads) {
    for (const [x, y, z] of [[x0, y0, b0], [x1, y1, b1], [x1, y1, t1], [x0, y0, b0], [x1, y1, t1], [x0, y0, t0]]) {
      pos[o++] = x; pos[o++] = z; pos[o++] = -y;
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  g.computeVertexNormals();
  return g;
}

/** Walls [{x0, y0, z0, x1, y1, z1}] (z: the floor under each end) as one group named `name`:
 * semi-transparent quads kBoundaryWallHeight high and a dark line along their top (what a plan
 * view sees). userData.segments: how many. */
export function wallObject(walls, name) {
  const group = new THREE.Group();
  group.name = name;
  group.userData.segments = walls.length;
  const quads = walls.map((w) => [w.x0, w.y0, w.x1, w.y1, w.z0 ?? 0, w.z1 ?? 0, (w.z0 ?? 0) + kBoundaryWallHeight, (w.z1 ?? 0) + kBoundaryWallHeight]);
  const mesh = new THREE.Mesh(quadGeometry(quads), new THREE.MeshLambertMaterial({
    color: kBoundaryWallColour, transparent: true, opacity: 0.55, side: THREE.DoubleSide, depthWrite: false }));
  mesh.renderOrder = 1;  // after the opaque floor and crowd, so the crowd shows through
  group.add(mesh);
  const top = [];
  for (const q of quads) top.push(q[0], q[6], -q[1], q[2], q[7], -q[3]);
  const lines = new THREE.BufferGeometry();
  lines.setAttribute('position', new THREE.Float32BufferAttribute(top, 3));
  group.add(new THREE.LineSegments(lines, new THREE.LineBasicMaterial({ color: kBoundaryTopColour })));
  return group;
}

/** The scenario's measurement lines ({line: [[x, y], [x, y]]}) and areas ({polygon}) as purple
 * lines 3 cm above the floor, one group named 'measurements' (userData.count: how many). */
function measurementObject(measurements) {
  const pts = [];
  for (const m of measurements) {
    const ring = m.line || m.polygon || [];
    const n = m.line ? ring.length - 1 : ring.length;
    for (let i = 0; i < n; ++i) {
      const [x0, y0] = ring[i], [x1, y1] = ring[(i + 1) % ring.length];
      pts.push(x0, 0.03, -y0, x1, 0.03, -y1);
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(pts, 3));
  const lines = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0x8a3ab9 }));
  lines.name = 'measurements';
  lines.userData.count = measurements.length;
  return lines;
}

/** A string's 32-bit FNV-1a hash (an exhibit's colours from its point's id: the same every time). */
function hashOf(text) {
  let h = 0x811c9dc5;
  for (let i = 0; i < text.length; ++i) h = Math.imul(h ^ text.charCodeAt(i), 0x01000193) >>> 0;
  return h;
}

/** An abstract picture for exhibit `id` on a 2D canvas context (w × h px): a ground and a few
 * shapes in colours drawn from the id's hash. Returns the ground's colour (the plan view's mark). */
function paintPicture(ctx, id, w, h) {
  let s = hashOf(id) || 1;
  const next = () => { s ^= s << 13; s >>>= 0; s ^= s >>> 17; s ^= s << 5; s >>>= 0; return s / 4294967296; };
  const hsl = (l) => `hsl(${Math.floor(next() * 360)}, ${45 + Math.floor(next() * 35)}%, ${l}%)`;
  const ground = hsl(35 + Math.floor(next() * 25));
  ctx.fillStyle = ground;
  ctx.fillRect(0, 0, w, h);
  for (let k = 0; k < 5; ++k) {
    ctx.fillStyle = hsl(25 + Math.floor(next() * 50));
    const x = next() * w, y = next() * h, r = (0.1 + 0.25 * next()) * h;
    ctx.beginPath();
    if (next() < 0.5) ctx.arc(x, y, r, 0, 2 * Math.PI); else ctx.rect(x - r, y - r * 0.6, 2 * r, 1.2 * r);
    ctx.fill();
  }
  return ground;
}

/** What visitors look at (walls.js exhibitsOnWalls): a framed picture on the wall, its bottom
 * kExhibitBottom above the floor, and under it on the floor a strip in the picture's ground colour
 * (a plan view sees the wall edge-on). One group named 'exhibits' (userData.segments: how many). */
const kExhibitBottom = 0.2;  // [m] low enough that the picture's top stays under the 1.2 m wall's
function exhibitObject(exhibits) {
  const group = new THREE.Group();
  group.name = 'exhibits';
  group.userData.segments = exhibits.length;  // how many (worldParts)
  const frameMat = new THREE.MeshLambertMaterial({ color: 0x4a3520, side: THREE.DoubleSide });
  for (const e of exhibits) {
    const w = e.width, h = 0.7 * w, z = pointHeight(e.point);
    const canvas = document.createElement('canvas');
    canvas.width = 96; canvas.height = 68;
    const ground = paintPicture(canvas.getContext('2d'), String(e.point.id ?? ''), canvas.width, canvas.height);
    const yaw = Math.atan2(e.nx, -e.ny);  // about Y: a plane's +Z normal onto the scene's (nx, 0, −ny)
    const place = (mesh, out, up) => {
      mesh.position.set(e.x + e.nx * out, z + up, -(e.y + e.ny * out));
      mesh.rotation.y = yaw;
      group.add(mesh);
    };
    place(new THREE.Mesh(new THREE.PlaneGeometry(w + 0.12, h + 0.12), frameMat), 0, kExhibitBottom + h / 2);
    const picture = new THREE.Mesh(new THREE.PlaneGeometry(w, h), new THREE.MeshBasicMaterial({ map: new THREE.CanvasTexture(canvas) }));
    picture.userData.point = e.point.id;
    place(picture, 0.01, kExhibitBottom + h / 2);
    const strip = new THREE.Mesh(new THREE.PlaneGeometry(w, 0.14), new THREE.MeshBasicMaterial({ color: new THREE.Color(ground) }));
    strip.rotation.order = 'YXZ';
    place(strip, 0.07, 0.03);
    strip.rotation.x = -Math.PI / 2;  // lying on the floor along the wall
  }
  return group;
}

/** Stair risers [{x0, y0, x1, y1, zLow, zHigh}] as one opaque mesh named 'stair-risers'. */
function riserObject(risers) {
  const mesh = new THREE.Mesh(quadGeometry(risers.map((r) => [r.x0, r.y0, r.x1, r.y1, r.zLow, r.zLow, r.zHigh, r.zHigh])),
    new THREE.MeshLambertMaterial({ color: kRiserColour, side: THREE.DoubleSide }));
  mesh.name = 'stair-risers';
  mesh.userData.segments = risers.length;
  return mesh;
}

function addTerrain(root, terrain, floorColor, wallMat) {
  const vertices = terrain.vertices || [];
  const floor = triangleGeometry(vertices, terrain.walkable);
  if (floor) {
    const m = new THREE.Mesh(floor, new THREE.MeshLambertMaterial({ color: floorColor, side: THREE.DoubleSide }));
    m.name = 'terrain-floor';
    m.userData.flat = 'floor';
    m.receiveShadow = true;
    root.add(m);
    const edges = boundaryEdges(vertices, terrain.walkable);
    if (edges.length) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(edges, 3));
      root.add(new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0x8a857a })));
    }
  }
  const solid = triangleGeometry(vertices, terrain.obstacles);
  if (solid) {
    const m = new THREE.Mesh(solid, wallMat.clone());
    m.material.side = THREE.DoubleSide;
    m.name = 'terrain-obstacles';
    m.userData.flat = 'obstacle';
    root.add(m);
  }
  const { walls, risers } = terrainWalls(terrain);
  if (walls.length) root.add(wallObject(walls, 'terrain-railings'));
  if (risers.length) root.add(riserObject(risers));
}

/** Importance of a point's label (which label wins when two would overlap): exits first. */
const kLabelImportance = { exit: 3, action: 2, interest: 1 };

/** Name labels of the scenario's points: [{key, name, kind, importance, at: [x, y, z]}] (world
 * metres; z: 2.2 m above the floor the point stands on, over a standing person's head). */
export function pointLabels(scenario) {
  return (scenario.points || []).filter((p) => p.id && (p.polygon || p.position)).map((p) => {
    const at = p.polygon ? centroid(p.polygon) : p.position;
    const kind = kLabelImportance[p.kind] ? p.kind : 'interest';
    return { key: `point:${p.id}`, name: String(p.id), kind, importance: kLabelImportance[kind], at: [at[0], at[1], pointHeight(p) + 2.2] };
  });
}

/** The scenario's lifts and escalators (`scenario.transports`) with their stops as world points:
 * [{id, kind, stops: [[x, y, z], …]}] (a stop's place: its polygon's centroid or its position, at
 * its height); stops naming no point are left out, and transports with fewer than two stops. */
export function transportShapes(scenario) {
  const byId = new Map((scenario.points || []).map((p) => [p.id, p]));
  const out = [];
  for (const t of scenario.transports || []) {
    const stops = [];
    for (const id of t.stops || []) {
      const p = byId.get(id);
      if (!p || !(p.polygon || p.position)) continue;
      const at = p.polygon ? centroid(p.polygon) : p.position;
      stops.push([at[0], at[1], pointHeight(p)]);
    }
    if (stops.length >= 2) out.push({ id: String(t.id ?? ''), kind: t.kind === 'elevator' ? 'elevator' : 'escalator', stops });
  }
  return out;
}

const kEscalatorWidth = 1.0;   // [m] a 1 m step band (EN 115-1's widest)
const kHandrailHeight = 0.9;   // [m]
const kShaftSide = 1.8;        // [m] a lift shaft round a car for 8 (EN 81-20: 1.1 × 1.4 m inside)
const kStoreyClearance = 2.6;  // [m] the shaft goes this far above the highest stop

/** Escalators as a belt with two handrails from foot to head; lifts as a glass shaft over the first
 * stop, from the lowest floor to above the highest (named transport-escalator / transport-lift,
 * userData.transport = the id). */
function addTransports(root, scenario) {
  const steel = new THREE.MeshLambertMaterial({ color: 0x8a9098 });
  const rail = new THREE.MeshLambertMaterial({ color: 0x303438 });
  const glass = new THREE.MeshLambertMaterial({ color: 0x7fb0d0, transparent: true, opacity: 0.22, depthWrite: false });
  for (const t of transportShapes(scenario)) {
    if (t.kind === 'escalator') {
      const [a, b] = t.stops;
      const from = new THREE.Vector3(a[0], a[2], -a[1]), to = new THREE.Vector3(b[0], b[2], -b[1]);
      const length = from.distanceTo(to);
      if (length < 1e-6) continue;
      const belt = new THREE.Mesh(new THREE.BoxGeometry(kEscalatorWidth, 0.12, length), steel);
      belt.position.copy(from).add(to).multiplyScalar(0.5);
      belt.position.y -= 0.06;  // its top is the line people stand on
      belt.lookAt(to.x, to.y - 0.06, to.z);
      for (const side of [-1, 1]) {
        const r = new THREE.Mesh(new THREE.BoxGeometry(0.06, 0.06, length), rail);
        r.position.set(side * (kEscalatorWidth / 2 + 0.05), kHandrailHeight, 0);
        belt.add(r);
      }
      belt.name = 'transport-escalator';
      belt.userData.transport = t.id;
      root.add(belt);
    } else {
      const zs = t.stops.map((s) => s[2]);
      const low = Math.min(...zs), high = Math.max(...zs) + kStoreyClearance;
      const shaft = new THREE.Mesh(new THREE.BoxGeometry(kShaftSide, high - low, kShaftSide), glass);
      shaft.position.set(t.stops[0][0], (low + high) / 2, -t.stops[0][1]);
      shaft.name = 'transport-lift';
      shaft.userData.transport = t.id;
      root.add(shaft);
    }
  }
}

export function buildWorld(scenario) {
  const root = new THREE.Group();
  root.name = 'world';
  const toScene = new THREE.Matrix4().makeRotationX(-Math.PI / 2);  // shape (x, y, z) → (x, z, −y)

  const floorMat = new THREE.MeshLambertMaterial({ color: 0xd8d4cc });
  for (const poly of scenario.walkable || []) {
    const g = new THREE.ShapeGeometry(shapeOf(poly));
    g.applyMatrix4(toScene);
    const m = new THREE.Mesh(g, floorMat);
    m.receiveShadow = true;
    m.userData.flat = 'floor';  // hidden when a glTF world's own meshes are drawn (gltf_materials.js)
    root.add(m);
  }
  // Walls where the walkable area ends (not between two walkable polygons: a shop's door stays open).
  const walls = walkableWalls(scenario.walkable);
  if (walls.length) root.add(wallObject(walls, 'boundary-walls'));

  const wallMat = new THREE.MeshLambertMaterial({ color: 0xb9a98f });
  const solids = [...(scenario.obstacles || []), ...(scenario.walls || []).flatMap(wallRectangles)];
  for (const poly of solids) {
    const g = new THREE.ExtrudeGeometry(shapeOf(poly), { depth: kWallHeight, bevelEnabled: false });
    g.applyMatrix4(toScene);
    const m = new THREE.Mesh(g, wallMat);
    m.userData.flat = 'obstacle';
    root.add(m);
  }
  if (scenario.measurements?.length) root.add(measurementObject(scenario.measurements));
  const exhibits = exhibitsOnWalls(scenario.points, [...walls, ...polygonEdges(solids)]);
  if (exhibits.length) root.add(exhibitObject(exhibits));
  if (scenario.terrain) addTerrain(root, scenario.terrain, 0xd8d4cc, wallMat);
  addTransports(root, scenario);

  const mats = {
    interest: new THREE.MeshBasicMaterial({ color: 0x3070d0, transparent: true, opacity: 0.45, side: THREE.DoubleSide, depthWrite: false }),
    action: new THREE.MeshBasicMaterial({ color: 0xe08020, transparent: true, opacity: 0.5, side: THREE.DoubleSide, depthWrite: false }),
    exit: new THREE.MeshBasicMaterial({ color: 0x30b050, transparent: true, opacity: 0.5, side: THREE.DoubleSide, depthWrite: false }),
  };
  for (const p of scenario.points || []) {
    const mat = mats[p.kind] || mats.interest;
    const h = pointHeight(p);  // [m] the floor it stands on
    let g;
    let at;
    if (p.polygon) {
      g = new THREE.ShapeGeometry(shapeOf(p.polygon));
      g.applyMatrix4(toScene);
      at = centroid(p.polygon);
    } else {
      const r = p.radius ?? 0.5;
      g = p.kind === 'interest' ? new THREE.RingGeometry(Math.max(r - 0.15, r * 0.7), r, 40) : new THREE.CircleGeometry(r, 40);
      g.applyMatrix4(toScene);
      g.translate(p.position[0], 0, -p.position[1]);
      at = p.position;
    }
    g.translate(0, h + 0.02, 0);
    const mesh = new THREE.Mesh(g, mat);
    mesh.userData.point = p;
    root.add(mesh);
    if (p.kind === 'action') {
      const o = p.orientation || [1, 0];
      const l = Math.hypot(o[0], o[1]) || 1;
      const arrow = new THREE.ArrowHelper(new THREE.Vector3(o[0] / l, 0, -o[1] / l), new THREE.Vector3(at[0], h + 0.05, -at[1]),
        Math.max((p.radius ?? 0.5) + 0.6, 1), 0xc05000, 0.35, 0.25);
      root.add(arrow);
    }
  }
  return root;
}

export function addLights(scene, bounds) {
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8070, 2.0));
  const sun = new THREE.DirectionalLight(0xffffff, 1.4);
  const cx = (bounds.minX + bounds.maxX) / 2, cy = (bounds.minY + bounds.maxY) / 2;
  sun.position.set(cx + 30, 60, -cy + 40);
  sun.target.position.set(cx, 0, -cy);
  scene.add(sun, sun.target);
  scene.background = new THREE.Color(0xeef2f5);
}
