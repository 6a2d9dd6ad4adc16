#!/usr/bin/python3
"""A parameter study from Python: 60 people through a 1.1 m long bottleneck of widths 0.8 ... 1.4 m,
three seeds each; the flow at the bottleneck's exit line (crossings per second between the first
and the last passing) against the width, plotted with matplotlib (docs/python.md).

usage: PYTHONPATH=build/python /usr/bin/python3 examples/python/bottleneck_study.py [--quick] [--out FILE.png]
"""
import argparse

import numpy as np

import throng
from throng import analysis


def bottleneck(width, seed, people):
    """A 6 m wide waiting area, a 1.1 m long bottleneck `width` wide at x = 8, an exit beyond it."""
    y0, y1 = 3.0 - width / 2, 3.0 + width / 2
    return (throng.ScenarioBuilder(f"bottleneck {width:.2f} m", seed=seed, duration=120)
            .walkable([(0, 0), (8, 0), (8, y0), (9.1, y0), (9.1, 0), (14, 0), (14, 6), (9.1, 6), (9.1, y1),
                       (8, y1), (8, 6), (0, 6)])
            .exit("exit", polygon=[(13, 0), (14, 0), (14, 6), (13, 6)])
            .population("people", goals=["exit"], spawn=[(0.5, 0.5), (6, 0.5), (6, 5.5), (0.5, 5.5)],
                        groups=people, speed={"mean": 1.34, "sd": 0.26}, radius=0.2))


def flow_through(width, seed, people):
    """Persons per second through the bottleneck's exit line, from the agents' positions every 0.1 s."""
    sim = throng.Simulation(throng.scenario(bottleneck(width, seed, people)), threads=1)
    rows = []
    while not sim.finished and sim.time < 120:
        sim.step(2)
        a = sim.agents()
        rows.append(np.column_stack([np.full(len(a), sim.tick // 2), a.id, a.x, a.y]))
    import pandas as pd
    traj = pd.DataFrame(np.concatenate(rows), columns=["frame", "id", "x", "y"]).astype({"frame": int, "id": int})
    c = analysis.crossings(traj, ((9.1, 0.0), (9.1, 6.0)))
    t = np.sort(c["frame"].to_numpy()) / 10.0
    return (len(t) - 1) / (t[-1] - t[0]) if len(t) > 1 else 0.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="two widths, one seed, 20 people (the test suite's run)")
    parser.add_argument("--out", default="bottleneck_study.png", help="the plot (PNG)")
    args = parser.parse_args()
    widths = [0.8, 1.2] if args.quick else [0.8, 0.9, 1.0, 1.1, 1.2, 1.4]
    seeds = [1] if args.quick else [1, 2, 3]
    people = 20 if args.quick else 60
    flows = {w: [flow_through(w, s, people) for s in seeds] for w in widths}
    for w, f in flows.items():
        print(f"width {w:.2f} m: flow {np.mean(f):.2f} 1/s (seeds {', '.join(f'{x:.2f}' for x in f)})")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.errorbar(widths, [np.mean(flows[w]) for w in widths], yerr=[np.std(flows[w]) for w in widths], fmt="o-",
                label="throng")
    ax.plot(widths, [1.9 * w for w in widths], "k--", label="1.9 /(m·s) · w (Seyfried et al. 2009 trend)")
    ax.set_xlabel("bottleneck width [m]")
    ax.set_ylabel("flow [1/s]")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    print(f"plot: {args.out}")
    mean = [np.mean(flows[w]) for w in widths]
    if not all(b > a for a, b in zip(mean, mean[1:])):
        raise SystemExit("unexpected: the flow does not grow with the width")


if __name__ == "__main__":
    main()
