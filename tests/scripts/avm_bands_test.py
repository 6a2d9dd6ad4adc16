#!/usr/bin/python3
"""The calibrated pedestrian model inside the experiments' bands (ctest: validate_avm_bands).

Runs scripts/validate.py --quick --model avm (one seed; deterministic) on the experiments that need
no external data and asserts the bands of issue 17 that avm meets (docs/validation.md, "Results:
the pedestrian model avm"): the ring's fundamental diagram from 0.5 to 5 /m² against Weidmann,
every bottleneck width 0.5-1.2 m accepted by `throng check` for the default body, its flow within
±25 % of the trend and no gap between passings over 5 s in this seed, the 1 m door's flow, and
lanes in counter-flow without deadlock, no more than 2 % of the ring's speed samples backward up to
3 /m² and of the single file's at every density, and nobody in the dense room's queue more than
0.5 m back from the door. Not asserted, because avm does not meet them yet or only on average (the
same page says why): the ring's backward samples at 4-5 /m² (five seeds: 1.8-2.1 %,
this one-seed short run: 2.0-2.3 %), the single file's speed at 1 /m, the dense room's overlaps; and
the 0.6 m flow, which this one-seed run may put just above its band (five seeds: 1.41 /s, band
0.86-1.42).
With `--model orca` this test fails (the 0.5 m door is refused; speed does not fall with density).

usage: avm_bands_test.py THRONG_BINARY [MODEL]"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "scripts", "validate.py")
ASSERTED = (
    [f"speed at {d} /m²" for d in ("0.5", "1", "1.5", "2", "3", "4", "5")]
    + [f"{w} m accepted by throng check" for w in ("0.5", "0.6", "0.7", "0.8", "1.0", "1.2")]
    + [f"{w} m flow" for w in ("0.5", "0.7", "0.8", "1.0", "1.2")]
    + [f"{w} m longest gap" for w in ("0.5", "0.6", "0.7", "0.8", "1.0", "1.2")]
    + ["1 m door flow", "lane order", "no deadlock"]
    + [f"backward samples at {d} /m²" for d in ("0.5", "1", "1.5", "2", "3")]
    + [f"backward samples at {d} /m" for d in ("1", "1.5", "2")]
    + ["max walk-back from the door"]
)


def main():
    binary = sys.argv[1]
    model = sys.argv[2] if len(sys.argv) > 2 else "avm"
    with tempfile.TemporaryDirectory(prefix="throng-avm-bands-") as tmp:
        out = os.path.join(tmp, "v.json")
        res = subprocess.run([sys.executable, SCRIPT, "--throng", binary, "--quick", "--model", model, "--only",
                              "ring,single-file,room,bottleneck,door,counterflow", "--no-plots", "--json", out],
                             capture_output=True, text=True, timeout=600)
        if res.returncode != 0:
            print(res.stdout + res.stderr)
            sys.exit(f"avm_bands_test: validate.py exited {res.returncode}")
        targets = json.load(open(out))["targets"]
    failed = []
    for prefix in ASSERTED:
        rows = [t for t in targets if t["target"] == prefix or t["target"].startswith(prefix + " ")]
        if len(rows) != 1:
            failed.append(f"{prefix}: {len(rows)} rows (expected 1)")
        elif rows[0]["status"] != "PASS":
            t = rows[0]
            failed.append(f"{t['experiment']} {t['target']}: {t['measured']} outside {t['band']} {t['unit']}")
    for f in failed:
        print("avm_bands_test: FAIL:", f)
    if failed:
        sys.exit(1)
    print(f"avm_bands_test: {len(ASSERTED)} targets inside their bands with --model {model}")


if __name__ == "__main__":
    main()
