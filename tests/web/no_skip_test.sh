#!/usr/bin/env bash
# ctest tests_never_skip: a missing component makes a test fail, never pass or skip.
# - No ctest test of the build carries SKIP_RETURN_CODE, nor SKIP_REGULAR_EXPRESSION other than
#   GoogleTest's "[  SKIPPED ]" (tests/web/skip_properties.cmake), so no missing component turns a
#   test into "skipped" or "passed"; scripts/test.sh fails when any test is reported skipped.
# - tests/web/node_test.cmake (protocol_js_decoder, viewer_js_unit, viewer_e2e, editor_js_unit, editor_e2e) fails, naming what
#   is missing, without node, without a REQUIRE path (web/node_modules, web/dist, chromium), when
#   its globs match nothing and when a test file fails; runs every file with ONE_BY_ONE even after
#   a failure; passes when its tests pass.
#   no_skip_test.sh BUILD_DIR SOURCE_DIR
set -uo pipefail
build="$1"
src="$2"
runner="$src/tests/web/node_test.cmake"
cmake="$(command -v cmake)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

if out="$("$cmake" -DBUILD="$build" -P "$src/tests/web/skip_properties.cmake" 2>&1)"; then
  echo "ok: $out"
else
  fail "$out"
fi
json="$(cd "$build" && ctest --show-only=json-v1)" || fail "ctest --show-only=json-v1 failed in $build"
for t in protocol_js_decoder viewer_js_unit viewer_e2e editor_js_unit editor_e2e; do
  grep -q "\"name\" : \"$t\"" <<< "$json" && echo "ok: $t registered" || fail "$t is not registered"
done

mkdir -p "$tmp/empty" "$tmp/t"
node="$(command -v node || true)"
[ -n "$node" ] || { echo "FAIL: node not found: apt-get install nodejs npm (scripts/test.sh does it)"; exit 1; }
printf "import { test } from 'node:test';\ntest('passes', () => {});\n" > "$tmp/t/a.test.mjs"
printf "import { test } from 'node:test';\nimport fs from 'node:fs';\ntest('fails', () => { fs.writeFileSync('%s/b.ran', ''); throw new Error('red'); });\n" "$tmp" > "$tmp/t/b.test.mjs"
printf "import { test } from 'node:test';\nimport fs from 'node:fs';\ntest('runs after a failure', () => { fs.writeFileSync('%s/c.ran', ''); });\n" "$tmp" > "$tmp/t/c.test.mjs"

# run WANT PATTERN NAME cmake-args...: node_test.cmake's status (fail: non-zero) and output.
run() {
  local want="$1" pattern="$2" name="$3" out rc
  shift 3
  out="$("$@" -P "$runner" 2>&1)"
  rc=$?
  if { [ "$want" = fail ] && [ "$rc" -eq 0 ]; } || { [ "$want" = ok ] && [ "$rc" -ne 0 ]; }; then
    fail "$name: status $rc (want $want): $out"
  elif ! grep -q -- "$pattern" <<< "$out"; then
    fail "$name: output lacks '$pattern': $out"
  else
    echo "ok: $name (status $rc)"
  fi
}
run fail 'node not found' 'no node on PATH' env PATH="$tmp/empty" "$cmake" -DNODE=NODE-NOTFOUND "-DGLOBS=$tmp/t/a.test.mjs"
run fail "$tmp/missing/node_modules is missing" 'web/node_modules absent' "$cmake" "-DNODE=$node" "-DGLOBS=$tmp/t/a.test.mjs" "-DREQUIRE=$tmp/t;$tmp/missing/node_modules"
run fail 'no test file matches' 'no test file' "$cmake" "-DNODE=$node" "-DGLOBS=$tmp/t/*.nothing.js"
run fail 'failed' 'a failing test file' "$cmake" "-DNODE=$node" "-DGLOBS=$tmp/t/b.test.mjs"
rm -f "$tmp/b.ran" "$tmp/c.ran"
run fail 'b.test.mjs' 'one by one, a failure among three' "$cmake" "-DNODE=$node" "-DGLOBS=$tmp/t/*.test.mjs" -DONE_BY_ONE=ON
[ -f "$tmp/b.ran" ] && [ -f "$tmp/c.ran" ] && echo "ok: one by one ran every file" || fail "one by one did not run every file"
rm -f "$tmp/t/b.test.mjs"
run ok '# fail 0' 'passing tests' "$cmake" "-DNODE=$node" "-DGLOBS=$tmp/t/*.test.mjs" "-DREQUIRE=$tmp/t"

[ "$failures" -eq 0 ] || { echo "$failures check(s) failed"; exit 1; }
