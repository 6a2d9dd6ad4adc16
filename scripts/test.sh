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
ctest --output-on-failure -j "$(nproc)" --timeout 600 "$@"
