#!/usr/bin/python3
"""Writes the verification scenarios (verification/rimea/*.json, verification/nist/*.json,
verification/iso/*.json) from scripts/verification/geometry.py. The files are committed; run this
after changing a builder and commit what changes (scripts/verify.py reads the files, not the
builders).

usage: /usr/bin/python3 scripts/verification/make_scenarios.py [--check]
  --check  write nothing; exit 1 if a committed file differs from what the builders give
"""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from verification import geometry as G  # noqa: E402
from validation import scenarios as VS  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(HERE))
OUT = os.path.join(ROOT, "verification")

# RiMEA 4: the fundamental diagram in a 2 m wide ring (r 3..5 m), the set-up of scripts/validate.py.
RING = {"r_in": 3.0, "r_out": 5.0, "slabs": 12, "densities": [0.5, 1.0, 2.0, 3.0, 4.0, 5.0], "warm": 10.0,
        "span": 10.0, "pad": 1.25 * 0.2 - 0.03}


def ring(rho):
    area = VS.ring_area(RING["r_in"], RING["r_out"])
    n = int(round(rho * area))
    s = VS.ring(RING["r_in"], RING["r_out"], n, RING["warm"] + RING["span"], slabs=RING["slabs"],
                name=f"RiMEA 4: fundamental diagram, ring, {rho:g} /m^2", pad=RING["pad"])
    per_wave = 0.5 * area / (math.pi * 0.2 * 0.2)
    return VS.in_waves(s, max(1, math.ceil(n / (0.97 * per_wave))), 1.0)


def impaired(name):
    """NIST 2.10: 10 persons with a movement impairment (0.6 m/s, 0.25 m body) among 40 others."""
    s = G.demographics(name)
    d = G.DEMOGRAPHICS
    spawn = {"polygon": G.rect(0.3, 0.3, d["spawn_to"], d["width"] - 0.3)}
    s["populations"] = [G.population("impaired", 10, spawn, ["end"], 0.6, radius=0.25),
                        G.population("others", 40, spawn, ["end"], G.SPEED)]
    return s


def scenarios():
    r = {
        "rimea/01-corridor": G.corridor("RiMEA 1: one person, 40 m corridor, 1.33 m/s", G.FLAT_SPEED),
        "rimea/02-stairs-up": G.stairs("RiMEA 2: one person up a 10 m flight", True),
        "rimea/03-stairs-down": G.stairs("RiMEA 3: one person down a 10 m flight", False),
        "rimea/05-premovement": G.premovement("RiMEA 5: ten persons, pre-movement 10 ... 100 s"),
        "rimea/06-corner": G.corner("RiMEA 6: 20 persons round a left corner", G.CORNER_SMALL, 6.0),
        "rimea/07-demographics": G.demographics("RiMEA 7: 50 persons in four speed groups"),
        "rimea/07-demographics-wide": G.demographics("RiMEA 7: the 50 at one end of a 200 m wide exit",
                                                     G.DEMOGRAPHICS["wide"]),
        "rimea/08-office": G.office_floor("RiMEA 8: office floor, parameter analysis"),
        "rimea/09-hall-open": G.hall("RiMEA 9: 1000 persons, four doors open", ()),
        "rimea/09-hall-closed": G.hall("RiMEA 9: 1000 persons, two doors closed", ("west-south", "west-north")),
        "rimea/10-assigned-exits": G.assigned_exits("RiMEA 10: twelve rooms, assigned exits"),
        "rimea/11-exit-choice": G.exit_choice("RiMEA 11: two exits, which one is used"),
        "rimea/12-bottlenecks": G.bottlenecks("RiMEA 12: 150 persons, two bottlenecks in a row"),
        "rimea/13-stair-jam": G.stair_jam("RiMEA 13: 250 persons through a 2 m corridor up a 2 m wide flight"),
        "rimea/14-route-choice": G.route_choice("RiMEA 14: a short route over stairs or a longer flat one"),
        "rimea/15-large-corner": G.corner("RiMEA 15: 500 persons round a left corner", G.CORNER_LARGE, 34.0),
        "nist/2.4-ramp-gentle-up": G.ramp("NIST 2.4: one person up a 1:12 ramp at 1 m/s", True, G.RAMP["gentle"]),
        "nist/2.4-ramp-gentle-down": G.ramp("NIST 2.4: one person down a 1:12 ramp at 1 m/s", False, G.RAMP["gentle"]),
        "nist/2.4-ramp-steep-up": G.ramp("NIST 2.4: one person up a 20° ramp, factor 0.8", True, G.RAMP["steep"],
                                         G.RAMP["steep_factors"]),
        "nist/2.4-ramp-steep-down": G.ramp("NIST 2.4: one person down a 20° ramp, factor 0.9", False, G.RAMP["steep"],
                                           G.RAMP["steep_factors"]),
        "nist/2.6-incapacitation": G.incapacitation("NIST 2.6: persons in carbon monoxide, 35000 ppm, incapacitated at "
                                                    "a dose of 1 (0.3 for the susceptible)"),
        "nist/2.9-groups": G.groups("NIST 2.9: groups of 2 to 4 walking together"),
        "nist/2.10-impaired": impaired("NIST 2.10: persons with reduced mobility among others"),
        "nist/3.2-social-influence": G.social_influence("NIST 3.2: 30 choosers among 15 walking to the far exit", True),
        "nist/3.2-social-influence-control": G.social_influence("NIST 3.2 control: the same without herding", False),
        "nist/3.3-affiliation": G.affiliation("NIST 3.3: 40 persons who know only the far exit", True),
        "nist/3.3-affiliation-control": G.affiliation("NIST 3.3 control: 40 persons who know both exits", False),
        "nist/4.1-dynamic-exits": G.dynamic_exits("NIST 4.1: the far exit closes at 15 s"),
        "nist/5.2-door-flow": G.door_room("NIST 5.2: 200 persons through a 1 m door"),
        "nist/2.7-elevators": G.lift(f"NIST 2.7: {G.LIFT['agents']} persons down by a lift for {G.LIFT['capacity']}"),
    }
    for rho in RING["densities"]:
        r[f"rimea/04-ring-{rho:g}"] = ring(rho)
    for k in G.COUNTER["against"]:
        r[f"rimea/16-counterflow-{k}"] = G.counter_flow(f"RiMEA 16: 50 persons east, {k} west", k)
    r.update(iso_scenarios())
    return r


def iso_scenarios():
    """ISO 20414 tests that differ from RiMEA's and NIST's (verification/iso/README.md)."""
    r = {"iso/07-overtaking": G.overtaking("ISO 20414 test 7: ten persons overtake one with reduced mobility"),
         "iso/12-stair-flow": G.stair_flow(f"ISO 20414 test 12: {G.STAIR_FLOW['agents']} persons down a 2 m wide "
                                           "flight"),
         "iso/17-route-layout": G.route_layout("ISO 20414 test 17: the exit nearer by walking, not as the crow flies"),
         "iso/21-escalators": G.escalator(f"ISO 20414 test 21: {G.ESCALATOR['agents']} persons up an escalator")}
    for rho in G.CORRIDOR_FD["densities"]:
        r[f"iso/13-corridor-{rho:g}"] = G.corridor_fd(f"ISO 20414 test 13: a 2 m corridor, crowd at {rho:g} /m^2", rho)
    return r


def text(s):
    return json.dumps(s, indent=1) + "\n"


def main(argv):
    check = "--check" in argv
    stale = []
    for rel, s in scenarios().items():
        path = os.path.join(OUT, rel + ".json")
        want = text(s)
        have = open(path).read() if os.path.exists(path) else None
        if have != want:
            stale.append(rel)
            if not check:
                os.makedirs(os.path.dirname(path), exist_ok=True)
                with open(path, "w") as f:
                    f.write(want)
    if check and stale:
        print("make_scenarios: out of date: " + ", ".join(stale))
        return 1
    print(f"make_scenarios: {'checked' if check else 'wrote'} {len(scenarios())} scenarios"
          + (f" ({len(stale)} changed)" if stale and not check else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
