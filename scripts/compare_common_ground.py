#!/usr/bin/python3
"""Compare a scenario with Common Ground on and off over several seeds.

Runs `throng run SCENARIO --seed S --common-ground on|off` for each seed, then
`throng metrics --json` on every recording, and prints a Markdown table of the means (and ranges)
over seeds: visits, arrival and exit rates, time to empty the scenario, group cohesion, congestion
at the key points, the coordinations and how groups came apart (wait timeouts) and back together
(reunions). With --plot it draws arrivals per minute and cohesion, on versus off.

This is the comparison in docs/social-model.md:

    scripts/compare_common_ground.py scenarios/mall.json --seeds 1 2 3 --plot docs/img/mall_common_ground.png

Needs a built throng (build/apps/throng/throng, or --throng PATH); the plot needs matplotlib
(Debian: python3-matplotlib). Recordings go to --workdir (default out/compare/).
"""
import argparse
import json
import os
import sqlite3
import subprocess
import sys
import time


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"compare_common_ground: {' '.join(cmd)} failed ({r.returncode}):\n{r.stderr.strip()}")
    return r.stdout


def events(path, kind):
    with sqlite3.connect(f"file:{path}?mode=ro", uri=True) as db:
        return db.execute("SELECT count(*) FROM throng_events WHERE kind = ?", (kind,)).fetchone()[0]


def measure(throng, scenario, seed, mode, workdir, threads):
    out = os.path.join(workdir, f"{os.path.splitext(os.path.basename(scenario))[0]}-{mode}-{seed}.sqlite")
    started = time.monotonic()
    summary = json.loads(run([throng, "run", scenario, "--seed", str(seed), "--common-ground", mode, "--out", out,
                              "--force", "--quiet", "--json", "--threads", str(threads)]))
    wall = time.monotonic() - started
    m = json.loads(run([throng, "metrics", out, "--json"]))
    rest = next((c for c in m["congestion"]["by_category"] if c["category"] == "restroom"), None)
    co = m["coordinations"]
    return {
        "visits": m["arrivals"]["visits"],
        "visits_per_min": m["arrivals"]["visits_per_minute"],
        "exits_per_min": m["arrivals"]["exits_per_minute"],
        "empty_s": summary.get("last_exit_time_s") if summary["agents_active"] == 0 and summary.get("last_exit_time_s") else summary["simulated_time_s"],
        "speedup": summary["simulated_time_s"] / max(1e-9, summary["wall_time_s"]),
        "wall_s": wall,
        "cohesion_m": m["cohesion"]["mean_distance_m"],
        "together": 100.0 * m["cohesion"]["share_together"],
        "restroom_mean": rest["mean"] if rest else 0.0,
        "restroom_p95": rest["p95"] if rest else 0.0,
        "grounded": co["by_outcome"].get("grounded", 0),
        "failed": co["by_outcome"].get("failed", 0),
        "alone": co["by_outcome"].get("alone", 0),
        "wait": co["by_plan"].get("divide_and_wait", 0),
        "proceed": co["by_plan"].get("divide_and_proceed", 0),
        "detour": co["by_plan"].get("detour_together", 0),
        "grounding_s": co.get("grounding_mean_s", 0.0),
        "reunited": co.get("reunited", 0),
        "timeouts": events(out, "group_timeout"),
        "bins": [(b["start"], b["visits"]) for b in m["arrivals"]["bins"]],
    }


ROWS = [
    ("visits", "visits (generated goals reached)", "{:.0f}"),
    ("visits_per_min", "visits per minute", "{:.1f}"),
    ("exits_per_min", "exits per minute", "{:.1f}"),
    ("empty_s", "time until the mall is empty [s]", "{:.0f}"),
    ("cohesion_m", "group cohesion: mean distance to centroid [m]", "{:.2f}"),
    ("together", "group-frames with everyone within 3 m [%]", "{:.1f}"),
    ("timeouts", "groups that gave up waiting for a member (wait timeouts)", "{:.0f}"),
    ("reunited", "reunions after a divide", "{:.0f}"),
    ("restroom_mean", "density within 2 m of restrooms, mean [1/m²]", "{:.3f}"),
    ("restroom_p95", "density within 2 m of restrooms, p95 [1/m²]", "{:.3f}"),
    ("grounded", "coordinations grounded", "{:.0f}"),
    ("failed", "coordinations failed (fallback)", "{:.0f}"),
    ("alone", "lone visits (no group mate, or Common Ground off)", "{:.0f}"),
    ("wait", "plan: divide-and-wait", "{:.0f}"),
    ("proceed", "plan: divide-and-proceed", "{:.0f}"),
    ("detour", "plan: detour-together", "{:.0f}"),
    ("grounding_s", "grounding time t8 − t0, mean [s]", "{:.1f}"),
    ("speedup", "simulated / wall time", "{:.0f}×"),
]


def cell(values, fmt):
    mean = sum(values) / len(values)
    text = fmt.format(mean)
    if len(values) > 1 and min(values) != max(values):
        text += f" ({fmt.format(min(values))}–{fmt.format(max(values))})"
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scenario")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--throng", default="build/apps/throng/throng")
    ap.add_argument("--workdir", default="out/compare")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--plot", help="write a PNG of arrivals per minute and cohesion, on vs off")
    ap.add_argument("--json", action="store_true", help="print the raw measurements as JSON instead of Markdown")
    args = ap.parse_args()
    if not os.access(args.throng, os.X_OK):
        sys.exit(f"compare_common_ground: {args.throng}: not an executable; build first (scripts/demo.sh) or pass --throng")
    os.makedirs(args.workdir, exist_ok=True)
    results = {"on": [], "off": []}
    total = 2 * len(args.seeds)
    done = 0
    for seed in args.seeds:
        for mode in ("on", "off"):
            print(f"[{done + 1}/{total}] seed {seed}, Common Ground {mode} ...", file=sys.stderr, flush=True)
            results[mode].append(measure(args.throng, args.scenario, seed, mode, args.workdir, args.threads))
            done += 1
    if args.json:
        print(json.dumps(results, indent=1))
    else:
        print(f"{os.path.basename(args.scenario)}, seeds {' '.join(map(str, args.seeds))}: mean (min–max) over seeds\n")
        print("| measure | Common Ground on | Common Ground off |")
        print("|---|---|---|")
        for key, label, fmt in ROWS:
            print(f"| {label} | {cell([r[key] for r in results['on']], fmt)} | {cell([r[key] for r in results['off']], fmt)} |")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4))
        for mode, colour in (("on", "tab:blue"), ("off", "tab:orange")):
            n = max(len(r["bins"]) for r in results[mode])
            mean = []
            for i in range(n):
                vals = [r["bins"][i][1] if i < len(r["bins"]) else 0 for r in results[mode]]
                mean.append(sum(vals) / len(vals))
            ax1.step([i for i in range(n)], mean, where="post", color=colour, label=f"Common Ground {mode}")
        ax1.set_xlabel("minute")
        ax1.set_ylabel("visits started per minute (mean over seeds)")
        ax1.set_title("Arrivals at destinations")
        ax1.legend()
        labels = ["cohesion [m]", "together [%/10]", "wait timeouts [/10]"]
        for k, (mode, colour) in enumerate((("on", "tab:blue"), ("off", "tab:orange"))):
            rs = results[mode]
            vals = [sum(r["cohesion_m"] for r in rs) / len(rs), sum(r["together"] for r in rs) / len(rs) / 10,
                    sum(r["timeouts"] for r in rs) / len(rs) / 10]
            ax2.bar([i + 0.38 * k for i in range(3)], vals, width=0.38, color=colour, label=f"Common Ground {mode}")
        ax2.set_xticks([i + 0.19 for i in range(3)])
        ax2.set_xticklabels(labels)
        ax2.set_title("Groups")
        ax2.legend()
        fig.suptitle(f"{os.path.basename(args.scenario)}: Common Ground on vs off, seeds {' '.join(map(str, args.seeds))}")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
        print(f"\nplot: {args.plot}", file=sys.stderr)


if __name__ == "__main__":
    main()
