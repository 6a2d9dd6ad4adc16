#!/usr/bin/env bash
# The README's second command (and CI's): install what is missing, build everything, run the
# whole test suite with ctest, the viewer's JavaScript and browser tests included (a missing
# component — node, npm, web/node_modules, web/dist, chromium — fails them; nothing is skipped).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/deps.sh"
throng_install_deps
throng_build "$root"
throng_build_web "$root"
cd "$root/build"
# A skipped test is a failure here: ctest exits 0 when tests only skip (GTEST_SKIP), so its summary
# is read for "(Skipped)" too.
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
set +e
ctest --output-on-failure -j "$(nproc)" --timeout 600 "$@" 2>&1 | tee "$log"
rc=${PIPESTATUS[0]}
set -e
skipped="$(grep -E '^[[:space:]]*[0-9]+ - .* \((Skipped|Disabled)\)$' "$log" || true)"
if [ -n "$skipped" ]; then
  echo "throng: error: tests did not run (a skip counts as a failure; see their output above):" >&2
  echo "$skipped" >&2
  exit 1
fi
exit "$rc"
