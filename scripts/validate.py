#!/usr/bin/python3
"""Validation of throng against pedestrian experiments (issue 17's targets).

Runs throng on the validation experiments, measures the recordings the way the experiments were
measured and prints one table: target, measured, band, PASS/FAIL. Experiments (--only):
  corridor     Juelich corridor uo-145-180-180: speed per density class, specific flow
  jam          Juelich uo-180-180-070: density, speed and flow in the jam behind a 0.70 m exit
  ring         fundamental diagram in a 2 m wide ring, 0.5 ... 5 /m^2, against Weidmann
  single-file  0.8 m wide ring, 1 ... 2 /m, against Seyfried et al. 2005
  bottleneck   75 persons through 1.1 m long bottlenecks 0.5 ... 1.2 m wide
  room         200 agents leave a 10 x 10 m room through a 1 m door: flow, overlaps, walking back
  counterflow  60 + 60 agents in opposite directions in a 4 m corridor: lanes, no deadlock
  door         the bundled 1 m door (scenarios/bottleneck.json)

usage: /usr/bin/python3 scripts/validate.py [--model SPEC] [--only NAME[,NAME]] [--seeds N] [--quick]
           [--radius R] [--check] [--json FILE] [--out-dir DIR] [--no-plots] [--keep DIR]
           [--throng PATH] [--data-dir DIR] [--jobs N]

Exit status: 0; 1 with --check when a selected target is outside its band; 2 for bad flags (an
unknown experiment, a model throng refuses, a missing binary or experiment data).
Needs numpy and matplotlib from Debian (python3-numpy, python3-matplotlib), hence /usr/bin/python3.
Set-ups, measurements and the source of every band: docs/validation.md.
"""
import argparse
import concurrent.futures
import contextlib
import json
import os
import sqlite3
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from validation import experiments as E  # noqa: E402
from validation import plots as P  # noqa: E402
from validation import scenarios as S  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# ../shared/validation-data/juelich next to the checkout (or next to its parent: a git worktree).
DEFAULT_DATA = next((d for d in (os.path.normpath(os.path.join(ROOT, *up, "shared", "validation-data", "juelich"))
                                 for up in ((".."), ("..", ".."))) if os.path.isdir(d)),
                    os.path.normpath(os.path.join(ROOT, "..", "shared", "validation-data", "juelich")))


def progress(text):
    print(f"validate: {text}", file=sys.stderr, flush=True)


class Runner:
    """Writes scenarios (with --model / --radius applied) into a temporary directory and runs
    `throng check` / `throng run` on them, `jobs` runs at a time, one thread each."""

    def __init__(self, binary, tmp, model, radius, jobs):
        self.binary, self.tmp, self.model, self.radius, self.jobs = binary, tmp, model, radius, jobs
        self.count = 0

    def write(self, label, scenario):
        path = os.path.join(self.tmp, f"{label}.json")
        with open(path, "w") as f:
            json.dump(S.with_model(scenario, self.model, self.radius), f)
        return path

    def check(self, label, scenario):
        """(accepted, first diagnostic line or 'ok ...')."""
        res = subprocess.run([self.binary, "check", self.write(label, scenario)], capture_output=True, text=True)
        text = (res.stdout + res.stderr).strip().splitlines()
        first = text[0] if text else ""
        return res.returncode == 0, first.split(": ", 1)[-1] if res.returncode else first

    def nav_margin(self, label, scenario):
        """How far the navmesh keeps agents' centres from walls in `scenario` [m] (`throng check --json`:
        the body radius times the model's passageRatio)."""
        res = subprocess.run([self.binary, "check", "--json", self.write(label, scenario)], capture_output=True, text=True)
        if res.returncode != 0:
            raise RuntimeError(f"throng check {label}: {(res.stdout + res.stderr).strip()}")
        return float(json.loads(res.stdout)["nav_margin_m"])

    def _one(self, task):
        label, scenario, seed, duration = task
        progress(f"run {label} seed {seed}")
        path = self.write(f"{label}-s{seed}", scenario)
        rec = os.path.join(self.tmp, f"{label}-s{seed}.sqlite")
        cmd = [self.binary, "run", path, "--out", rec, "--force", "--seed", str(seed), "--quiet", "--json",
               "--threads", "1"]
        if duration is not None:
            cmd += ["--duration", str(duration)]
        res = subprocess.run(cmd, capture_output=True, text=True)
        if res.returncode != 0:
            lines = res.stderr.strip().splitlines()
            return {"error": f"throng run exit {res.returncode}: " + (lines[0] if lines else "")}
        return {"recording": rec, "summary": json.loads(res.stdout.strip().splitlines()[-1])}

    def run(self, tasks):
        """Results of the tasks (label, scenario, seed, duration or None), in order."""
        self.count += len(tasks)
        with concurrent.futures.ThreadPoolExecutor(max_workers=self.jobs) as pool:
            return list(pool.map(self._one, tasks))


class Context:
    def __init__(self, runner, seeds, quick, data_dir, radius):
        self.runner, self.seeds, self.quick, self.data_dir, self.radius = runner, seeds, quick, data_dir, radius
        self.targets = E.Targets()


def parse_model(spec):
    """A model name or a JSON object with "name"; None when not given."""
    if spec is None:
        return None
    spec = spec.strip()
    if spec.startswith("{"):
        try:
            model = json.loads(spec)
        except json.JSONDecodeError as e:
            raise ValueError(f"--model: not valid JSON ({e})")
        if not isinstance(model, dict) or not isinstance(model.get("name"), str):
            raise ValueError('--model: a JSON object needs a "name" string, e.g. {"name":"cfsm","timeGap":0.9}')
        return model
    if not spec:
        raise ValueError("--model: empty")
    return spec


def model_tag(model):
    if model is None:
        return "default model"
    if isinstance(model, str):
        return model
    extra = ",".join(f"{k}={v}" for k, v in model.items() if k != "name")
    return model["name"] + (f" {extra}" if extra else "")


def default_radius(runner):
    """The body radius the engine gives a population that names none [m] (from a 0.1 s run)."""
    probe = {"format": "throng/1", "walkable": [[[0, 0], [6, 0], [6, 6], [0, 6]]], "populations": [
        {"id": "probe", "groups": 1, "spawn": {"polygon": [[1, 1], [5, 1], [5, 5], [1, 5]]}}]}
    res = runner.run([("radius-probe", probe, 1, 0.1)])[0]
    if res.get("error"):
        raise RuntimeError(res["error"])
    db = sqlite3.connect(res["recording"])
    try:
        return float(db.execute("SELECT radius FROM throng_populations").fetchone()[0])
    finally:
        db.close()


def check_model(binary, model, tmp):
    """Lets `throng check` judge the model on a small scenario: (ok, message)."""
    probe = {"format": "throng/1", "walkable": [[[0, 0], [6, 0], [6, 6], [0, 6]]], "populations": [
        {"id": "probe", "groups": 1, "spawn": {"polygon": [[1, 1], [5, 1], [5, 5], [1, 5]]}}]}
    runner = Runner(binary, tmp, model, None, 1)
    return runner.check("model-probe", probe)


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="\n\n".join(p for p in __doc__.split("\n\n")[1:] if not p.startswith("usage")))
    ap.add_argument("--throng", default=os.path.join(ROOT, "build", "apps", "throng", "throng"),
                    help="path to the throng binary (default: build/apps/throng/throng)")
    ap.add_argument("--data-dir", default=DEFAULT_DATA, help=f"experiment files (default: {DEFAULT_DATA})")
    ap.add_argument("--out-dir", default=os.path.join(ROOT, "docs", "img"), help="where the PNGs go (default: docs/img)")
    ap.add_argument("--model", metavar="SPEC",
                    help='every population walks with this model: a name (orca, cfsm) or a JSON object '
                         '\'{"name":"cfsm","timeGap":0.9}\' (default: the scenarios\' own, i.e. the engine default)')
    ap.add_argument("--radius", type=float, metavar="R",
                    help="every population gets this body radius [m] (default: the engine's default body)")
    ap.add_argument("--only", metavar="NAME[,NAME]", help=f"run only these experiments: {', '.join(E.EXPERIMENTS)}")
    ap.add_argument("--seeds", type=int, metavar="N", help="seeds per scenario (default 5, --quick 1)")
    ap.add_argument("--quick", action="store_true", help="one seed, shorter rings and rooms (well under a minute)")
    ap.add_argument("--jobs", type=int, default=2, metavar="N", help="throng runs at a time (default 2)")
    ap.add_argument("--check", action="store_true", help="exit status 1 when a selected target is outside its band")
    ap.add_argument("--json", metavar="FILE", help="write every figure as JSON to FILE ('-' = stdout)")
    ap.add_argument("--no-plots", action="store_true", help="skip the PNGs")
    ap.add_argument("--keep", metavar="DIR",
                    help="keep every generated scenario (model applied) and recording in DIR (default: a "
                         "temporary directory, removed)")
    args = ap.parse_args(argv)
    names = list(E.EXPERIMENTS) if not args.only else [n.strip() for n in args.only.split(",") if n.strip()]
    bad = [n for n in names if n not in E.EXPERIMENTS]
    if bad or not names:
        ap.error(f"--only: unknown experiment {', '.join(bad) or '(none)'}; expected some of {', '.join(E.EXPERIMENTS)}")
    args.only = names
    if args.seeds is not None and args.seeds < 1:
        ap.error("--seeds: at least 1")
    if args.jobs < 1:
        ap.error("--jobs: at least 1")
    if args.radius is not None and not 0.05 <= args.radius <= 1:
        ap.error("--radius: 0.05 ... 1 m")
    try:
        args.model = parse_model(args.model)
    except ValueError as e:
        ap.error(str(e))
    if not os.access(args.throng, os.X_OK):
        ap.error(f"throng binary {args.throng} not found or not executable (use --throng)")
    needs = [n for n in names if n in E.NEEDS_DATA]
    if needs and not os.path.isdir(args.data_dir):
        ap.error(f"{', '.join(needs)} need the experiment data, not found in {args.data_dir} (use --data-dir)")
    return args


def print_table(rows, tag, out=sys.stdout):
    print(f"throng validation ({tag}): target, measured, band", file=out)
    w = max(len(r["target"]) for r in rows) if rows else 10
    print(f"{'experiment':<12} {'target':<{w}} {'measured':>10} {'band':>16} {'unit':<8} result  note", file=out)
    for r in rows:
        m = "—" if r["measured"] is None else f"{r['measured']:.3f}"
        if r["band"] is None:
            band = "(reported)"
        else:
            lo, hi = r["band"]
            band = f"≥ {lo:.3g}" if hi is None else f"≤ {hi:.3g}" if lo in (None, 0.0) and hi != lo else \
                f"= {lo:.3g}" if lo == hi else f"{lo:.3g} … {hi:.3g}"
        print(f"{r['experiment']:<12} {r['target']:<{w}} {m:>10} {band:>16} {r['unit']:<8} {r['status']:<7} {r['note']}",
              file=out)
    passed = sum(r["status"] == "PASS" for r in rows)
    failed = sum(r["status"] == "FAIL" for r in rows)
    print(f"{passed} passed, {failed} failed, {len(rows) - passed - failed} reported", file=out)


def strip(obj):
    """Drops the private numpy series before JSON output."""
    if isinstance(obj, dict):
        return {str(k): strip(v) for k, v in obj.items() if not str(k).startswith("_")}
    if isinstance(obj, (list, tuple)):
        return [strip(v) for v in obj]
    return obj


def write_plots(results, out_dir, tag, suffix):
    os.makedirs(out_dir, exist_ok=True)
    path = lambda name: os.path.join(out_dir, f"validation-{name}{suffix}.png")  # noqa: E731
    if "corridor" in results or "jam" in results:
        P.corridor(results, path("corridor"), tag)
    if "bottleneck" in results:
        P.bottleneck_cumulative(results["bottleneck"], path("bottleneck"), tag)
        P.bottleneck_widths(results["bottleneck"], E.bottleneck_trend, path("bottleneck-widths"), tag)
    if "ring" in results:
        P.ring(results["ring"], path("ring"), tag)
    if "single-file" in results:
        P.single_file(results["single-file"], path("single-file"), tag)


def main(argv=None):
    args = parse_args(argv)
    started = time.time()
    tag = model_tag(args.model)
    seeds = list(range(1, (args.seeds or (1 if args.quick else 5)) + 1))
    if args.keep:
        os.makedirs(args.keep, exist_ok=True)
    with (contextlib.nullcontext(args.keep) if args.keep else tempfile.TemporaryDirectory(prefix="throng-validate-")) as tmp:
        if args.model is not None:
            ok, message = check_model(args.throng, args.model, tmp)
            if not ok:
                print(f"validate.py: --model: throng refuses it: {message}", file=sys.stderr)
                return 2
        runner = Runner(args.throng, tmp, args.model, args.radius, args.jobs)
        ctx = Context(runner, seeds, args.quick, args.data_dir, args.radius or default_radius(runner))
        results = {}
        for name in args.only:
            progress(f"experiment {name} ({tag}, seeds {seeds[0]}..{seeds[-1]})")
            results[name] = E.EXPERIMENTS[name](ctx)
    if not args.no_plots:
        suffix = "" if args.model is None else "-" + model_tag(args.model).split()[0]
        write_plots(results, args.out_dir, tag, suffix)
    print_table(ctx.targets.rows, tag)
    wall = time.time() - started
    print(f"({runner.count} throng runs, {wall:.1f} s)")
    if args.json:
        summary = {"model": args.model, "model_tag": tag, "body_radius": ctx.radius,
                   "body_radius_from": "--radius" if args.radius else "engine default", "seeds": seeds, "quick": args.quick,
                   "experiments": args.only, "targets": ctx.targets.rows, "results": strip(results),
                   "runs": runner.count, "wall_time_s": wall}
        text = json.dumps(summary, indent=1, allow_nan=False, default=float)
        if args.json == "-":
            print(text)
        else:
            with open(args.json, "w") as f:
                f.write(text + "\n")
    return 1 if args.check and ctx.targets.failed() else 0


if __name__ == "__main__":
    sys.exit(main())
