"""The Jülich corridor scenarios' inflow, replayed from the measured trajectories.

Each participant becomes a one-person population that enters at the time and place of its first
recorded position (PeTrack starts tracking at the top of the camera's view, y ≈ 7.7-8 m, upstream
of the corridor), walking to the exit at N(1.34, 0.26) m/s like every validation scenario. The
experiment's own gaps and bursts in the inflow reach the measurement area, as they did in the
experiment; an even inflow (the scenarios until session 41) smoothed them out, and with them the
corridor's sparse and dense frames (docs/validation.md, "Inflow").

    /usr/bin/python3 scripts/validation/inflow.py uo-145-180-180   # rewrites scenarios/validation/uo-145-180-180.json

The geometry and the exit are kept from the scenario file; only its populations are replaced. The
file is written whole or not at all (a temporary file, then renamed).
"""
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SPEED = {"mean": 1.34, "sd": 0.26}  # Weidmann 1993, as scripts/validation/scenarios.py
ENTRY_X = (-0.8, 2.6)  # the entry area inside the walkable [-1, 2.8] with a body to spare [m]
ENTRY_Y = (4.3, 7.8)   # below the walkable's top edge (y = 8) [m]
FPS, SCALE = 16.0, 0.01  # the Jülich files: frames at 16 fps, centimetres (GEOMETRY.md)


def first_appearances(path):
    """(time [s], x [m], y [m], id) of each person's first recorded frame, by time then id."""
    d = np.loadtxt(path)
    out = []
    for pid in np.unique(d[:, 0]):
        rows = d[d[:, 0] == pid]
        k = int(np.argmin(rows[:, 1]))
        out.append((rows[k, 1] / FPS, rows[k, 2] * SCALE, rows[k, 3] * SCALE, int(pid)))
    return sorted(out)


def replay(scenario, appearances):
    """A copy of `scenario` whose populations are one person per appearance."""
    s = dict(scenario)
    s["name"] = s["name"].split("; measured inflow")[0].split("; each participant")[0] + "; each participant enters at their recorded time and place)"
    pops = []
    for t, x, y, pid in appearances:
        pos = [round(min(max(x, ENTRY_X[0]), ENTRY_X[1]), 3), round(min(max(y, ENTRY_Y[0]), ENTRY_Y[1]), 3)]
        pops.append({"id": f"p{pid:03d}", "groups": 1, "size": 1, "start": round(t, 4), "spawn": {"position": pos},
                     "goals": ["exit"], "speed": dict(SPEED)})
    s["populations"] = pops
    return s


def main(argv):
    if len(argv) != 1 or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv and argv[0] in ("-h", "--help") else 2
    name = argv[0]
    data = os.path.join(ROOT, "..", "shared", "validation-data", "juelich", f"{name}.txt")
    target = os.path.join(ROOT, "scenarios", "validation", f"{name}.json")
    if not os.path.isfile(data) or not os.path.isfile(target):
        print(f"inflow.py: {name}: expected {data} and {target}", file=sys.stderr)
        return 1
    with open(target) as f:
        scenario = json.load(f)
    out = replay(scenario, first_appearances(data))
    tmp = target + ".tmp"
    head = {k: v for k, v in out.items() if k != "populations"}
    text = json.dumps(head)[:-1] + ', "populations": [\n'
    text += ",\n".join("  " + json.dumps(p) for p in out["populations"]) + "\n]}\n"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, target)
    print(f"inflow.py: {target}: {len(out['populations'])} persons")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
