// Crowd frame layout shared by every data source (live, replay, demo) and read by interpolate.js:
// struct-of-arrays for n agents, ascending ids. Positions in world metres (x, y on the ground, z
// up), yaw in radians (0 = +x, counter-clockwise), phase in [0, 1), tier as the protocol's
// (0 near, 1 middle, 2 far), joints only for near agents (3 angles per skeleton joint, X Y Z [rad]).

export function makeFrame(n) {
  return {
    count: n,
    simTick: 0,
    ids: new Uint32Array(n),
    tier: new Uint8Array(n),
    x: new Float32Array(n), y: new Float32Array(n), z: new Float32Array(n),
    yaw: new Float32Array(n),
    clip: new Uint16Array(n),
    phase: new Float32Array(n),
    joints: new Map(),
  };
}

/** Builds a frame from an array of agent objects {id, tier, x, y, z, yaw, clip, phase, joints}. */
export function frameFromAgents(agents, simTick = 0) {
  const sorted = [...agents].sort((a, b) => a.id - b.id);
  const f = makeFrame(sorted.length);
  f.simTick = simTick;
  sorted.forEach((a, i) => {
    f.ids[i] = a.id; f.tier[i] = a.tier ?? 1;
    f.x[i] = a.x; f.y[i] = a.y; f.z[i] = a.z ?? 0; f.yaw[i] = a.yaw ?? 0;
    f.clip[i] = a.clip ?? 0; f.phase[i] = a.phase ?? 0;
    if (a.joints && a.joints.length) f.joints.set(a.id, Float32Array.from(a.joints));
  });
  return f;
}
