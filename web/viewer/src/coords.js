// World ↔ scene coordinates. The engine's world is a ground plane (x, y) [m] with z up and yaw
// [rad] counter-clockwise from +x; three.js is Y up. We map world (x, y, z) → scene (x, z, −y)
// so a map seen from above keeps its orientation (x right, y up on screen), and a body authored
// facing +Z (the BVH convention) turns by yaw + π/2 about Y to face the world heading.

export function toScene(x, y, z = 0) {
  return [x, z, -y];
}

export function toWorld(sx, sy, sz) {
  return [sx, -sz, sy];
}

/** Scene rotation about Y [rad] for a world yaw [rad]. */
export function sceneYaw(yaw) {
  return yaw + Math.PI / 2;
}

/** World yaw [rad] for a scene rotation about Y [rad]. */
export function worldYaw(rotationY) {
  return rotationY - Math.PI / 2;
}
