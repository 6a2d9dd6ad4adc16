#!/usr/bin/python3
"""What driving the engine from Python costs (issue 19's speed target): the same world stepped
(a) in one call, sim.step(N), which loops in C++ with the GIL released;
(b) from a Python loop, sim.step(1) N times;
(c) from a Python loop that also reads every agent's position each tick from a snapshot
    (sim.agents().x, .y: the engine copies its columns into a frame);
(d) the same reading the live columns in place (sim.view().x, .y: nothing copied).
The ways take turns on one world, a few ticks each, round after round (a, b, c, d, a, b, ...), so
that they step the same agents and a busy machine slows them alike; each round compares a way with
that round's (a), and the median over rounds counts. Prints agent-steps/s for each and the overhead
of (b), (c) and (d) over (a). Also checks that reading the state allocates no Python memory that grows with
the agents (tracemalloc over the loop).

usage: PYTHONPATH=build/python /usr/bin/python3 benches/python/step_overhead.py [--agents N] [--ticks T] [--threads K]
       [--rounds R] [--clock wall|cpu]
"""
import argparse
import statistics
import time
import tracemalloc

import throng


def world(agents, threads, seed=1):
    side = max(20.0, (agents * 4.0) ** 0.5)  # about 0.25 agents per m²: free walking, little avoidance
    b = (throng.ScenarioBuilder("python bench", seed=seed, duration=3600)
         .walkable([(0, 0), (side, 0), (side, side), (0, side)])
         .interest("a", polygon=[(0, 0), (side * 0.1, 0), (side * 0.1, side), (0, side)])
         .interest("b", polygon=[(side * 0.9, 0), (side, 0), (side, side), (side * 0.9, side)])
         .population("walkers", goals=["b", "a"] * 50, spawn=[(1, 1), (side - 1, 1), (side - 1, side - 1), (1, side - 1)],
                     groups=agents, speed=1.3, radius=0.2))
    return throng.Simulation(throng.scenario(b), threads=threads)


CLOCK = time.perf_counter


def rate(fn, sim, ticks):
    n = len(sim.agents())
    start = CLOCK()
    fn(sim, ticks)
    return n * ticks / (CLOCK() - start)


def one_call(sim, ticks):
    sim.step(ticks)


def python_loop(sim, ticks):
    for _ in range(ticks):
        sim.step(1)


def python_loop_reading(sim, ticks):
    total = 0.0
    for _ in range(ticks):
        sim.step(1)
        a = sim.agents()
        total += float(a.x[0]) + float(a.y[0])
    return total


def python_loop_viewing(sim, ticks):
    total = 0.0
    for _ in range(ticks):
        sim.step(1)
        v = sim.view()
        total += float(v.x[0]) + float(v.y[0])
    return total


WAYS = (("one call", one_call), ("python loop", python_loop), ("loop + agents()", python_loop_reading),
        ("loop + view()", python_loop_viewing))


def grown_bytes(args, fn):
    """Python memory grown over 20 ticks of fn after 5 (tracemalloc)."""
    sim = world(args.agents, args.threads)
    sim.step(5)
    tracemalloc.start()
    fn(sim, 5)
    before = tracemalloc.take_snapshot()
    fn(sim, 20)
    grown = sum(s.size_diff for s in tracemalloc.take_snapshot().compare_to(before, "filename"))
    tracemalloc.stop()
    return grown


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--agents", type=int, default=100_000)
    parser.add_argument("--ticks", type=int, default=5, help="ticks per way and round")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--rounds", type=int, default=20)
    parser.add_argument("--clock", choices=("wall", "cpu"), default="wall",
                        help="cpu: the process's CPU time (less disturbed by other work on a busy machine; 1 thread)")
    args = parser.parse_args()
    global CLOCK
    CLOCK = time.process_time if args.clock == "cpu" else time.perf_counter
    sim = world(args.agents, args.threads)
    sim.step(20)  # warm: paths planned, caches filled
    rates = {name: [] for name, _ in WAYS}
    for _ in range(args.rounds):
        for name, fn in WAYS:
            rates[name].append(rate(fn, sim, args.ticks))
    base = rates["one call"]
    print(f"{args.agents} agents, {args.rounds} rounds of {args.ticks} ticks per way, {args.threads} thread(s),"
          f" {args.clock} clock:")
    for name, r in rates.items():
        over = sorted(100.0 * (b / x - 1.0) for b, x in zip(base, r))
        q = len(over) // 4
        print(f"  {name:18s} {statistics.median(r) / 1e6:6.3f} M agent-steps/s   {statistics.median(over):+6.1f} % time vs one call"
              f"   (middle half of rounds {over[q]:+.1f} .. {over[-1 - q]:+.1f} %)")
    del sim
    for name, fn in WAYS[2:]:
        print(f"  Python memory grown over 20 more ticks of {name}: {grown_bytes(args, fn)} bytes")


if __name__ == "__main__":
    main()
