// Markers no other thing in the world uses: your own avatar's — a red ring at its feet and a red
// pin (a cone pointing down) over its head, seen from any camera, plan view included — and the
// selected agent's yellow ring. In a plan view zoomed far out they grow so as to stay at least
// kMinMarkerPx across. Scene coordinates: world (x, y, z) → scene (x, z, −y).
import * as THREE from 'three';

export const kSelfColour = 0xe8102a;
export const kMinMarkerPx = 18;  // [px] the smallest a marker is drawn in plan view

function ring(inner, outer, colour) {
  const g = new THREE.RingGeometry(inner, outer, 40);
  g.rotateX(-Math.PI / 2);
  const m = new THREE.Mesh(g, new THREE.MeshBasicMaterial({ color: colour, side: THREE.DoubleSide, depthWrite: false }));
  m.renderOrder = 3;
  m.visible = false;
  return m;
}

export class Markers {
  constructor(scene, selectedColour) {
    this.self = new THREE.Group();
    this.self.add(ring(0.45, 0.68, kSelfColour));
    const cone = new THREE.Mesh(new THREE.ConeGeometry(0.22, 0.5, 20), new THREE.MeshBasicMaterial({ color: kSelfColour }));
    cone.rotateX(Math.PI);  // tip down
    cone.position.y = 2.35;
    this.self.add(cone);
    this.self.children[0].visible = true;
    this.self.visible = false;
    this.selected = ring(0.36, 0.52, selectedColour);
    scene.add(this.self, this.selected);
  }

  /** Per frame: `self` and `selected` world {x, y, z} or null; `metresPerPx` in plan view (0 in 3D). */
  update(self, selected, metresPerPx = 0) {
    const grow = (r) => Math.max(1, (kMinMarkerPx * metresPerPx) / (2 * r));
    this.self.visible = !!self;
    if (self) {
      this.self.position.set(self.x, (self.z || 0) + 0.03, -self.y);
      this.self.scale.setScalar(grow(0.68));
    }
    this.selected.visible = !!selected;
    if (selected) {
      this.selected.position.set(selected.x, (selected.z || 0) + 0.04, -selected.y);
      this.selected.scale.setScalar(grow(0.52));
    }
  }
}
