#!/usr/bin/env bash
# ctest web_build_script: scripts/deps.sh's throng_build_web (what scripts/demo.sh and
# scripts/test.sh run) fails — returns non-zero and says what is missing and how to get it — when
# node or npm is missing, node is older than 18, `npm ci` fails or `npm run build` fails, and
# succeeds when all is there. node and npm are stubs on a PATH of their own; nothing is installed.
#   build_web_test.sh scripts/deps.sh
set -uo pipefail
deps="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/root/web" "$tmp/bin"
echo '{}' > "$tmp/root/web/package-lock.json"
ln -s "$(command -v touch)" "$tmp/bin/touch"
ln -s "$(command -v mkdir)" "$tmp/bin/mkdir"
failures=0

# stub NAME SCRIPT: an executable $tmp/bin/NAME running SCRIPT with /bin/sh.
stub() { printf '#!/bin/sh\n%s\n' "$2" > "$tmp/bin/$1"; chmod +x "$tmp/bin/$1"; }
# expect RC PATTERN CASE: runs throng_build_web with PATH=$tmp/bin, checks its status and output.
expect() {
  local want="$1" pattern="$2" name="$3" out rc
  out="$(PATH="$tmp/bin" "$BASH" -c 'source "$1"; throng_build_web "$2"' bash "$deps" "$tmp/root" 2>&1)"
  rc=$?
  if [ "$want" = fail ] && [ "$rc" -eq 0 ]; then
    echo "FAIL: $name: throng_build_web returned 0 (want non-zero); it said: $out"; failures=$((failures + 1))
  elif [ "$want" = ok ] && [ "$rc" -ne 0 ]; then
    echo "FAIL: $name: throng_build_web returned $rc (want 0); it said: $out"; failures=$((failures + 1))
  elif ! grep -q -- "$pattern" <<< "$out"; then
    echo "FAIL: $name: output lacks '$pattern': $out"; failures=$((failures + 1))
  else
    echo "ok: $name (status $rc): $(head -c 300 <<< "$out" | tr '\n' ' ')"
  fi
}

expect fail 'apt-get install nodejs npm' 'no node, no npm'
stub npm 'exit 0'
expect fail 'apt-get install nodejs npm' 'npm but no node'
stub node 'case "$1" in --version) echo v16.20.2;; -e) exit 1;; esac'
expect fail 'v16.20.2 is too old' 'node 16'
stub node 'case "$1" in --version) echo v18.20.4;; -e) exit 0;; esac'
stub npm 'case "$1" in ci) echo "npm ERR! network"; exit 1;; esac; exit 0'
expect fail 'npm ci failed' 'npm ci fails (offline)'
stub npm 'case "$1" in ci) mkdir -p node_modules;; run) echo "vite: build error"; exit 1;; esac'
expect fail 'build failed' 'npm run build fails'
stub npm 'case "$1" in ci) mkdir -p node_modules;; run) echo "built web/dist";; esac'
rm -rf "$tmp/root/web/node_modules"
expect ok 'built web/dist' 'node 18 and npm: npm ci and the build run'

[ "$failures" -eq 0 ] || { echo "$failures case(s) failed"; exit 1; }
