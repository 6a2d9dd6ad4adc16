#!/usr/bin/env bash
# Long fuzzing runs: builds the libFuzzer targets (clang) and fuzzes each for SECONDS of wall-clock
# time, then merges what was found into the committed corpus (fuzz/corpus/<name>/: only inputs that
# add coverage are kept, `-merge=1`). Prints executions, coverage and corpus size per target.
#
#   scripts/fuzz.sh                      # every target, 600 s each
#   scripts/fuzz.sh -t 3600 scenario gltf  # two targets, an hour each
#   scripts/fuzz.sh --no-merge -t 60     # fuzz only; leave fuzz/corpus/ as it is
#   scripts/fuzz.sh --help
#
# A crash or leak stops that target with libFuzzer's report; the input is in
# build/fuzz/artifacts/<name>/ — add it to fuzz/corpus/<name>/ once fixed (a regression test:
# ctest's fuzz_<name>_corpus replays every corpus file).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds=600
merge=1
targets=()
usage() { sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; }
while [ $# -gt 0 ]; do
  case "$1" in
    -t|--seconds) [ $# -ge 2 ] || { echo "fuzz.sh: $1 needs a number of seconds" >&2; exit 2; }; seconds="$2"; shift 2 ;;
    --no-merge) merge=0; shift ;;
    -h|--help) usage; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
case "$seconds" in ''|*[!0-9]*) echo "fuzz.sh: --seconds wants a whole number, got '$seconds'" >&2; exit 2 ;; esac

source "$root/scripts/deps.sh"
throng_install_deps
if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz.sh: clang++ is needed for libFuzzer (apt-get install clang libclang-rt-14-dev)" >&2
  exit 1
fi
throng_build "$root"
if [ ${#targets[@]} -eq 0 ]; then
  for d in "$root"/fuzz/corpus/*/; do targets+=("$(basename "$d")"); done
fi
summary=()
failed=0
for name in "${targets[@]}"; do
  exe="$root/build/fuzz/fuzz_$name"
  corpus="$root/fuzz/corpus/$name"
  [ -x "$exe" ] || { echo "fuzz.sh: no fuzz target '$name' (expected $exe)" >&2; exit 2; }
  work="$root/build/fuzz/long/$name"
  artifacts="$root/build/fuzz/artifacts/$name/"
  mkdir -p "$work" "$artifacts"
  dict=()
  [ -f "$root/fuzz/$name.dict" ] && dict=(-dict="$root/fuzz/$name.dict")
  before=$(find "$corpus" -type f | wc -l)
  echo "== fuzz_$name: ${seconds} s, corpus $before files"
  log="$work.log"
  set +e
  "$exe" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
         -artifact_prefix="$artifacts" "${dict[@]}" "$work" "$corpus" 2>&1 | tee "$log" | grep -E "^#[0-9]+.*(pulse|DONE)|ERROR|stat::"
  status=${PIPESTATUS[0]}
  set -e
  execs=$(grep -h "stat::number_of_executed_units" "$log" | awk '{s += $2} END {print s + 0}')
  if [ "$merge" -eq 1 ]; then
    "$exe" -merge=1 -rss_limit_mb=2048 "$corpus" "$work" >/dev/null 2>&1
  fi
  after=$(find "$corpus" -type f | wc -l)
  summary+=("$(printf '%-18s %12s executions  corpus %4d -> %4d  exit %d' "$name" "$execs" "$before" "$after" "$status")")
  if [ "$status" -ne 0 ]; then
    echo "fuzz.sh: fuzz_$name failed (exit $status): see $log and $artifacts" >&2
    failed=1
  fi
done
echo
echo "target             executions            corpus files"
printf '%s\n' "${summary[@]}"
exit $failed
