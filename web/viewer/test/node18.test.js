// The viewer's toolchain installs and runs on Debian 12's own node (18.20.4, what
// `apt-get install nodejs` gives and scripts/deps.sh accepts): every package web/package-lock.json
// installs declares an engines.node range (if any) that admits it, and so does web/package.json.
// Vite 7+ and playwright-core 1.62+ need node 20 and would make the README's commands build no
// viewer on a stock Debian 12 machine (docs/viewer.md, "Dependencies").
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const webRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const debianNode = '18.20.4';

// A small subset of npm's semver ranges, enough for engines fields: `||`, space-separated
// comparators (<, <=, >, >=, =), caret and tilde ranges, x/* and missing parts.
function parts(v) {
  return v.replace(/^v/, '').split('.').map((p) => (p === '' || p === 'x' || p === 'X' || p === '*' ? null : Number(p)));
}
function cmp(a, b) {
  for (let i = 0; i < 3; ++i) if ((a[i] ?? 0) !== (b[i] ?? 0)) return (a[i] ?? 0) < (b[i] ?? 0) ? -1 : 1;
  return 0;
}
function comparator(version, c) {
  const m = /^(<=|>=|<|>|=|\^|~)?\s*v?([0-9xX*][0-9xX*.]*)?$/.exec(c);
  if (!m) throw new Error(`unsupported range part '${c}'`);
  const op = m[1] || '';
  const p = parts(m[2] || '*');
  while (p.length < 3) p.push(null);
  const known = p.findIndex((x) => x === null);
  const n = known === -1 ? 3 : known; // number of given parts
  const lo = p.map((x) => x ?? 0);
  const v = parts(version);
  if (op === '>=') return cmp(v, lo) >= 0;
  if (op === '>') return n === 3 ? cmp(v, lo) > 0 : cmp(v, bump(lo, n - 1)) >= 0;
  if (op === '<') return cmp(v, lo) < 0;
  if (op === '<=') return n === 3 ? cmp(v, lo) <= 0 : cmp(v, bump(lo, n - 1)) < 0;
  if (n === 0) return true;
  let hi;
  if (op === '^') hi = bump(lo, lo[0] !== 0 || n === 1 ? 0 : lo[1] !== 0 || n === 2 ? 1 : 2);
  else if (op === '~') hi = bump(lo, n === 1 ? 0 : 1);
  else hi = bump(lo, n - 1); // x-range or exact
  if (op === '' || op === '=') { if (n === 3) return cmp(v, lo) === 0; }
  return cmp(v, lo) >= 0 && cmp(v, hi) < 0;
}
function bump(v, i) {
  const r = [...v];
  r[i] += 1;
  for (let j = i + 1; j < 3; ++j) r[j] = 0;
  return r;
}
export function satisfies(version, range) {
  return range.split('||').some((set) => {
    const cs = set.trim().replace(/(<=|>=|<|>|=|\^|~)\s+/g, '$1').split(/\s+/).filter(Boolean);
    return cs.every((c) => comparator(version, c));
  });
}

test('the range checker agrees with npm on the forms engines fields use', () => {
  assert.ok(satisfies('18.20.4', '>=18'));
  assert.ok(satisfies('18.20.4', '>= 12.0.0'));
  assert.ok(satisfies('18.20.4', '^18.0.0 || ^20.0.0 || >=22.0.0'));
  assert.ok(satisfies('18.20.4', '^10 || ^12 || ^13.7 || ^14 || >=15.0.1'));
  assert.ok(satisfies('18.20.4', '>=14.17 <19'));
  assert.ok(satisfies('18.20.4', '~18.20.1'));
  assert.ok(satisfies('18.20.4', '18.x'));
  assert.ok(!satisfies('18.20.4', '>=20'));
  assert.ok(!satisfies('18.20.4', '^20.19.0 || >=22.12.0'));
  assert.ok(!satisfies('18.20.4', '^20.19.0 || ^22.13.0 || >=23.5.0'));
  assert.ok(!satisfies('18.20.4', '~18.21.0'));
  assert.ok(!satisfies('18.20.4', '>18.20.4'));
  assert.ok(!satisfies('18.20.4', '<18.20'));
  assert.ok(!satisfies('18.20.4', '^18.21'));
  assert.ok(satisfies('20.20.2', '^20.19.0 || >=22.12.0'));
});

test(`every package of web/package-lock.json runs on Debian 12's node ${debianNode}`, () => {
  const lock = JSON.parse(fs.readFileSync(path.join(webRoot, 'package-lock.json'), 'utf8'));
  const pkgs = Object.entries(lock.packages || {});
  assert.ok(pkgs.length > 5, `web/package-lock.json lists ${pkgs.length} packages (lockfileVersion 3 expected)`);
  const refused = pkgs
    .filter(([, p]) => p.engines && typeof p.engines.node === 'string' && !satisfies(debianNode, p.engines.node))
    .map(([name, p]) => `${name || '(web/package.json)'}@${p.version} needs node ${p.engines.node}`);
  assert.deepEqual(refused, [], `packages that refuse node ${debianNode}:\n${refused.join('\n')}`);
  const own = JSON.parse(fs.readFileSync(path.join(webRoot, 'package.json'), 'utf8'));
  assert.ok(own.engines && satisfies(debianNode, own.engines.node), `web/package.json engines ${JSON.stringify(own.engines)}`);
});
