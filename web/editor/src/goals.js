// A population's goals as the editor edits them, pure (no DOM): each entry is a point id or a
// waypoint choice {"choose": [ids], "split": "shares" | "leastTargeted", "shares": [numbers]}
// (docs/scenario-format.md, Waypoint choices). Turning a goal into a choice, adding and removing
// its options, its split and shares (parsed with a message naming what is wrong), the ids an entry
// names (for the plan's arrows), and renaming or removing a point in every entry.

/** True for a waypoint choice entry. */
export const isChoice = (goal) => Boolean(goal) && typeof goal === 'object' && Array.isArray(goal.choose);

/** The point ids an entry names, in order. */
export const goalIds = (goal) => (isChoice(goal) ? goal.choose.slice() : [goal]);

/** A short text for an entry: "exit" or "one of a, b (shares 2 : 1)". */
export function goalLabel(goal) {
  if (!isChoice(goal)) return String(goal);
  const split = goal.split === 'leastTargeted' ? ' (least targeted)'
    : Array.isArray(goal.shares) ? ` (shares ${goal.shares.join(' : ')})` : '';
  return `one of ${goal.choose.join(', ')}${split}`;
}

/**
 * The entry with point `id` added as an option: a plain goal becomes a choice between it and `id`;
 * a choice gains `id` (its shares, if set, gain an equal share: the mean of the others). An id
 * already among the options changes nothing.
 */
export function addOption(goal, id) {
  if (!isChoice(goal)) return goal === id ? goal : { choose: [goal, id] };
  if (goal.choose.includes(id)) return goal;
  const next = { ...goal, choose: [...goal.choose, id] };
  if (Array.isArray(goal.shares)) {
    const mean = goal.shares.reduce((a, b) => a + b, 0) / Math.max(1, goal.shares.length);
    next.shares = [...goal.shares, Number(mean.toFixed(3))];
  }
  return next;
}

/**
 * The entry without option `id` (its share goes with it): a choice left with one option becomes
 * that plain goal, with none it is null (the entry goes). A plain goal equal to `id` is null.
 */
export function removeOption(goal, id) {
  if (!isChoice(goal)) return goal === id ? null : goal;
  const keep = goal.choose.map((g, i) => [g, i]).filter(([g]) => g !== id);
  if (keep.length === goal.choose.length) return goal;
  if (keep.length === 0) return null;
  if (keep.length === 1) return keep[0][0];
  const next = { ...goal, choose: keep.map(([g]) => g) };
  if (Array.isArray(goal.shares)) next.shares = keep.map(([, i]) => goal.shares[i]);
  return next;
}

/** The entry renamed: every option `old` becomes `id`. */
export function renameInGoal(goal, old, id) {
  if (!isChoice(goal)) return goal === old ? id : goal;
  return { ...goal, choose: goal.choose.map((g) => (g === old ? id : g)) };
}

/** The choice with split `split` (the schema's enum); shares belong to the shares split only. */
export function setSplit(goal, split) {
  const next = { ...goal };
  if (split === undefined || split === 'shares') delete next.split;
  else next.split = split;
  if (split === 'leastTargeted') delete next.shares;
  return next;
}

/**
 * What `text` typed as the shares of a choice means: {value} (an array of numbers, one per option;
 * undefined for empty: equal shares) or {error} naming what is wrong. Separators: commas, colons or
 * spaces.
 */
export function parseShares(goal, text) {
  const s = String(text ?? '').trim();
  if (s === '') return { value: undefined };
  const parts = s.split(/[\s,:;]+/).filter(Boolean);
  const values = parts.map(Number);
  const bad = parts.find((p, i) => !Number.isFinite(values[i]));
  if (bad !== undefined) return { error: `"${bad}" is not a number` };
  if (values.length !== goal.choose.length) {
    return { error: `${values.length} shares for ${goal.choose.length} options: give one per option` };
  }
  const negative = values.find((v) => v < 0);
  if (negative !== undefined) return { error: `${negative} is below the minimum 0` };
  if (values.every((v) => v === 0)) return { error: 'the shares are all 0: at least one must be above 0' };
  return { value: values };
}

/** The choice with shares `shares` (undefined: equal shares, the key goes). */
export function setShares(goal, shares) {
  const next = { ...goal };
  if (shares === undefined) delete next.shares;
  else next.shares = shares;
  return next;
}
