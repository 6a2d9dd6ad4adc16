#!/usr/bin/env bash
# The README's second command (and CI's): install what is missing, build everything, run the
# whole test suite with ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/deps.sh"
throng_install_deps
throng_build "$root"
throng_build_web "$root"
cd "$root/build"
ctest --output-on-failure -j "$(nproc)" --timeout 600 "$@"
