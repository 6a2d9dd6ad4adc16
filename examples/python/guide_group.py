#!/usr/bin/python3
"""A group guided from Python: the museum's first visitor group follows a guide (say an avatar a
user moves) along a loop of waypoints, then is released and resumes its own visit
(Musse et al. §3.2.6 guided crowds; docs/python.md).

usage: PYTHONPATH=build/python /usr/bin/python3 examples/python/guide_group.py [--quick]
"""
import argparse
import math
import os

import throng

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="a shorter walk (the test suite's run)")
    args = parser.parse_args()
    museum = throng.Scenario.load(os.path.join(ROOT, "scenarios", "museum.json"))
    sim = throng.Simulation(museum, threads=2)
    population = museum.populations[0]
    while True:  # wait until the first group and its members are in the world
        try:
            group = sim.group(population, 0)
            members = sim.group_info(group)["members"]
            start = sim.agent(members[0])["position"]
            break
        except (KeyError, IndexError):
            sim.step(1)
    print(f"group {group} of '{population}': members {members}, at ({start[0]:.1f}, {start[1]:.1f})")
    # The guide walks a 3 m circle round the group's start at 0.8 m/s; the group follows.
    seconds = 10 if args.quick else 30
    worst = 0.0
    for k in range(int(seconds / sim.dt)):
        angle = 0.8 * k * sim.dt / 3.0
        gx, gy = start[0] + 3.0 * math.cos(angle) - 3.0, start[1] + 3.0 * math.sin(angle)
        sim.guide(group, gx, gy)
        sim.step(1)
        if k * sim.dt > 5.0:  # after catching up: how far the members are from the guide
            for m in members:
                x, y = sim.agent(m)["position"]
                worst = max(worst, math.hypot(x - gx, y - gy))
    print(f"guided for {seconds} s: members stayed within {worst:.2f} m of the guide")
    sim.release(group)
    sim.step(20)
    print(f"released: '{sim.agent(members[0])['state']}'")
    if worst > 4.0:
        raise SystemExit("unexpected: the group did not follow its guide")


if __name__ == "__main__":
    main()
