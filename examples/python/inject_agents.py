#!/usr/bin/python3
"""Agents injected while stepping: a hall where a new group of visitors enters through the west door
every 5 s (a throng-crowd/1 document per wave, insert_crowd), at 12 s everyone within 3 m of the
pillar's centre is taken out by id (remove_agents, found in the live columns: sim.view()), and the
first wave is removed after 20 s (remove_crowd). Prints the head count as it goes (docs/python.md).

usage: PYTHONPATH=build/python /usr/bin/python3 examples/python/inject_agents.py [--quick]
"""
import argparse
import json

import numpy as np

import throng

HALL = (throng.ScenarioBuilder("hall", seed=4, duration=60)
        .walkable([(0, 0), (30, 0), (30, 12), (0, 12)])
        .obstacle([(14, 4), (16, 4), (16, 8), (14, 8)])
        .exit("east-door", polygon=[(29, 4), (30, 4), (30, 8), (29, 8)])
        .interest("west-door", polygon=[(0, 4), (1, 4), (1, 8), (0, 8)])
        # People already in the hall (the body size they set is what the navmesh makes room for).
        .population("early", goals=["east-door"], spawn=[(2, 1), (8, 1), (8, 11), (2, 11)], groups=6, radius=0.2))


def wave(k, groups):
    return json.dumps({"format": "throng-crowd/1", "id": f"wave-{k}",
                       "populations": [{"id": f"visitors-{k}", "groups": groups, "size": [1, 3],
                                        "spawn": {"point": "west-door"}, "goals": ["east-door"],
                                        "speed": {"mean": 1.2, "sd": 0.2}, "radius": 0.2}]})


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="30 s instead of 60 (the test suite's run)")
    args = parser.parse_args()
    end = 30.0 if args.quick else 60.0
    sim = throng.Simulation(throng.scenario(HALL), threads=2, duration=end)
    k = 0
    removed = False
    peak = 0
    taken_out = []
    while sim.time < end - 1e-6:
        if sim.tick % 100 == 0:  # every 5 s
            sim.insert_crowd(wave(k, groups=4), f"wave-{k}")
            k += 1
        if not taken_out and sim.time >= 12.0:
            v = sim.view()  # the live columns, no copy; valid until the next step
            taken_out = [int(i) for i in v.id[np.hypot(v.x - 15.0, v.y - 6.0) < 3.0]]
            sim.remove_agents(taken_out)
            print(f"t = {sim.time:5.1f} s: {len(taken_out)} agents near the pillar taken out: {taken_out}")
            taken_out = taken_out or [None]
        if not removed and sim.time >= 20.0:
            sim.remove_crowd("wave-0")
            removed = True
        sim.step(1)
        if sim.tick % 100 == 0:
            n = len(sim.view())
            peak = max(peak, n)
            print(f"t = {sim.time:5.1f} s: {n:3d} agents, {sim.stats['exited']:3d} left by the east door")
    kinds = [e["kind"] for e in sim.events()]
    print(f"{k} waves inserted, {kinds.count('spawn')} agents spawned, {kinds.count('exit')} exits")
    if peak == 0 or kinds.count("spawn") < 6 + 4 * k:
        raise SystemExit("unexpected: the waves did not spawn")
    if taken_out == [None] or sim.stats["removed"] < len(taken_out):
        raise SystemExit("unexpected: nobody near the pillar was taken out")


if __name__ == "__main__":
    main()
