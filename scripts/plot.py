#!/usr/bin/python3
"""Plots of a throng recording for reports (docs/plot.md): PNG figures of the trajectories, a density
and a speed heatmap, the passings and flow at measurement lines and a fundamental diagram.

usage: /usr/bin/python3 scripts/plot.py RECORDING.sqlite [--out DIR] [--what LIST] [--line X0,Y0,X1,Y1]
           [--area X0,Y0,X1,Y1] [--cell METRES] [--density DEF] [--speed DEF] [--json]

Figures (--what, a comma list; default all):
  trajectories  every agent's path over the walkable area, the exits, the line(s) and the area
  density       classic density per grid cell, averaged over every recorded frame [1/m²]; with
                --density voronoi PedPy's Voronoi density per cell (plotting/voronoi.py)
  speed         mean individual speed of the agents seen in each grid cell [m/s]; with --speed
                voronoi Steffen and Seyfried's Voronoi speed per cell (plotting/voronoi.py)
  flow          cumulative passings N(t) at each measurement line and the flow in 5 s windows
  fd            fundamental diagram: classic density and mean speed in the measurement area per
                frame, with Weidmann's (1993) curve
Without --line, the lines are the scenario's "measurements" lines (passings counted both ways), or
when it has none, one line 1 m in front of each exit, across the walkable area there (passings
counted toward the exit); without --area, the area is the scenario's first measurement area, or when
it has none, 2 m deep behind the first exit's line.
Exit status: 0 when the figures are written; 1 for a recording that cannot be read or a line or area
that cannot measure anything; 2 for bad flags. `throng plot ...` runs this script with the same
flags. Needs numpy, pandas and matplotlib from Debian (python3-numpy, python3-pandas,
python3-matplotlib), hence /usr/bin/python3. The measurements are python/throng/analysis.py's
(PedPy's definitions) and scripts/validation/measures.py's.
"""
import argparse
import importlib.util
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
FIGURES = ("trajectories", "density", "speed", "flow", "fd")
FLOW_WINDOW_S = 5.0
SPEED_HALF_WINDOW_S = 0.5  # individual speed: central difference over +- this time [s]


def _load(name, filename):
    """python/throng/<filename> (the source tree's, or the installed copy at the same place relative to
    this script) as module `name`, without the package's __init__ (which needs the native module)."""
    path = os.path.join(os.path.dirname(HERE), "python", "throng", filename)
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or not os.path.isfile(path):
        raise ImportError(f"{path} is missing; expected python/throng/{filename} beside scripts/")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


class UsageError(Exception):
    pass


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message)


def _numbers(flag, text, count):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) != count or not all(abs(v) < float("inf") for v in values):
        raise UsageError(f"{flag} {text}: expected {count} numbers separated by commas (x0,y0,x1,y1 in metres)")
    return values


def parse_args(argv):
    ap = Parser(prog="plot.py", description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter,
                epilog="\n\n".join(p for p in __doc__.split("\n\n")[1:] if not p.startswith("usage")))
    ap.add_argument("recording", help="a recording written by throng run (SQLite)")
    ap.add_argument("--out", metavar="DIR", help="directory for the PNGs (default: RECORDING without .sqlite, plus -plots)")
    ap.add_argument("--what", default=",".join(FIGURES), metavar="LIST", help=f"figures to draw: {', '.join(FIGURES)}")
    ap.add_argument("--line", metavar="X0,Y0,X1,Y1", help="the measurement line [m] (default: the scenario's measurement lines, "
                                                          "else one in front of each exit)")
    ap.add_argument("--area", metavar="X0,Y0,X1,Y1", help="the measurement area, two opposite corners [m] "
                                                          "(default: the scenario's first measurement area, else 2 m deep "
                                                          "behind the first exit's line)")
    ap.add_argument("--cell", type=float, default=0.5, metavar="METRES", help="heatmap cell size [m] (default 0.5)")
    ap.add_argument("--density", default="classic", metavar="DEF",
                    help="the density heatmap's definition: classic (default) or voronoi (cells cut to 2 m)")
    ap.add_argument("--speed", default="classic", metavar="DEF",
                    help="the speed heatmap's definition: classic (default: the mean speed of those in the cell) or "
                         "voronoi (each one's speed over their Voronoi cell, cut to 2 m, averaged by area)")
    ap.add_argument("--json", action="store_true", help="print the written files and the numbers as one JSON object")
    ap.add_argument("--prog", default="plot.py", help=argparse.SUPPRESS)  # the name errors start with (throng plot)
    args = ap.parse_args(argv)
    args.what = [w.strip() for w in args.what.split(",") if w.strip()]
    bad = [w for w in args.what if w not in FIGURES]
    if bad or not args.what:
        raise UsageError(f"--what: unknown figure {', '.join(bad) or '(none)'}; expected some of {', '.join(FIGURES)}")
    for flag, value in (("--density", args.density), ("--speed", args.speed)):
        if value not in ("classic", "voronoi"):
            raise UsageError(f"{flag} {value}: expected classic or voronoi")
    if not 0.05 <= args.cell <= 100:
        raise UsageError(f"--cell {args.cell:g}: expected a cell size from 0.05 to 100 m")
    args.line = _numbers("--line", args.line, 4) if args.line else None
    args.area = _numbers("--area", args.area, 4) if args.area else None
    return args


PROG = ["plot.py"]  # "throng plot" when run by it (--prog)
LARGE_RECORDING_BYTES = 20 << 20  # "reading" is worth a line from this size on


def error(text):
    print(f"{PROG[0]}: error: {text}", file=sys.stderr)


def progress(text):
    print(f"plot: {text}", file=sys.stderr, flush=True)


class Input:
    """The recording and what is measured on it: world bounds, rings, measurement lines and area."""

    def __init__(self, args, R, G):
        if os.path.getsize(args.recording) >= LARGE_RECORDING_BYTES:
            progress(f"reading {args.recording}")
        self.rec = R.read_recording(args.recording)
        self.traj = self.rec.trajectory
        self.fps = self.rec.fps
        self.rings = G.walkable_rings(self.rec.walkable_area)
        self.world = G.bounds(self.rings, self.traj)
        self.frames = len(self.rec.frame_time) or int(self.traj["frame"].nunique())
        self.agents = int(self.traj["id"].nunique())
        pts = self.rec.points
        self.exits = pts[pts["kind"] == "exit"].to_dict("records") if len(pts) else []
        self.population_of = (dict(zip(self.rec.agents["id"].astype(int), self.rec.agents["population_id"].fillna("")))
                              if len(self.rec.agents) else {})
        self.name = self.rec.metadata.get("throng_scenario_name") or os.path.basename(args.recording)
        self.lines, self.area, self.notes = self._measurement(args, G)
        progress(f"{self.agents} agents, {self.frames} frames at {self.fps:g} fps")

    def _measurement(self, args, G):
        notes = {}
        own_lines, own_area = G.scenario_measurements(self.rec.scenario)
        if args.line:
            lines = [{"name": "line", "line": G.check_line(args.line, self.world), "normal": None}]
        elif own_lines:
            lines = own_lines
        else:
            start = self.traj.groupby("id").first()[["x", "y"]].mean().to_numpy() if len(self.traj) else (0.0, 0.0)
            lines = G.exit_lines(self.exits, self.rings, start)
            if not lines:
                notes["flow"] = "the recording has no exit to put a measurement line in front of; give --line x0,y0,x1,y1"
        if args.area:
            area = G.check_area(args.area, self.world)
        elif own_area:
            area = own_area
        else:
            area = G.area_in_front(lines[0], self.rings) if lines and lines[0].get("width") else None
            if area is None:
                notes["fd"] = "no default measurement area (no exit with a walkable stretch in front of it); give --area x0,y0,x1,y1"
        return lines, area, notes


def direction_of(line):
    """+1 / -1: the crossing direction (analysis.crossings) toward the exit; None: both count."""
    if line.get("normal") is None:
        return None
    (x0, y0), (x1, y1) = line["line"]
    left = (-(y1 - y0), x1 - x0)
    return 1 if left[0] * line["normal"][0] + left[1] * line["normal"][1] > 0 else -1


def frame_step(fps):
    return max(1, int(round(SPEED_HALF_WINDOW_S * fps)))


def cell_grids(inp, cell, A, G, definition="classic", speed_definition="classic"):
    """Per cell: mean classic (or Voronoi) density over every recorded frame (Voronoi: at most
    voronoi.MAX_FRAMES of them) [1/m²] and mean individual speed [m/s] (NaN where nobody was seen,
    or the cell's centre is not walkable; Voronoi: the area-weighted speed of the Voronoi cells over
    the same frames as the density); the cell edges."""
    import numpy as np
    xs, ys = G.grid(inp.world, cell)
    t = inp.traj
    if definition == "voronoi":
        from plotting import voronoi as V
        density, used = V.voronoi_density(t, xs, ys, inp.rings, G.inside_walkable)
        progress(f"Voronoi density over {used} frames")
    else:
        counts, _, _ = np.histogram2d(t["x"], t["y"], bins=(xs, ys))
        density = counts / (max(inp.frames, 1) * cell * cell)
    speeds = A.individual_speed(t, inp.fps, frame_step(inp.fps)).merge(t[["id", "frame", "x", "y"]], on=["id", "frame"])
    n, _, _ = np.histogram2d(speeds["x"], speeds["y"], bins=(xs, ys))
    total, _, _ = np.histogram2d(speeds["x"], speeds["y"], bins=(xs, ys), weights=speeds["speed"])
    if speed_definition == "voronoi":
        from plotting import voronoi as V
        speed, used = V.voronoi_speed(t, speeds, xs, ys, inp.rings, G.inside_walkable)
        progress(f"Voronoi speed over {used} frames")
    else:
        with np.errstate(invalid="ignore", divide="ignore"):
            speed = np.where(n > 0, total / n, np.nan)
    cx, cy = np.meshgrid((xs[:-1] + xs[1:]) / 2, (ys[:-1] + ys[1:]) / 2, indexing="ij")
    walkable = G.inside_walkable(cx.ravel(), cy.ravel(), inp.rings).reshape(cx.shape) if inp.rings else np.ones(cx.shape, bool)
    density = np.where(walkable, density, np.nan)
    speed = np.where(walkable, speed, np.nan)
    return density, speed, xs, ys, speeds


def measure_lines(inp, A, M):
    """Per line: its N(t), windowed flow and numbers (passings, flow (N-1)/(t_N-t_1), first and last)."""
    series, numbers = [], []
    for line in inp.lines:
        direction = direction_of(line)
        c = A.crossings(inp.traj, line["line"])
        if direction is not None:
            c = c[c["direction"] == direction]
        first = c.groupby("id")["frame"].min()  # an agent's first passing only
        stats = M.flow_and_gaps(first.to_numpy() / inp.fps)
        nt = A.n_t(inp.traj, line["line"], inp.fps, direction)
        series.append((line["name"], nt, A.flow(c, inp.fps, FLOW_WINDOW_S)))
        (x0, y0), (x1, y1) = line["line"]
        numbers.append({"name": line["name"], "line": [x0, y0, x1, y1],
                        "counted": "toward the exit" if direction is not None else "both directions",
                        "passings": stats["passed"], "flow": stats["flow"],
                        "first_s": float(first.min() / inp.fps) if len(first) else None,
                        "last_s": float(first.max() / inp.fps) if len(first) else None,
                        "longest_gap_s": stats["longest_gap"]})
    return series, numbers


def measure_area(inp, A):
    """Density and mean speed in the area per frame: analysis.fundamental_diagram, less the frames where none
    of those inside has a speed yet (a trajectory's first and last frame_step frames have none)."""
    fd = A.fundamental_diagram(inp.traj, inp.area, inp.fps, frame_step(inp.fps))
    speeds = A.individual_speed(inp.traj, inp.fps, frame_step(inp.fps)).merge(inp.traj[["id", "frame", "x", "y"]],
                                                                              on=["id", "frame"])
    sampled = speeds.loc[A.inside(speeds["x"].to_numpy(), speeds["y"].to_numpy(), inp.area), "frame"].unique()
    fd = fd[fd.index.isin(sampled)]
    return fd, {"polygon": [list(p) for p in inp.area], "frames": int(len(fd)),
                "mean_density": float(fd["density"].mean()) if len(fd) else 0.0,
                "max_density": float(fd["density"].max()) if len(fd) else 0.0,
                "mean_speed": float(fd["speed"].mean()) if len(fd) else None}


def draw(args, inp, plt, A, M, G, F):
    """Writes the wanted figures; returns (files {figure: path}, numbers)."""
    files, numbers = {}, {}
    path = lambda what: os.path.join(args.out, f"{what}.png")  # noqa: E731
    wanted = [w for w in FIGURES if w in args.what]
    for k, what in enumerate(wanted, 1):
        if what in inp.notes:
            numbers.setdefault("skipped", {})[what] = inp.notes[what]
            progress(f"[{k}/{len(wanted)}] {what}: skipped: {inp.notes[what]}")
            continue
        progress(f"[{k}/{len(wanted)}] {what} -> {path(what)}")
        if what == "trajectories":
            F.trajectories(plt, path(what), inp.traj, inp.rec.walkable_area, inp.world, inp.population_of, inp.exits,
                           inp.lines, inp.area, inp.name)
        elif what in ("density", "speed"):
            if "_grids" not in numbers:
                numbers["_grids"] = cell_grids(inp, args.cell, A, G, args.density, args.speed)
            density, speed, xs, ys, samples = numbers["_grids"]
            values = density if what == "density" else speed
            label = (f"mean {args.density} density [1/m²]" if what == "density"
                     else f"mean {args.speed} speed [m/s]").replace("voronoi", "Voronoi").replace("classic speed", "speed")
            F.heatmap(plt, path(what), values, xs, ys, inp.rec.walkable_area, inp.world, label,
                      f"{inp.name}: {label} ({args.cell:g} m cells)", "magma_r" if what == "density" else "viridis")
            numbers[what] = grid_numbers(values, samples, args.cell, what)
            numbers[what]["definition"] = args.density if what == "density" else args.speed
        elif what == "flow":
            series, numbers["lines"] = measure_lines(inp, A, M)
            F.passings(plt, path(what), series, FLOW_WINDOW_S, f"{inp.name}: passings at the measurement line(s)")
        else:
            fd, numbers["area"] = measure_area(inp, A)
            F.fundamental(plt, path(what), fd, M.weidmann, f"{inp.name}: fundamental diagram in the measurement area")
        files[what] = path(what)
    numbers.pop("_grids", None)
    return files, numbers


def grid_numbers(values, samples, cell, what):
    import numpy as np
    finite = values[np.isfinite(values)]
    out = {"cell_m": cell, "max": float(finite.max()) if len(finite) else 0.0, "cells": int(len(finite))}
    if what == "density":
        out["mean"] = float(finite.mean()) if len(finite) else 0.0
    else:
        out["mean"] = float(samples["speed"].mean()) if len(samples) else None
        out["samples"] = int(len(samples))
    return out


def summary(args, inp, files, numbers):
    return {"recording": os.path.abspath(args.recording), "scenario": inp.name, "fps": inp.fps, "frames": inp.frames,
            "agents": inp.agents, "out": os.path.abspath(args.out),
            "files": {k: os.path.abspath(v) for k, v in files.items()}, **numbers}


def print_summary(s):
    for what, path in s["files"].items():
        print(f"{what:13s} {path}")
    for line in s.get("lines", []):
        flow = f"{line['flow']:.2f}/s" if line["passings"] > 1 else "-"
        print(f"line {line['name']}: {line['passings']} passings ({line['counted']}), flow {flow}")
    if "area" in s:
        a = s["area"]
        print(f"area: {a['frames']} frames with someone inside, mean density {a['mean_density']:.2f}/m², "
              f"mean speed {a['mean_speed'] if a['mean_speed'] is None else round(a['mean_speed'], 2)} m/s")
    for what, why in s.get("skipped", {}).items():
        print(f"{what}: skipped: {why}")


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    try:
        args = parse_args(argv)
    except UsageError as e:
        prog = argv[argv.index("--prog") + 1] if "--prog" in argv[:-1] else "plot.py"
        print(f"{prog}: error: {e}\nRun '{prog} --help' for the flags.", file=sys.stderr)
        return 2
    PROG[0] = args.prog
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        A = _load("throng_analysis", "analysis.py")
        R = _load("throng_recording", "recording.py")
        from plotting import figures as F, geometry as G
        from validation import measures as M
    except ImportError as e:
        error(f"{e}; expected Debian's python3-numpy, python3-pandas and python3-matplotlib (run with /usr/bin/python3)")
        return 1
    try:
        inp = Input(args, R, G)
    except (OSError, ValueError) as e:
        error(str(e))
        return 1
    if args.out is None:
        args.out = os.path.splitext(args.recording)[0] + "-plots"
    explicit = [w for w in args.what if w in inp.notes] if len(args.what) < len(FIGURES) else []
    if explicit:
        error(f"{explicit[0]}: {inp.notes[explicit[0]]}")
        return 1
    try:
        os.makedirs(args.out, exist_ok=True)
    except OSError as e:
        error(f"--out {args.out}: {e.strerror}; expected a directory that can be created and written")
        return 1
    files, numbers = draw(args, inp, plt, A, M, G, F)
    s = summary(args, inp, files, numbers)
    if args.json:
        print(json.dumps(s, indent=1, allow_nan=False))
    else:
        print_summary(s)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        sys.exit(130)
