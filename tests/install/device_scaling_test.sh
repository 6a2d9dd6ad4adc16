#!/usr/bin/env bash
# device_scaling: scripts/device_scaling.sh packs the build into a folder that runs on a machine
# without throng's packages (the lent many-core machine of docs/performance.md, "16 cores"), and
# its measuring part runs from that folder alone: `pack`, then the `avm` and `simd` parts at 1/100
# of the agents (QUICK=1) with the program and libraries taken from the folder (ldd must resolve
# every throng library there), and the summary must list the three avm runs and the four on the
# portable SIMD path.
#   device_scaling_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
bash "$src/scripts/device_scaling.sh" pack "$tmp/dev" "$build" >/dev/null
[[ -x $tmp/dev/bin/throng ]] || { echo "pack left no bin/throng"; exit 1; }
# Every throng library the program needs comes from the folder, none from the build tree.
missing=$(LD_LIBRARY_PATH="$tmp/dev/lib" ldd "$tmp/dev/bin/throng" | awk '/libthrong_/ && $3 !~ "^'"$tmp"'/dev/lib/" {print $1}')
[[ -z $missing ]] || { echo "not packed: $missing"; exit 1; }
summary=$(QUICK=1 bash "$src/scripts/device_scaling.sh" "$tmp/dev" "$tmp/out" avm simd)
echo "$summary"
rows=$(grep -c '"model":"avm"' "$tmp/out/throng.jsonl" || true)
[[ $rows == 5 ]] || { echo "expected 5 avm runs in throng.jsonl (3 + 2 portable), got $rows"; exit 1; }
for t in 1 4 16; do
  grep -Eq "^throng avm (avx2|portable) 1000 $t " <<<"$summary" || { echo "summary lacks the $t-thread row"; exit 1; }
done
for model in orca avm; do
  for t in 1 16; do
    grep -q "^throng $model portable 1000 $t " <<<"$summary" || { echo "summary lacks the portable $model $t-thread row"; exit 1; }
  done
done
echo "device_scaling: ok"
