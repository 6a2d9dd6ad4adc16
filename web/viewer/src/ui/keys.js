// The viewer's keyboard: one table of every key (kKeys: what the help overlay lists, ui/help.js)
// and one keydown listener that calls the named action (never while typing in a field, nor with
// Ctrl/Alt/Meta held, so the browser's own shortcuts still work). The walk camera reads its
// movement keys itself (camera/cameras.js); they are listed here too, with no action.

/** [{keys: shown, match: [KeyboardEvent.key values, lower case], action: name | null, what}] */
export const kKeys = [
  { keys: 'C', match: ['c'], action: 'nextCamera', what: 'next camera: plan → orbit → walk' },
  { keys: 'P', match: ['p'], action: 'plan', what: 'plan view (top-down, orthographic)' },
  { keys: 'O', match: ['o'], action: 'orbit', what: 'orbit camera (3D)' },
  { keys: 'F', match: ['f'], action: 'fit', what: 'fit the whole world in view' },
  { keys: 'T', match: ['t'], action: 'follow', what: 'follow the selected agent (or group) / stop' },
  { keys: 'L', match: ['l'], action: 'labels', what: 'labels of points on / off (names of participants stay)' },
  { keys: 'B', match: ['b'], action: 'colourBy', what: 'colour by: group → population → speed → density → state' },
  { keys: 'R', match: ['r'], action: 'trails', what: 'trails (where each agent walked in the last 10 s) on / off' },
  { keys: 'M', match: ['m'], action: 'heatmap', what: 'density map (persons/m² per 1 m cell, last 5 s) on / off' },
  { keys: 'G', match: ['g'], action: 'speedmap', what: 'speed map (mean speed per 1 m cell, last 5 s) on / off' },
  { keys: 'K', match: ['k'], action: 'screenshot', what: 'download a PNG screenshot of the view' },
  { keys: 'V', match: ['v'], action: 'record', what: 'record the view as a WebM video: start / stop (then downloads)' },
  { keys: '? or H', match: ['?', 'h'], action: 'help', what: 'this help' },
  { keys: 'Esc', match: ['escape'], action: 'escape', what: 'close the help, clear the selection, stop following' },
  { keys: '1 – 4', match: ['1', '2', '3', '4'], action: 'gesture', what: 'gesture of your avatar (wave, nod, point, call out), once joined' },
  { keys: 'W/S or ↑/↓', match: [], action: null, what: 'walk camera: forward / back (Shift runs)' },
  { keys: 'A/D or ←/→', match: [], action: null, what: 'walk camera: turn (or drag)' },
  { keys: 'Q/E', match: [], action: null, what: 'walk camera: step left / right' },
];

/** Mouse, for the help overlay. */
export const kMouse = [
  { keys: 'click', what: 'select an agent (any camera)' },
  { keys: 'drag', what: 'plan: pan · orbit: rotate · walk: turn' },
  { keys: 'right-drag', what: 'pan' },
  { keys: 'wheel', what: 'zoom (plan: at the pointer)' },
];

/** The action for a keydown event, or null. */
export function actionOf(e) {
  if (e.ctrlKey || e.altKey || e.metaKey) return null;
  const t = e.target;
  if (t && /^(INPUT|SELECT|TEXTAREA)$/.test(t.tagName)) return null;
  const k = String(e.key || '').toLowerCase();
  const b = kKeys.find((x) => x.action && x.match.includes(k));
  return b ? b.action : null;
}

/** Calls handlers[action](event) for each bound key pressed. */
export function bindKeys(handlers, target = globalThis) {
  target.addEventListener('keydown', (e) => {
    const a = actionOf(e);
    if (a && handlers[a]) { handlers[a](e); e.preventDefault(); }
  });
}
