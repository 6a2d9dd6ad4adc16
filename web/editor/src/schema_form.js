// Forms from the JSON Schema (scenarios/schema/scenario.schema.json), pure (no DOM): the fields of
// an object's simple properties (numbers with their limits, integers, booleans, strings, enums)
// with their defaults and descriptions, the pedestrian models and each model's parameters, and the
// coercion of what was typed into a field, with a message naming the limit it breaks.

/** Follows a local "$ref" ("#/$defs/x"); other nodes come back as they are. */
export function resolve(schema, node) {
  let n = node;
  for (let i = 0; n && n.$ref && i < 10; i++) {
    const path = n.$ref.replace(/^#\//, '').split('/');
    n = path.reduce((o, k) => (o ? o[k] : undefined), schema);
  }
  return n || {};
}

/** One field from a property schema, or null when it is not a simple value. */
export function fieldOf(schema, key, node) {
  const p = resolve(schema, node);
  const base = { key, description: p.description || node?.description || '', default: p.default };
  if (Array.isArray(p.enum)) return { ...base, type: 'enum', options: p.enum };
  if (p.type === 'number' || p.type === 'integer') {
    return { ...base, type: p.type, minimum: p.minimum, maximum: p.maximum, exclusiveMinimum: p.exclusiveMinimum };
  }
  if (p.type === 'boolean' || p.type === 'string') return { ...base, type: p.type };
  return null;
}

/** The simple fields of an object schema, in the schema's order (only `keys` when given). */
export function objectFields(schema, objectNode, keys = null) {
  const props = resolve(schema, objectNode).properties || {};
  const names = keys || Object.keys(props);
  return names.filter((k) => props[k]).map((k) => fieldOf(schema, k, props[k])).filter(Boolean);
}

/** The pedestrian models a population may name (the schema's string enum). */
export function modelNames(schema) {
  const model = resolve(schema, schema.$defs?.model);
  const named = (model.oneOf || []).find((o) => o.type === 'string' && Array.isArray(o.enum));
  return named ? named.enum.slice() : [];
}

/** The variants of a oneOf of objects told apart by the constant of `key` ("distribution"). */
export function variantNames(schema, node, key) {
  return (resolve(schema, node).oneOf || [])
    .filter((o) => o.type === 'object' && o.properties?.[key]?.const !== undefined).map((o) => o.properties[key].const);
}

/** The fields of variant `value` of such a oneOf (its properties but `key`); [] for none. */
export function variantFields(schema, node, key, value) {
  const form = (resolve(schema, node).oneOf || []).find((o) => o.type === 'object' && o.properties?.[key]?.const === value);
  if (!form) return [];
  return Object.entries(form.properties).filter(([k]) => k !== key).map(([k, v]) => fieldOf(schema, k, v)).filter(Boolean);
}

/** The parameters of model `name` as fields (the object form's properties but "name"). */
export function modelParameters(schema, name) {
  return variantFields(schema, schema.$defs?.model, 'name', name);
}

/** The model a population walks with when it names none (the engine default, docs/scenario-format.md). */
export const DEFAULT_MODEL = 'avm';

/** The model of a population as {name, params}: "orca" or {"name": "orca", ...}; avm (the engine's default) when absent. */
export function readModel(value) {
  if (typeof value === 'string') return { name: value, params: {} };
  if (value && typeof value === 'object') {
    const { name, ...params } = value;
    return { name: name || DEFAULT_MODEL, params };
  }
  return { name: DEFAULT_MODEL, params: {} };
}

/** The JSON for a model: the bare name without parameters, else the object. */
export function writeModel(name, params) {
  const set = Object.entries(params).filter(([, v]) => v !== undefined && v !== '');
  return set.length ? { name, ...Object.fromEntries(set) } : name;
}

/**
 * What `text` typed in `field` means: {value} (undefined for an empty field: the default), or
 * {error} naming the limit ("0.3 is below the minimum 0.5").
 */
export function coerce(field, text) {
  if (field.type === 'boolean') return { value: Boolean(text) };
  const s = String(text ?? '').trim();
  if (s === '') return { value: undefined };
  if (field.type === 'string') return { value: s };
  if (field.type === 'enum') {
    return field.options.includes(s) ? { value: s } : { error: `expected one of ${field.options.join(', ')}` };
  }
  const v = Number(s);
  if (!Number.isFinite(v)) return { error: `"${s}" is not a number` };
  if (field.type === 'integer' && !Number.isInteger(v)) return { error: `${v} is not a whole number` };
  if (field.minimum !== undefined && v < field.minimum) return { error: `${v} is below the minimum ${field.minimum}` };
  if (field.exclusiveMinimum !== undefined && v <= field.exclusiveMinimum) return { error: `${v} must be above ${field.exclusiveMinimum}` };
  if (field.maximum !== undefined && v > field.maximum) return { error: `${v} is above the maximum ${field.maximum}` };
  return { value: v };
}
