#!/usr/bin/python3
"""What driving the engine from Python costs (issue 19's speed target): the same world stepped
(a) in one call, sim.step(N), which loops in C++ with the GIL released;
(b) from a Python loop, sim.step(1) N times;
(c) from a Python loop that also reads every agent's position each tick (sim.agents().x, .y).
Prints agent-steps/s for each and the overhead of (b) and (c) over (a). Also checks that reading the
state allocates no Python memory that grows with the agents (tracemalloc over the loop).

usage: PYTHONPATH=build/python /usr/bin/python3 benches/python/step_overhead.py [--agents N] [--ticks T] [--threads K]
"""
import argparse
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


def rate(fn, sim, ticks):
    n = len(sim.agents())
    start = time.perf_counter()
    fn(sim, ticks)
    return n * ticks / (time.perf_counter() - start)


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


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--agents", type=int, default=100_000)
    parser.add_argument("--ticks", type=int, default=40)
    parser.add_argument("--threads", type=int, default=1)
    args = parser.parse_args()
    results = {}
    for name, fn in (("one call", one_call), ("python loop", python_loop), ("loop + positions", python_loop_reading)):
        sim = world(args.agents, args.threads)
        sim.step(20)  # warm: paths planned, caches filled
        results[name] = rate(fn, sim, args.ticks)
    base = results["one call"]
    print(f"{args.agents} agents, {args.ticks} ticks, {args.threads} thread(s):")
    for name, r in results.items():
        print(f"  {name:18s} {r / 1e6:6.3f} M agent-steps/s   {100.0 * (base / r - 1.0):+6.1f} % time vs one call")
    sim = world(args.agents, args.threads)
    sim.step(5)
    tracemalloc.start()
    python_loop_reading(sim, 5)
    before = tracemalloc.take_snapshot()
    python_loop_reading(sim, 20)
    grown = sum(s.size_diff for s in tracemalloc.take_snapshot().compare_to(before, "filename"))
    print(f"  Python memory grown over 20 more ticks of reading: {grown} bytes")


if __name__ == "__main__":
    main()
