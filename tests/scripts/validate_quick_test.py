#!/usr/bin/python3
"""End-to-end test of scripts/validate.py (ctest: validate_script_quick): runs it as a user would,
with --quick on the experiments that need no external data, and checks that it works and reports
every field: a row per target with a band and a status, every experiment's figures in --json, the
PNGs, the table on stdout, exit 2 for bad flags, --check's exit status and --keep. It does not
assert the bands (the current models do not pass them yet).

usage: validate_quick_test.py THRONG_BINARY"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "scripts", "validate.py")
EXPERIMENTS = "ring,single-file,bottleneck,room,counterflow,door"
TARGET_KEYS = {"experiment", "target", "measured", "band", "unit", "status", "note"}
# Targets each experiment must report (a prefix of the target name) and its result keys.
EXPECTED = {
    "ring": (["speed at 0.5 /m²", "speed at 5 /m²", "backward samples at 5 /m²"], ["densities", "sector_area_m2"]),
    "single-file": (["speed at 1 /m", "speed at 2 /m", "backward samples at 2 /m", "max overlap depth at 2 /m"],
                    ["densities", "mid_circumference_m"]),
    "bottleneck": ([f"{w} m accepted by throng check" for w in ("0.5", "0.6", "0.7", "0.8", "1.0", "1.2")]
                   + ["0.5 m flow", "1.2 m flow", "0.5 m longest gap", "1.2 m longest gap"], ["widths"]),
    "room": (["door flow", "max overlap depth after 1 s", "max walk-back from the door"],
             ["flow", "max_overlap", "max_walk_back"]),
    "counterflow": (["lane order", "no deadlock"], ["lane_order", "lane_order_shuffled"]),
    "door": (["1 m door flow"], ["flow"]),
}
PLOTS = ["ring", "single-file", "bottleneck-widths", "bottleneck"]


def fail(msg):
    print(f"validate_quick_test: FAIL: {msg}")
    sys.exit(1)


def run(args):
    return subprocess.run([sys.executable, SCRIPT] + args, capture_output=True, text=True, timeout=300)


def check_summary(summary):
    rows = summary["targets"]
    for r in rows:
        if set(r) != TARGET_KEYS or r["status"] not in ("PASS", "FAIL", "INFO"):
            fail(f"malformed target row {r}")
        if r["status"] != "INFO" and (r["band"] is None or len(r["band"]) != 2):
            fail(f"target without band: {r}")
    for exp, (targets, keys) in EXPECTED.items():
        names = [r["target"] for r in rows if r["experiment"] == exp]
        for t in targets:
            if not any(n.startswith(t) for n in names):
                fail(f"{exp}: no target '{t}' in {names}")
        for k in keys:
            if k not in summary["results"].get(exp, {}):
                fail(f"{exp}: no result '{k}' in --json")
    # Measured values where the runs produced data (a refused bottleneck may have none).
    for r in rows:
        if r["experiment"] in ("ring", "single-file", "room", "counterflow", "door") and r["measured"] is None:
            fail(f"no measurement for {r['experiment']}: {r['target']}")
    for rho, row in summary["results"]["ring"]["densities"].items():
        if row["spawned"] != [row["agents"]]:
            fail(f"ring {rho} /m²: spawned {row['spawned']} of {row['agents']}")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    throng = sys.argv[1]
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
    except ImportError as e:
        fail(f"{e}: apt-get install python3-numpy python3-matplotlib (scripts/deps.sh does it)")
    with tempfile.TemporaryDirectory(prefix="validate-test-") as tmp:
        out = os.path.join(tmp, "v.json")
        res = run(["--throng", throng, "--quick", "--only", EXPERIMENTS, "--model", "orca", "--json", out,
                   "--out-dir", tmp])
        if res.returncode != 0:
            fail(f"exit {res.returncode}: {res.stderr[-2000:]}")
        if "result" not in res.stdout or "passed," not in res.stdout:
            fail(f"no table on stdout: {res.stdout[:500]}")
        if "validate: run ring" not in res.stderr:
            fail("no progress lines on stderr")
        with open(out) as f:
            summary = json.load(f)
        if summary["model"] != "orca" or summary["seeds"] != [1]:
            fail(f"model/seeds not recorded: {summary['model']}, {summary['seeds']}")
        check_summary(summary)
        for p in PLOTS:
            path = os.path.join(tmp, f"validation-{p}-orca.png")
            if not os.path.isfile(path) or os.path.getsize(path) < 1000:
                fail(f"plot {path} missing")
        # --check: exit 1 exactly when a target failed (the same quick run is deterministic).
        failed = any(r["status"] == "FAIL" for r in summary["targets"])
        keep = os.path.join(tmp, "keep")
        res = run(["--throng", throng, "--quick", "--only", "door", "--model", "orca", "--no-plots", "--check",
                   "--keep", keep])
        door_failed = "FAIL" in res.stdout.split("result", 1)[-1]
        if res.returncode != (1 if door_failed else 0):
            fail(f"--check exit {res.returncode} with door failed = {door_failed}")
        # --keep: the scenario as run (model applied) and its recording stay.
        with open(os.path.join(keep, "door-s1.json")) as f:
            if any(p.get("model") != "orca" for p in json.load(f)["populations"]):
                fail("--keep: the kept scenario does not carry --model")
        if not os.path.isfile(os.path.join(keep, "door-s1.sqlite")):
            fail("--keep: no recording kept")
        print(f"quick run: {len(summary['targets'])} targets, any failed: {failed}")
    for bad in (["--only", "nosuch"], ["--model", "{not json"], ["--model", "nosuchmodel", "--only", "door"],
                ["--seeds", "0"]):
        res = run(["--throng", throng, "--no-plots"] + bad)
        if res.returncode != 2:
            fail(f"{bad}: exit {res.returncode}, expected 2 ({res.stderr[-300:]})")
    print("validate_quick_test: ok")


if __name__ == "__main__":
    main()
