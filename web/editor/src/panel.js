// The properties panel: a form for the selection (or the scenario's own keys when nothing is
// selected). Points by kind, walls, measurements and crowds — size, speed, start, goals in order
// (picked on the plan; a goal may be a waypoint choice among points, with its split and shares),
// exit choice (the exits, the rule and its keys, the familiar exits) and the
// pedestrian model with its parameters, a form generated from the
// JSON Schema (schema_form.js). A value out of its schema limits is shown under its field and not
// written; every accepted change is one undoable edit (`app.commit`).
import {
  DEFAULT_MODEL, coerce, fieldOf, modelNames, modelParameters, objectFields, readModel, variantFields, variantNames, writeModel,
} from './schema_form.js';
import { polygonArea, polygonProblem, polylineLength } from './geometry.js';
import { isClosed, renamePoint, verticesOf } from './doc.js';
import { goalIds, isChoice, parseShares, removeOption, setShares, setSplit } from './goals.js';

function h(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k.startsWith('on')) node.addEventListener(k.slice(2), v);
    else if (v !== undefined && v !== null && v !== false) node.setAttribute(k, v === true ? '' : String(v));
  }
  for (const c of children) if (c !== null && c !== undefined) node.append(c);
  return node;
}

export class Panel {
  constructor(app, root, schema) {
    this.app = app;
    this.root = root;
    this.schema = schema;
  }

  /** One input for a schema field (labelled `field.label`, else its key); `set(value)` writes the
   * accepted value (undefined: remove). */
  input(field, value, set) {
    const id = `f-${field.key}`;
    const error = h('div', { class: 'field-error' });
    let control;
    const apply = (raw) => {
      const r = coerce(field, raw);
      error.textContent = r.error || '';
      if (!r.error) set(r.value);
    };
    if (field.type === 'boolean') {
      control = h('input', { type: 'checkbox', id, 'data-field': field.key, checked: value ?? field.default ?? false,
        onchange: (e) => apply(e.target.checked) });
    } else if (field.type === 'enum') {
      control = h('select', { id, 'data-field': field.key, onchange: (e) => apply(e.target.value) },
        ...field.options.map((o) => h('option', { value: o, selected: (value ?? field.default) === o }, String(o))));
    } else {
      const limits = [field.minimum ?? (field.exclusiveMinimum !== undefined ? `>${field.exclusiveMinimum}` : null), field.maximum]
        .filter((x) => x !== null && x !== undefined);
      control = h('input', { id, 'data-field': field.key, value: value ?? '', placeholder: field.default ?? '',
        title: `${field.description}${limits.length ? ` [${limits.join(' … ')}]` : ''}`,
        onchange: (e) => apply(e.target.value) });
    }
    return h('div', { class: 'field' }, h('label', { for: id, title: field.description }, field.label ?? field.key), control, error);
  }

  render() {
    const { doc, sel } = this.app;
    this.root.replaceChildren();
    if (!sel || sel.index == null || !doc[sel.layer]?.[sel.index]) return this.renderScenario();
    const item = doc[sel.layer][sel.index];
    this.root.append(h('h3', {}, `${sel.layer} ${sel.index}`));
    this.measures(sel);
    if (sel.layer === 'points') this.renderPoint(item, sel.index);
    else if (sel.layer === 'populations') this.renderPopulation(item);
    else if (sel.layer === 'walls') {
      this.root.append(this.input({ key: 'id', type: 'string', description: 'wall id' }, item.id, (v) => this.set(item, 'id', v)));
      const f = fieldOf(this.schema, 'thickness', this.schema.$defs?.wall?.properties?.thickness || { type: 'number', exclusiveMinimum: 0, maximum: 5, default: 0.2 });
      this.root.append(this.input(f, item.thickness, (v) => this.set(item, 'thickness', v)));
    } else if (sel.layer === 'measurements') {
      this.root.append(this.input({ key: 'id', type: 'string', description: 'measurement id' }, item.id, (v) => this.set(item, 'id', v)));
    }
    this.root.append(h('button', { class: 'danger', 'data-action': 'delete', onclick: () => this.app.deleteSelection() }, 'Delete (Del)'));
  }

  measures(sel) {
    const vs = verticesOf(this.app.doc, sel);
    if (!vs || vs.length < 2) return;
    const text = isClosed(this.app.doc, sel)
      ? `area ${polygonArea(vs).toFixed(2)} m² · perimeter ${polylineLength(vs, true).toFixed(2)} m · ${vs.length} vertices`
      : `length ${polylineLength(vs).toFixed(2)} m · ${vs.length} points`;
    this.root.append(h('div', { class: 'measures', id: 'measures' }, text));
    const problem = isClosed(this.app.doc, sel) ? polygonProblem(vs) : null;
    if (problem) this.root.append(h('div', { class: 'field-error', id: 'shape-problem' }, `not a simple polygon: ${problem}`));
  }

  set(obj, key, value) {
    if (value === undefined) delete obj[key];
    else obj[key] = value;
    this.app.commit(`${key} changed`);
  }

  renderScenario() {
    const { doc } = this.app;
    this.root.append(h('h3', {}, 'Scenario'));
    for (const f of objectFields(this.schema, this.schema, ['name', 'seed', 'duration', 'dt'])) {
      this.root.append(this.input(f, doc[f.key], (v) => this.set(doc, f.key, v)));
    }
    this.root.append(h('p', { class: 'small' }, 'Pick a tool (keys on the toolbar, ? for all) and draw on the plan.'));
  }

  renderPoint(point, index) {
    const defs = this.schema.$defs || {};
    this.root.append(this.input({ key: 'id', type: 'string', description: 'unique id; goals name it' }, point.id, (v) => {
      if (v) { renamePoint(this.app.doc, index, v); this.app.commit('renamed'); }
    }));
    const keys = ['kind'];
    if (Array.isArray(point.position)) keys.push('radius');
    if (point.kind === 'exit') keys.push('width');
    if (point.kind !== 'action') keys.push('aim');
    if (point.kind === 'action') keys.push('stop', 'duration', 'action', 'clip');
    keys.push('category');
    for (const f of objectFields(this.schema, defs.point, keys)) {
      this.root.append(this.input(f, point[f.key], (v) => {
        if (f.key === 'kind') this.changeKind(point, v);
        else this.set(point, f.key, v);
      }));
    }
    if (point.kind === 'action') {
      const o = point.orientation || [1, 0];
      const angle = Math.round((Math.atan2(o[1], o[0]) * 180) / Math.PI);
      this.root.append(this.input({ key: 'orientation°', type: 'number', minimum: -360, maximum: 360, description: 'facing direction while stopped, degrees from +x' },
        angle, (v) => {
          const a = ((v ?? 0) * Math.PI) / 180;
          this.set(point, 'orientation', [Number(Math.cos(a).toFixed(4)), Number(Math.sin(a).toFixed(4))]);
        }));
    }
  }

  /** Keys of one kind are errors on another: they go when the kind changes. */
  changeKind(point, kind) {
    point.kind = kind;
    if (kind !== 'action') for (const k of ['stop', 'orientation', 'action', 'duration', 'clip']) delete point[k];
    if (kind !== 'exit') delete point.width;
    if (kind === 'action') delete point.aim;
    if (kind === 'action' && !point.orientation) point.orientation = [1, 0];
    this.app.commit('kind changed');
  }

  renderPopulation(pop) {
    const defs = this.schema.$defs || {};
    for (const f of objectFields(this.schema, defs.population, ['id', 'groups', 'start', 'radius'])) {
      this.root.append(this.input(f, pop[f.key], (v) => this.set(pop, f.key, v)));
    }
    const size = Array.isArray(pop.size) ? pop.size.join('-') : pop.size ?? '';
    this.root.append(this.input({ key: 'size', type: 'string', description: 'agents per group: N or MIN-MAX' }, size, (v) => {
      const m = /^(\d+)(?:\s*-\s*(\d+))?$/.exec(v || '');
      if (!v) this.set(pop, 'size', undefined);
      else if (m) this.set(pop, 'size', m[2] ? [Number(m[1]), Number(m[2])] : Number(m[1]));
    }));
    const speed = typeof pop.speed === 'number' ? { mean: pop.speed } : pop.speed || {};
    const speedFields = objectFields(this.schema, (defs.speed?.oneOf || []).find((o) => o.properties?.mean) || {}, ['mean', 'sd']);
    for (const f of speedFields) {
      this.root.append(this.input({ ...f, key: `speed.${f.key}` }, speed[f.key], (v) => {
        const next = { ...speed, [f.key]: v };
        if (v === undefined) delete next[f.key];
        this.set(pop, 'speed', Object.keys(next).length ? next : undefined);
      }));
    }
    this.renderPreMovement(pop);
    this.renderGoals(pop);
    this.renderExitChoice(pop);
    this.renderModel(pop);
  }

  /** Exit choice (docs/scenario-format.md "Exit choice"): after its goals each group chooses one of
   * the ticked exits by the rule; the familiar ones among them; the rule's keys from the schema. */
  renderExitChoice(pop) {
    const exits = (this.app.doc.points || []).filter((p) => p.kind === 'exit').map((p) => p.id);
    if (!exits.length) return;
    const chosen = Array.isArray(pop.exits) ? pop.exits : [];
    const toggle = (list, id, on) => (on ? [...list.filter((x) => x !== id), id] : list.filter((x) => x !== id));
    const boxes = (name, list, onChange, among) => h('div', { class: 'checks', id: `${name}-list` }, ...among.map((id) =>
      h('label', { class: 'check' }, h('input', { type: 'checkbox', 'data-exit': id, ...(list.includes(id) ? { checked: '' } : {}),
        onchange: (e) => onChange(toggle(list, id, e.target.checked)) }), ` ${id}`)));
    this.root.append(h('div', { class: 'field' }, h('label', { title: 'after its goals, each group chooses one of these exits' }, 'exits'),
      boxes('exits', chosen, (next) => {
        if (next.length) pop.exits = exits.filter((x) => next.includes(x));
        else { delete pop.exits; delete pop.exitChoice; }
        if (pop.exitChoice?.familiar) pop.exitChoice.familiar = pop.exitChoice.familiar.filter((x) => next.includes(x));
        this.app.commit('exits changed');
      }, exits)));
    if (!chosen.length) return;
    const choice = pop.exitChoice || {};
    const setChoice = (key, value) => {
      const next = { ...choice, [key]: value };
      if (value === undefined || (Array.isArray(value) && !value.length)) delete next[key];
      this.set(pop, 'exitChoice', Object.keys(next).length ? next : undefined);
    };
    const node = this.schema.$defs?.population?.properties?.exitChoice || {};
    for (const f of objectFields(this.schema, node, ['rule', 'period', 'hysteresis', 'familiarity', 'herding', 'herdingRadius'])) {
      this.root.append(this.input({ ...f, key: `exitChoice.${f.key}` }, choice[f.key], (v) => setChoice(f.key, v)));
    }
    this.root.append(h('div', { class: 'field' }, h('label', { title: 'the exits the group knows; the others look familiarity times as dear' }, 'familiar'),
      boxes('familiar', Array.isArray(choice.familiar) ? choice.familiar : [], (next) => setChoice('familiar', next), chosen)));
  }

  /** Pre-movement time: none or one of the schema's distributions, with its keys. */
  renderPreMovement(pop) {
    const node = this.schema.$defs?.preMovement;
    const current = pop.preMovement?.distribution;
    this.root.append(this.input({ key: 'preMovement', type: 'enum', options: ['none', ...variantNames(this.schema, node, 'distribution')],
      description: 'pre-movement time: agents stand where they appear for a time drawn from this distribution [s]' },
      current || 'none', (v) => this.set(pop, 'preMovement', v === 'none' ? undefined : { distribution: v })));
    if (!current) return;
    for (const f of variantFields(this.schema, node, 'distribution', current)) {
      this.root.append(this.input({ ...f, key: `preMovement.${f.key}` }, pop.preMovement[f.key], (v) => {
        const next = { ...pop.preMovement, [f.key]: v };
        if (v === undefined) delete next[f.key];
        this.set(pop, 'preMovement', next);
      }));
    }
  }

  /** The goals in order; each a point or a waypoint choice (docs/scenario-format.md, Waypoint
   * choices): "or…" turns a goal into a choice and picks its options on the plan; a choice shows its
   * options (each removable), its split and, for the shares split, its shares. */
  renderGoals(pop) {
    const goals = Array.isArray(pop.goals) ? pop.goals : [];
    const { pickGoals, pickChoice } = this.app.state;
    const replace = (i, goal, what) => {
      if (goal === null) {
        pop.goals.splice(i, 1);
        if (pickChoice !== null) { this.app.state.pickGoals = false; this.app.state.pickChoice = null; }  // its index moved
      } else pop.goals[i] = goal;
      this.app.commit(what);
    };
    const exits = new Set((this.app.doc.points || []).filter((p) => p.kind === 'exit').map((p) => p.id));
    const items = goals.map((g, i) => {
      const picking = pickGoals && pickChoice === i;
      // An exit is no waypoint to choose among (the crowd's "exits" and "exitChoice" are for that).
      const more = exits.has(g) ? null : h('button', { class: `or${picking ? ' on' : ''}`, 'data-choice': i,
        title: 'add options to choose among: click points on the plan', onclick: () => this.app.pickOptions(i) },
      picking ? 'picking…' : (isChoice(g) ? '+ option' : 'or…'));
      const remove = h('button', { class: 'x', title: 'remove this goal', onclick: () => replace(i, null, 'goal removed') }, '×');
      if (!isChoice(g)) return h('li', {}, g, ' ', more, remove);
      const options = goalIds(g).map((id) => h('span', { class: 'option' }, id,
        h('button', { class: 'x', title: `remove ${id} from the choice`, 'data-option': id,
          onclick: () => replace(i, removeOption(g, id), `${id} removed from the choice`) }, '×')));
      return h('li', { class: 'choice' }, h('div', {}, 'one of ', ...options, ' ', more, remove),
        ...this.choiceFields(g, (next, what) => replace(i, next, what), i));
    });
    this.root.append(h('div', { class: 'field goals-field' }, h('label', {}, 'goals'),
      h('ol', { class: 'goals', id: 'goal-list' }, ...items),
      h('button', { id: 'pick-goals', class: pickGoals && pickChoice === null ? 'on' : '', onclick: () => this.app.togglePickGoals() },
        pickGoals && pickChoice === null ? 'Picking… click points (G ends)' : 'Pick goals (G)')));
  }

  /** The split of a waypoint choice (the schema's enum) and, with the shares split, its shares. */
  choiceFields(goal, write, index) {
    const node = this.schema.$defs?.goalChoice?.properties || {};
    const split = fieldOf(this.schema, 'split', node.split || { enum: ['shares', 'leastTargeted'], default: 'shares' });
    const out = [this.input({ ...split, key: `goals.${index}.split`, label: 'split' }, goal.split,
      (v) => write(setSplit(goal, v), 'split changed'))];
    if (goal.split === 'leastTargeted') return out;
    const id = `f-goals-${index}-shares`;
    const error = h('div', { class: 'field-error' });
    const control = h('input', { id, 'data-field': `goals.${index}.shares`, value: Array.isArray(goal.shares) ? goal.shares.join(', ') : '',
      placeholder: 'equal', title: node.shares?.description || 'one share per option',
      onchange: (e) => {
        const r = parseShares(goal, e.target.value);
        error.textContent = r.error || '';
        if (!r.error) write(setShares(goal, r.value), 'shares changed');
      } });
    out.push(h('div', { class: 'field' }, h('label', { for: id, title: node.shares?.description || '' }, 'shares'), control, error));
    return out;
  }

  renderModel(pop) {
    const { name, params } = readModel(pop.model);
    const names = modelNames(this.schema);
    const write = (n, p) => {
      const value = writeModel(n, p);
      this.set(pop, 'model', value === DEFAULT_MODEL && pop.model === undefined ? undefined : value);
    };
    this.root.append(this.input({ key: 'model', type: 'enum', options: names, description: 'pedestrian model (docs/scenario-format.md, Models)' },
      name, (v) => write(v, {})));
    for (const f of modelParameters(this.schema, name)) {
      this.root.append(this.input(f, params[f.key], (v) => write(name, { ...params, [f.key]: v })));
    }
  }
}
