// The static world from the scenario JSON (docs/scenario-format.md) as the world description
// carries it: walkable polygons as floors, obstacles extruded as walls, points as markers —
// interest (blue ring), action (orange disc with an arrow along its orientation), exit (green
// area) — with name labels; lights and a ground grid. World (x, y) → scene (x, 0, −y).
import * as THREE from 'three';

const kWallHeight = 2.4;  // [m]

function shapeOf(polygon) {
  const s = new THREE.Shape();
  polygon.forEach(([x, y], i) => (i === 0 ? s.moveTo(x, y) : s.lineTo(x, y)));
  return s;
}

function label(text, color = '#222') {
  const c = document.createElement('canvas');
  const ctx = c.getContext('2d');
  ctx.font = '28px sans-serif';
  c.width = Math.ceil(ctx.measureText(text).width) + 16;
  c.height = 40;
  ctx.font = '28px sans-serif';
  ctx.fillStyle = 'rgba(255,255,255,0.75)';
  ctx.fillRect(0, 0, c.width, c.height);
  ctx.fillStyle = color;
  ctx.fillText(text, 8, 30);
  const tex = new THREE.CanvasTexture(c);
  tex.colorSpace = THREE.SRGBColorSpace;
  const s = new THREE.Sprite(new THREE.SpriteMaterial({ map: tex, depthWrite: false }));
  s.scale.set((c.width / c.height) * 0.5, 0.5, 1);
  return s;
}

function centroid(polygon) {
  let x = 0, y = 0;
  for (const p of polygon) { x += p[0]; y += p[1]; }
  return [x / polygon.length, y / polygon.length];
}

/** Bounds of the walkable area: {minX, minY, maxX, maxY} [m]. */
export function worldBounds(scenario) {
  const b = { minX: Infinity, minY: Infinity, maxX: -Infinity, maxY: -Infinity };
  for (const poly of scenario.walkable || []) {
    for (const [x, y] of poly) {
      b.minX = Math.min(b.minX, x); b.minY = Math.min(b.minY, y);
      b.maxX = Math.max(b.maxX, x); b.maxY = Math.max(b.maxY, y);
    }
  }
  if (!Number.isFinite(b.minX)) Object.assign(b, { minX: -10, minY: -10, maxX: 10, maxY: 10 });
  return b;
}

export function buildWorld(scenario, { labels = true } = {}) {
  const root = new THREE.Group();
  root.name = 'world';
  const toScene = new THREE.Matrix4().makeRotationX(-Math.PI / 2);  // shape (x, y, z) → (x, z, −y)

  const floorMat = new THREE.MeshLambertMaterial({ color: 0xd8d4cc });
  for (const poly of scenario.walkable || []) {
    const g = new THREE.ShapeGeometry(shapeOf(poly));
    g.applyMatrix4(toScene);
    const m = new THREE.Mesh(g, floorMat);
    m.receiveShadow = true;
    root.add(m);
    const edge = new THREE.LineLoop(
      new THREE.BufferGeometry().setFromPoints(poly.map(([x, y]) => new THREE.Vector3(x, 0.01, -y))),
      new THREE.LineBasicMaterial({ color: 0x8a857a }));
    root.add(edge);
  }

  const wallMat = new THREE.MeshLambertMaterial({ color: 0xb9a98f });
  for (const poly of scenario.obstacles || []) {
    const g = new THREE.ExtrudeGeometry(shapeOf(poly), { depth: kWallHeight, bevelEnabled: false });
    g.applyMatrix4(toScene);
    root.add(new THREE.Mesh(g, wallMat));
  }

  const mats = {
    interest: new THREE.MeshBasicMaterial({ color: 0x3070d0, transparent: true, opacity: 0.45, side: THREE.DoubleSide, depthWrite: false }),
    action: new THREE.MeshBasicMaterial({ color: 0xe08020, transparent: true, opacity: 0.5, side: THREE.DoubleSide, depthWrite: false }),
    exit: new THREE.MeshBasicMaterial({ color: 0x30b050, transparent: true, opacity: 0.5, side: THREE.DoubleSide, depthWrite: false }),
  };
  for (const p of scenario.points || []) {
    const mat = mats[p.kind] || mats.interest;
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
    g.translate(0, 0.02, 0);
    const mesh = new THREE.Mesh(g, mat);
    mesh.userData.point = p;
    root.add(mesh);
    if (p.kind === 'action') {
      const o = p.orientation || [1, 0];
      const l = Math.hypot(o[0], o[1]) || 1;
      const arrow = new THREE.ArrowHelper(new THREE.Vector3(o[0] / l, 0, -o[1] / l), new THREE.Vector3(at[0], 0.05, -at[1]),
        Math.max((p.radius ?? 0.5) + 0.6, 1), 0xc05000, 0.35, 0.25);
      root.add(arrow);
    }
    if (labels) {
      const s = label(p.id, p.kind === 'exit' ? '#106020' : p.kind === 'action' ? '#904000' : '#103080');
      s.position.set(at[0], 2.7, -at[1]);
      root.add(s);
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
