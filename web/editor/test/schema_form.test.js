// Unit tests of web/editor/src/schema_form.js against the real scenario JSON Schema: the models
// and their parameters (each with the limits and default the schema gives), object fields, model
// values read and written, and what typed text becomes (limits named in the message).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import {
  coerce, modelNames, modelParameters, objectFields, readModel, resolve, variantFields, variantNames, writeModel,
} from '../src/schema_form.js';

const schema = JSON.parse(fs.readFileSync(new URL('../../../scenarios/schema/scenario.schema.json', import.meta.url), 'utf8'));

test('every model of the schema, each with its parameters', () => {
  const names = modelNames(schema);
  assert.ok(names.includes('orca') && names.includes('avm') && names.includes('cfsm'), names.join());
  const model = resolve(schema, schema.$defs.model);
  for (const name of names) {
    const form = model.oneOf.find((o) => o.type === 'object' && o.properties?.name?.const === name);
    const params = modelParameters(schema, name);
    assert.deepEqual(params.map((p) => p.key), Object.keys(form.properties).filter((k) => k !== 'name'), name);
    for (const p of params) assert.ok(['number', 'integer', 'boolean', 'enum', 'string'].includes(p.type), `${name}.${p.key}`);
  }
  const orca = Object.fromEntries(modelParameters(schema, 'orca').map((p) => [p.key, p]));
  assert.equal(orca.yieldResponsibility.minimum, 0.5);
  assert.equal(orca.yieldResponsibility.maximum, 1);
  assert.equal(orca.yieldResponsibility.default, 0.8);
  assert.equal(orca.lodNeighbours.type, 'integer');
  assert.deepEqual(modelParameters(schema, 'nope'), []);
});

test('object fields follow $ref and keep the schema order', () => {
  const fields = objectFields(schema, schema.$defs.population, ['groups', 'radius', 'spawn', 'wander']);
  assert.deepEqual(fields.map((f) => f.key), ['groups', 'radius', 'wander']);  // spawn is not a simple value
  assert.equal(fields[0].type, 'integer');
  assert.equal(fields[1].minimum, 0.05);
  const kind = objectFields(schema, schema.$defs.point, ['kind'])[0];
  assert.equal(kind.type, 'enum');
  assert.deepEqual(kind.options, ['interest', 'action', 'exit']);
});

test('model values: a bare name without parameters, else an object', () => {
  assert.deepEqual(readModel(undefined), { name: 'avm', params: {} });
  assert.deepEqual(readModel('avm'), { name: 'avm', params: {} });
  assert.deepEqual(readModel({ name: 'cfsm', timeGap: 0.8 }), { name: 'cfsm', params: { timeGap: 0.8 } });
  assert.equal(writeModel('avm', {}), 'avm');
  assert.equal(writeModel('avm', { timeGap: undefined }), 'avm');
  assert.deepEqual(writeModel('cfsm', { timeGap: 0.8 }), { name: 'cfsm', timeGap: 0.8 });
});

test('typed text: numbers within limits, whole numbers, enums, empty means the default', () => {
  const f = { key: 'x', type: 'number', minimum: 0.5, maximum: 1 };
  assert.deepEqual(coerce(f, '0.75'), { value: 0.75 });
  assert.deepEqual(coerce(f, ''), { value: undefined });
  assert.match(coerce(f, '0.3').error, /below the minimum 0\.5/);
  assert.match(coerce(f, '2').error, /above the maximum 1/);
  assert.match(coerce(f, 'abc').error, /not a number/);
  assert.match(coerce({ key: 'n', type: 'integer' }, '2.5').error, /whole number/);
  assert.match(coerce({ key: 't', type: 'number', exclusiveMinimum: 0 }, '0').error, /above 0/);
  assert.deepEqual(coerce({ key: 'b', type: 'boolean' }, true), { value: true });
  assert.match(coerce({ key: 'k', type: 'enum', options: ['a', 'b'] }, 'c').error, /one of a, b/);
});

test('pre-movement distributions and their keys, from the schema', () => {
  const node = schema.$defs.preMovement;
  assert.deepEqual(variantNames(schema, node, 'distribution'), ['uniform', 'normal', 'lognormal']);
  assert.deepEqual(variantFields(schema, node, 'distribution', 'uniform').map((f) => f.key), ['min', 'max']);
  const lognormal = Object.fromEntries(variantFields(schema, node, 'distribution', 'lognormal').map((f) => [f.key, f]));
  assert.equal(lognormal.mu.minimum, -10);
  assert.equal(lognormal.sigma.maximum, 3);
  assert.deepEqual(variantFields(schema, node, 'distribution', 'weibull'), []);
});
