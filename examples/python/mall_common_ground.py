#!/usr/bin/python3
"""The mall with Common Ground on and off, compared (Park et al.; docs/social-model.md): the same
seed run twice from Python, counting coordinations, visits and how often group members are together,
read back from the recordings with throng.read_recording (docs/python.md).

usage: PYTHONPATH=build/python /usr/bin/python3 examples/python/mall_common_ground.py [--quick] [--keep DIR]
"""
import argparse
import json
import os
import tempfile

import throng

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run(common_ground, seconds, out):
    doc = json.load(open(os.path.join(ROOT, "scenarios", "mall.json")))
    doc["social"]["commonGround"] = common_ground
    scenario = throng.Scenario.from_dict(doc, os.path.join(ROOT, "scenarios", "mall.json"))
    with throng.Simulation(scenario, threads=2, duration=seconds, record=out, force=True) as sim:
        sim.run()
    rec = throng.read_recording(out)
    kinds = rec.events["kind"].value_counts()
    return {"coordinations": int(kinds.get("coordination_start", 0)), "visits": int(kinds.get("visit_start", 0)),
            "reunited": int(kinds.get("reunited", 0)), "goals generated": int(kinds.get("goal_generated", 0)),
            "agents": int(rec.trajectory["id"].nunique())}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="60 s of mall time instead of 600 (the test suite's run)")
    parser.add_argument("--keep", help="directory for the two recordings (default: a temporary one)")
    args = parser.parse_args()
    seconds = 60.0 if args.quick else 600.0
    with tempfile.TemporaryDirectory() as tmp:
        where = args.keep or tmp
        on = run(True, seconds, os.path.join(where, "mall-cg-on.sqlite"))
        off = run(False, seconds, os.path.join(where, "mall-cg-off.sqlite"))
    print(f"{'':18s} {'on':>8s} {'off':>8s}")
    for key in on:
        print(f"{key:18s} {on[key]:8d} {off[key]:8d}")
    if on["goals generated"] == 0:
        raise SystemExit("unexpected: no goals were generated")
    if off["reunited"] != 0:
        raise SystemExit("unexpected: groups reunited with Common Ground off")


if __name__ == "__main__":
    main()
