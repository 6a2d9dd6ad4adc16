// How a participant's avatar looks, chosen when joining (the join form's menu): a few looks the
// viewer's procedural bodies can show — colours for shirt, trousers, skin and shoes, and a height —
// the part of the body each skeleton joint's solids belong to (lookPartOf), the per-vertex colours
// of a skinned body in a look (lookVertexColours), and the choice remembered in the browser
// (loadLookChoice / saveLookChoice). Pure but for the storage passed in. The marks that make your
// own avatar unmistakable (crowd/markers.js: the red ring and pin) stay whatever the look.
// The look's index goes to the server in Join's `avatar` field; the server relays it to the other
// viewers in Presence (protocol 2), which draw each participant in their look (docs/viewer.md,
// "Avatar look").

/** The looks: [{name, shirt, trousers, skin, shoes (0xRRGGBB), height (scale of the skeleton)}]. */
export const kAvatarLooks = [
  { name: 'red jacket', shirt: 0xe8102a, trousers: 0x2b2f3a, skin: 0xe0b594, shoes: 0x202020, height: 1.0 },
  { name: 'teal hoodie', shirt: 0x0f8b8d, trousers: 0x3b4a6b, skin: 0x8d5a3b, shoes: 0xf0f0f0, height: 1.0 },
  { name: 'blue coat, tall', shirt: 0x2450c8, trousers: 0x595959, skin: 0xf1c7a5, shoes: 0x4a3020, height: 1.06 },
  { name: 'green top, short', shirt: 0x2e9b3c, trousers: 0x6b4f2a, skin: 0xc68e5f, shoes: 0x202020, height: 0.94 },
  { name: 'white shirt', shirt: 0xf2f2f2, trousers: 0x1d2a4a, skin: 0x5e3a24, shoes: 0x202020, height: 1.0 },
  { name: 'black suit', shirt: 0x262626, trousers: 0x262626, skin: 0xd9a77e, shoes: 0x101010, height: 1.03 },
];

/** The look at `index`, the first one for an index out of range. */
export function lookAt(index) {
  const i = Number(index);
  return Number.isInteger(i) && i >= 0 && i < kAvatarLooks.length ? kAvatarLooks[i] : kAvatarLooks[0];
}

/** The body part a joint's solids are coloured as (body_geometry.js skins each solid to one
 * joint): 'skin' (head, neck, hands), 'shoes' (feet), 'trousers' (pelvis, legs), else 'shirt'. */
export function lookPartOf(jointName) {
  const n = jointName.toLowerCase();
  if (/skull|head|neck|wrist|hand|finger|thumb/.test(n)) return 'skin';
  if (/ankle|foot|toe/.test(n)) return 'shoes';
  if (/hip|knee|thigh|shin|leg|sacro|pelvis/.test(n)) return 'trousers';
  return 'shirt';
}

/** [r, g, b] in 0..1 of 0xRRGGBB, as written (sRGB). */
export function rgbOf(hex) {
  return [((hex >> 16) & 255) / 255, ((hex >> 8) & 255) / 255, (hex & 255) / 255];
}

/** Per-vertex colours (3 per vertex) of a skinned body in `look`: each vertex gets its bone's part
 * colour. `skinIndex`: 4 bone indices per vertex (the first has weight 1); `joints`: the skeleton;
 * `toRgb`: 0xRRGGBB → [r, g, b] (three's renderer wants linear values: near_bodies.js converts). */
export function lookVertexColours(skinIndex, joints, look, toRgb = rgbOf) {
  const byJoint = joints.map((j) => toRgb(look[lookPartOf(j.name)]));
  const n = skinIndex.length / 4;
  const out = new Float32Array(n * 3);
  for (let v = 0; v < n; ++v) out.set(byJoint[skinIndex[v * 4]] || byJoint[0], v * 3);
  return out;
}

const kStorageKey = 'throng.avatarLook';

/** The look index remembered in `storage` (localStorage), 0 when none or invalid. */
export function loadLookChoice(storage) {
  try {
    const i = Number(storage?.getItem(kStorageKey));
    return Number.isInteger(i) && i >= 0 && i < kAvatarLooks.length ? i : 0;
  } catch { return 0; }  // storage refused (private mode, file://)
}

/** Remembers look `index` in `storage`; nothing when it refuses. */
export function saveLookChoice(storage, index) {
  try { storage?.setItem(kStorageKey, String(index)); } catch { /* not remembered */ }
}
