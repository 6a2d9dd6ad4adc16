#!/usr/bin/env bash
# Thread and rank scaling of a built throng on a many-core machine that has no package registry
# (docs/performance.md "16 cores", docs/scaling.md "Measured on 16 cores"). Everything it needs is
# carried in one folder DEV, made on the build machine by
#   scripts/device_scaling.sh pack DEV [BUILD=build]
# DEV/bin/throng, DEV/bin/rvo2_driver (when BUILD/rvo2 has it: scripts/bench_rvo2.sh), DEV/lib/*.so
# (throng's libraries and every dependency but glibc's), DEV/mpi.tar.xz when OpenMPI is installed
# (Debian's OpenMPI files, unpacked into / there without replacing any file already there). Then,
# on the many-core machine:
#   scripts/device_scaling.sh DEV OUT [parts: threads rvo2 avm simd mpi]
# Writes OUT/*.jsonl (one JSON object per run) and OUT/log.txt; prints a summary table last.
set -uo pipefail
if [[ ${1:-} == pack ]]; then
  dev="$2"; build="${3:-build}"
  mkdir -p "$dev/bin" "$dev/lib"
  cp "$build/apps/throng/throng" "$dev/bin/"
  [[ -x $build/rvo2/rvo2_driver ]] && cp "$build/rvo2/rvo2_driver" "$dev/bin/"
  for f in $(ldd "$dev"/bin/* | awk '/=>/{print $3}' | sort -u); do
    case $(basename "$f") in libc.so*|libm.so*|libpthread*|libdl.so*|librt.so*|ld-linux*) ;; *) cp -L "$f" "$dev/lib/";; esac
  done
  strip --strip-unneeded "$dev"/bin/* "$dev"/lib/libthrong_* 2>/dev/null
  if dpkg -s openmpi-bin >/dev/null 2>&1; then
    files=$(dpkg -L openmpi-bin libopenmpi3 openmpi-common libpmix2 libhwloc15 2>/dev/null |
            grep -v '/doc/\|/man/\|lintian' | while read -r f; do [[ -f $f || -L $f ]] && echo "$f"; done)
    deps=$(for f in $files; do case $f in *.so*|/usr/bin/*) ldd "$f" 2>/dev/null;; esac; done |
           awk '/=>/{print $3}' | sort -u | grep -v 'libc.so\|libm.so\|libpthread\|libdl.so\|librt.so\|ld-linux')
    (for f in $files $deps; do echo "${f#/}"; done; for d in $deps; do r=$(readlink -f "$d"); echo "${r#/}"; done) |
      sort -u | tar -C / -cJf "$dev/mpi.tar.xz" -T -
  fi
  du -sh "$dev"
  exit 0
fi
dev="$(cd "$1" && pwd)"; out="$2"; shift 2
parts="${*:-threads rvo2 avm simd mpi}"
# QUICK=1: tiny sizes, to check the script itself on the build machine.
K=1; [[ ${QUICK:-0} == 1 ]] && K=100
mkdir -p "$out"
export LD_LIBRARY_PATH="$dev/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
T="$dev/bin/throng"; R="$dev/bin/rvo2_driver"
log() { echo "$*" | tee -a "$out/log.txt"; }
log "machine: $(nproc) cpus, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2), $(free -g | awk '/Mem/{print $2}') GiB"
"$T" --version >>"$out/log.txt" 2>&1 || { log "throng does not start:"; ldd "$T" | tee -a "$out/log.txt"; exit 1; }

if [[ $parts == *threads* ]]; then
  log "== throng ORCA, random, 100k: threads 1 2 4 8 16"
  timeout 150 "$T" bench --agents $((100000 / K)) --threads 1,2,4,8,16 --ticks 20 --no-baseline --phase-times --json \
    >>"$out/throng.jsonl" 2>>"$out/log.txt"
  log "== throng ORCA, random, 1M: threads 1 4 8 16"
  timeout 240 "$T" bench --agents $((1000000 / K)) --threads 1,4,8,16 --ticks 6 --warmup 10 --no-baseline --phase-times --json \
    >>"$out/throng.jsonl" 2>>"$out/log.txt"
fi
if [[ $parts == *rvo2* ]]; then
  for n in $((100000 / K)) $((1000000 / K)); do
    steps=20; [[ $n == $((1000000 / K)) ]] && steps=6
    for t in 1 4 8 16; do
      OMP_NUM_THREADS=$t timeout 120 "$R" $n $steps 10 >>"$out/rvo2.jsonl" 2>>"$out/log.txt"
    done
  done
fi
if [[ $parts == *avm* ]]; then
  log "== throng avm, random, 100k: threads 1 4 16"
  timeout 120 "$T" bench --agents $((100000 / K)) --threads 1,4,16 --ticks 20 --model avm --no-baseline --phase-times --json \
    >>"$out/throng.jsonl" 2>>"$out/log.txt"
fi
if [[ $parts == *simd* ]]; then
  log "== throng ORCA and avm, random, 100k, the portable SIMD path (the runs above take the widest the CPU has)"
  for model in orca avm; do
    THRONG_SIMD=portable timeout 120 "$T" bench --agents $((100000 / K)) --threads 1,16 --ticks 20 --model $model --no-baseline \
      --json >>"$out/throng.jsonl" 2>>"$out/log.txt"
  done
fi
if [[ $parts == *mpi* && -f $dev/mpi.tar.xz ]]; then
  log "== MPI (replicated control, shared steer): strong 100k and weak 50k per rank"
  tar -C / --skip-old-files -xJf "$dev/mpi.tar.xz" 2>>"$out/log.txt"; ldconfig 2>/dev/null
  mpi=(mpirun --allow-run-as-root --oversubscribe --bind-to none --mca btl self,vader
       --mca btl_vader_single_copy_mechanism none -x LD_LIBRARY_PATH)
  mk() {  # N agents wandering in a square at 1 agent/m² (the layout of `throng bench --scenario random`)
    python3 - "$1" "$2" <<'PY'
import json, math, sys
n = int(sys.argv[1]); s = round(math.sqrt(n), 1)
sq = [[0, 0], [s, 0], [s, s], [0, s]]
json.dump({"format": "throng/1", "name": f"random{n}", "seed": 1, "duration": 2,
           "walkable": [sq], "populations": [{"id": "walkers", "groups": n, "size": 1,
           "spawn": {"polygon": sq}, "wander": True, "speed": {"mean": 1.3, "sd": 0}, "radius": 0.2}]},
          open(sys.argv[2], "w"))
PY
  }
  for spec in "1 100000" "2 100000" "4 100000" "8 100000" "2 200000" "4 400000" "8 800000" "1 200000" "1 400000"; do
    set -- $spec; r=$1; n=$(($2 / K)); f="/tmp/random$n.json"; [[ -f $f ]] || mk $n $f
    if [[ $r == 1 ]]; then cmd=("$T"); else cmd=("${mpi[@]}" -np $r "$T"); fi
    s=$(date +%s%N)
    line=$(timeout 150 "${cmd[@]}" run "$f" --threads 1 --fps 1 --phase-times --json -q --force --out /tmp/r.sqlite 2>>"$out/log.txt" | tail -1)
    ms=$(( ($(date +%s%N) - s) / 1000000 ))
    echo "{\"ranks\":$r,\"agents\":$n,\"wall_total_ms\":$ms,\"summary\":${line:-null}}" >>"$out/mpi.jsonl"
    log "ranks $r agents $n: $ms ms"
  done
fi
python3 - "$out" <<'PY'
import json, sys, os
out = sys.argv[1]
def rows(name):
    p = os.path.join(out, name)
    return [json.loads(l) for l in open(p) if l.startswith("{")] if os.path.exists(p) else []
print("engine model simd agents threads Msteps/s ms/tick")
for r in rows("throng.jsonl") + rows("rvo2.jsonl"):
    print(r["engine"], r.get("model", "-"), r.get("simd", "-"), r["agents"], r["threads"],
          round(r["agent_steps_per_s"] / 1e6, 3), round(r["ms_per_tick_median"], 1))
for r in rows("mpi.jsonl"):
    s = r["summary"] or {}
    print("mpi ranks", r["ranks"], "agents", r["agents"], "wall", r["wall_total_ms"], "hash", s.get("state_hash"))
PY
