#!/usr/bin/env bash
# Builds benches/external/rvo2_driver.cpp against an RVO2 checkout (github.com/snape/RVO2; not a
# Debian package, so never part of throng's build) and prints where the program is.
#   scripts/bench_rvo2.sh /path/to/RVO2 [OUT_DIR=build/rvo2]
# Then, side by side with throng on the same machine (docs/performance.md, "Against RVO2"):
#   OMP_NUM_THREADS=1 build/rvo2/rvo2_driver 100000 20 10
#   build/apps/throng/throng bench --agents 100000 --threads 1 --no-baseline --json
set -euo pipefail
if [[ $# -lt 1 || ! -f "$1/src/RVOSimulator.cc" ]]; then
  echo "usage: $0 RVO2_CHECKOUT [OUT_DIR]  (RVO2_CHECKOUT/src/RVOSimulator.cc must exist)" >&2
  exit 2
fi
rvo="$1/src"
out="${2:-build/rvo2}"
here="$(cd "$(dirname "$0")/.." && pwd)"
mkdir -p "$out"
${CXX:-g++} -std=c++17 -O3 -fopenmp -DNDEBUG -I"$rvo" \
  "$rvo"/Agent.cc "$rvo"/KdTree.cc "$rvo"/Line.cc "$rvo"/Obstacle.cc "$rvo"/RVOSimulator.cc "$rvo"/Vector2.cc \
  "$here/benches/external/rvo2_driver.cpp" -o "$out/rvo2_driver"
if git -C "$1" rev-parse HEAD >/dev/null 2>&1; then
  echo "RVO2 commit $(git -C "$1" rev-parse HEAD)"
fi
echo "$out/rvo2_driver"
