"""The experiments of scripts/validate.py: each sets up its scenarios, has the runner simulate them,
measures the recordings (measures.py) and adds its targets (target, measured, band) to a Targets
list. docs/validation.md gives the set-ups, the measurements and the source of every band.

Every experiment is a function (ctx) -> dict of results (JSON-able, private numpy series under keys
starting with "_"); ctx carries the runner, the targets, the seeds, --quick, the experiment data
and the body radius the agents get (--radius or the engine's default).
"""
import json
import math
import os

import numpy as np

from . import measures as M
from . import scenarios as S

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENARIO_DIR = os.path.join(ROOT, "scenarios", "validation")


class Targets:
    """Rows (experiment, target, measured, band (lo, hi) or None, unit, note); None measured = FAIL."""

    def __init__(self):
        self.rows = []

    def add(self, experiment, name, measured, lo=None, hi=None, unit="", note=""):
        informative = lo is None and hi is None
        if informative:
            status = "INFO"
        elif measured is None or not np.isfinite(measured):
            status = "FAIL"
        else:
            status = "PASS" if (lo is None or measured >= lo) and (hi is None or measured <= hi) else "FAIL"
        self.rows.append({"experiment": experiment, "target": name,
                          "measured": None if measured is None else float(measured),
                          "band": None if informative else [lo, hi], "unit": unit, "status": status, "note": note})

    def failed(self):
        return [r for r in self.rows if r["status"] == "FAIL"]


def _mean(values):
    values = [v for v in values if v is not None]
    return float(np.mean(values)) if values else None


def _max(values):
    values = [v for v in values if v is not None]
    return float(np.max(values)) if values else None


# --- Jülich corridor and jam (experiment files in ../shared/validation-data/juelich) ---------------
CORRIDOR_AREA = (0.0, 1.8, -2.0, 0.0)  # x0, x1, y0, y1 [m]: 3.6 m^2
CORRIDOR_LINE_Y = 0.0                  # measurement line (0,0)-(1.8,0), walking direction -y
CORRIDOR_WIDTH = 1.8                   # [m]
CORRIDOR_RUNS = {
    # name: (experiment file, unit scale to metres, fps, steady-state frames)
    "uo-145-180-180": ("uo-145-180-180.txt", 0.01, 16.0, (300, 1097)),
    "uo-180-180-070": ("uo-180-180-070.txt", 0.01, 16.0, (500, 1399)),
}
DENSITY_BIN = 0.5             # width of the density classes [1/m^2]
# A class is compared when it holds this much steady-state time [s]: in the experiment's one run,
# or pooled over the simulation's seeds (the class mean's precision depends on the frames it pools).
# Until session 41 each seed had to give 2 s (10 s over 5 seeds): the experiment itself has 3.2 s in
# the 0.5-1.0 /m² class and 2.25 s in the 2.0-2.5 one, so a simulation with the experiment's own
# share of sparse frames could not be compared there. The notes say how many seconds each class has.
MIN_FRAMES_PER_BIN_S = 2.0
# Issue 17's targets: the experiment's steady-state classes (class -> speed) and Js.
CORRIDOR_TARGETS = [((0.5, 1.0), 0.82, 1.12), ((1.0, 1.5), 1.31, 1.05), ((1.5, 2.0), 1.77, 0.97),
                    ((2.0, 2.5), 2.22, 0.91)]
CORRIDOR_SPEED_TOL = 0.12
CORRIDOR_JS, CORRIDOR_JS_TOL = 1.55, 0.10
JAM_DENSITY, JAM_SPEED, JAM_FLOW, JAM_FLOW_TOL = (2.5, 4.5), (0.25, 0.45), 0.94, 0.15


def corridor_measures(traj, frames):
    """Steady-state measures of a corridor run: density classes, means, specific flow."""
    _, rho, v = traj.area_series(CORRIDOR_AREA, frames)
    ok = np.isfinite(v)
    t0, t1 = frames[0] / traj.fps, frames[1] / traj.fps
    cross = traj.crossings(CORRIDOR_LINE_Y, (CORRIDOR_AREA[0], CORRIDOR_AREA[1]))
    n_line = int(np.sum((cross >= t0) & (cross <= t1)))
    return {"frames": [int(frames[0]), int(frames[1])], "fps": traj.fps, "persons": int(len(traj.persons())),
            "mean_density": float(rho.mean()), "mean_speed": float(np.nanmean(v)) if ok.any() else 0.0,
            "weidmann_at_mean_density": float(M.weidmann(rho.mean())),
            "specific_flow_rho_v": float(np.where(ok, rho * np.nan_to_num(v), 0.0).mean()),
            "specific_flow_line": n_line / (t1 - t0) / CORRIDOR_WIDTH,
            "classes": pool_classes([(rho[ok], v[ok])], traj.fps),
            "_series": (rho[ok], v[ok])}


def pool_classes(series, fps):
    """Density classes 0.5 /m^2 wide of several runs' (rho, v) frame series, pooled (frame-weighted);
    a class with under MIN_FRAMES_PER_BIN_S seconds of frames in the pool is left out."""
    edges = np.arange(0.0, 8.0 + DENSITY_BIN, DENSITY_BIN)
    rs = np.concatenate([s[0] for s in series])
    vs = np.concatenate([s[1] for s in series])
    out = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        sel = (rs >= lo) & (rs < hi)
        if sel.sum() >= MIN_FRAMES_PER_BIN_S * fps:
            out.append({"class": [float(lo), float(hi)], "density": float(rs[sel].mean()), "seconds": float(sel.sum() / fps),
                        "speed": float(vs[sel].mean()), "speed_sd": float(vs[sel].std()), "frames": int(sel.sum()),
                        "weidmann": float(M.weidmann(rs[sel].mean()))})
    return out


def _experiment_corridor(ctx, name):
    fname, scale, fps, frames = CORRIDOR_RUNS[name]
    traj = M.load_text(os.path.join(ctx.data_dir, fname), scale, fps)
    return corridor_measures(traj, frames)


def _simulate_corridor(ctx, name):
    with open(os.path.join(SCENARIO_DIR, f"{name}.json")) as f:
        scen = json.load(f)
    _, _, exp_fps, exp_frames = CORRIDOR_RUNS[name]
    runs = []
    for seed, res in zip(ctx.seeds, ctx.runner.run([(name, scen, s, None) for s in ctx.seeds])):
        if res.get("error"):
            runs.append({"seed": seed, "error": res["error"]})
            continue
        traj = M.load_recording(res["recording"])
        # The scenarios replay the measured inflow on the experiment's clock: same window in seconds.
        m = corridor_measures(traj, tuple(int(round(f / exp_fps * traj.fps)) for f in exp_frames))
        m.update(seed=seed, exited=res["summary"]["agents_exited"], spawned=res["summary"]["agents_spawned"])
        runs.append(m)
    ok = [r for r in runs if "error" not in r]
    pooled = pool_classes([r["_series"] for r in ok], ok[0]["fps"]) if ok else []
    return {"experiment": _experiment_corridor(ctx, name), "runs": runs, "classes": pooled}


def corridor(ctx):
    """uo-145-180-180: speed per density class and specific flow (issue 17 bands)."""
    out = _simulate_corridor(ctx, "uo-145-180-180")
    runs = [r for r in out["runs"] if "error" not in r]
    for (lo, hi), rho, v in CORRIDOR_TARGETS:
        cls = next((c for c in out["classes"] if c["class"][0] == lo), None)
        exp = next((c for c in out["experiment"]["classes"] if c["class"][0] == lo), None)
        exp_s = f"experiment {exp['seconds']:.1f} s" if exp else "experiment none"
        ctx.targets.add("corridor", f"speed, density class {lo:.1f}-{hi:.1f} (exp. {rho:.2f} /m²)",
                        cls and cls["speed"], v - CORRIDOR_SPEED_TOL, v + CORRIDOR_SPEED_TOL, "m/s",
                        f"under {MIN_FRAMES_PER_BIN_S:g} s of steady-state frames in this class ({exp_s})" if cls is None
                        else f"ρ̄ = {cls['density']:.2f}, {cls['seconds']:.1f} s of frames over {len(runs)} runs ({exp_s})")
    js = _mean([r["specific_flow_rho_v"] for r in runs])
    ctx.targets.add("corridor", "specific flow Js = ρv", js, CORRIDOR_JS * (1 - CORRIDOR_JS_TOL),
                    CORRIDOR_JS * (1 + CORRIDOR_JS_TOL), "1/(m·s)")
    return out


def jam(ctx):
    """uo-180-180-070: density, speed and flow in the jam behind the 0.70 m exit."""
    out = _simulate_corridor(ctx, "uo-180-180-070")
    runs = [r for r in out["runs"] if "error" not in r]
    ctx.targets.add("jam", "mean density, steady state", _mean([r["mean_density"] for r in runs]), *JAM_DENSITY, "1/m²")
    ctx.targets.add("jam", "mean speed, steady state", _mean([r["mean_speed"] for r in runs]), *JAM_SPEED, "m/s")
    ctx.targets.add("jam", "specific flow J/b at the line", _mean([r["specific_flow_line"] for r in runs]),
                    JAM_FLOW * (1 - JAM_FLOW_TOL), JAM_FLOW * (1 + JAM_FLOW_TOL), "1/(m·s)",
                    f"left at end: {[r['spawned'] - r['exited'] for r in runs]}")
    return out


# --- Rings ----------------------------------------------------------------------------------------
# The slabs (interest points) reach 3 cm into the navmesh's eroded margin (the model's: radius x
# passageRatio from the walls, 0.13 m for avm's default body; `throng check --json` nav_margin_m) so
# that they span every place an agent can be: an agent that passes beside a slab has to walk back
# to it (with slabs 5 cm inside the margin, 40-60 % of the agents at 2 /m² walked backwards at some
# time; with slabs at ORCA's margin, 1.25 r, avm's agents along the walls passed beside them and 2 %
# of the samples at 4-5 /m² were backward). Their targets are snapped onto the navmesh (sim/goals.cpp).
RING = {"r_in": 3.0, "r_out": 5.0, "slabs": 12, "densities": [0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0]}
# Single file: passing was prohibited in the experiment and people walked in line along the
# corridor's middle, so its waypoints span the middle 0.2 m ("pad": 0.3 m from either wall). Spanning
# the whole width, they drew every agent's next target anywhere across it, 1.6 m ahead: agents wove
# from wall to wall and walked staggered, half a body aside, which no participant did
# (docs/validation.md: 0.47 / 0.30 m/s at 1.5 / 2 /m with full-width waypoints, 0.40 / 0.21 with these).
SINGLE_FILE = {"r_in": 3.74, "r_out": 4.54, "slabs": 16, "densities": [1.0, 1.5, 2.0], "pad": 0.3}
SLAB_PAD = lambda margin: margin - 0.03  # noqa: E731  [m], margin: the navmesh's (nav_margin_m)
RING_SPEED_TOL = 0.15
BACKWARD_SPEED = -0.05   # a tangential speed below this is a backward sample [m/s]
BACKWARD_MAX = 0.02
SPAWN_PACKING = 0.5      # throng check: a spawn area holds at most packing * area / (pi r^2) agents
# Measured over the whole ring: in a closed ring the global density N / A is exact and pairs with
# the space-mean speed; a sector's time average is biased by platoons over a 30 s window.
SECTOR = (0.0, 2 * math.pi)
WAVE_GAP_S = 1.0         # spawn waves this far apart [s]


def _ring_windows(ctx):
    return (10.0, 15.0) if ctx.quick else (20.0, 30.0)


def _ring_runs(ctx, label, geo, agents_of, size_of):
    """Simulates a ring per density and seed; returns per density the runs' ring_measures."""
    warm, span = _ring_windows(ctx)
    radius = ctx.radius
    margin = ctx.runner.nav_margin(f"{label}-margin", S.ring(geo["r_in"], geo["r_out"], 1, warm + span, slabs=geo["slabs"]))
    tasks, meta = [], []
    for rho in geo["densities"]:
        n = agents_of(rho)
        scen = S.ring(geo["r_in"], geo["r_out"], n, warm + span, slabs=geo["slabs"], name=f"{label} {rho}",
                      pad=geo.get("pad", SLAB_PAD(margin)))
        # Above what `throng check` accepts in one wave, spawn in waves 1 s apart (docs/validation.md).
        per_wave = SPAWN_PACKING * S.ring_area(geo["r_in"], geo["r_out"]) / (math.pi * radius * radius)
        waves = max(1, math.ceil(n / (0.97 * per_wave)))
        scen = S.in_waves(scen, waves, WAVE_GAP_S)
        for seed in ctx.seeds:
            tasks.append((f"{label}-{rho}", scen, seed, warm + span))
            meta.append((rho, n, waves, seed))
    results = ctx.runner.run(tasks)
    per = {}
    for (rho, n, waves, seed), res in zip(meta, results):
        row = per.setdefault(rho, {"nominal_density": rho, "agents": n, "spawn_waves": waves, "runs": []})
        if res.get("error"):
            row["runs"].append({"seed": seed, "error": res["error"]})
            continue
        traj = M.load_recording(res["recording"])
        m = M.ring_measures(traj, SECTOR, size_of, warm, warm + span, BACKWARD_SPEED)
        m.update(seed=seed, spawned=res["summary"]["agents_spawned"],
                 spawn_overlaps=M.overlapping_pairs(traj, int(round((waves - 1) * WAVE_GAP_S * traj.fps)) + 1),
                 overlap=M.max_overlap(traj, warm), overlap_after_1s=M.max_overlap(traj, 1.0 + waves))
        row["runs"].append(m)
    return per


def _ring_summary(row, reference):
    runs = [r for r in row["runs"] if "error" not in r]
    samples = sum(r["samples"] for r in runs)
    row.update(density=_mean([r["density"] for r in runs]), speed=_mean([r["speed"] for r in runs]),
               speed_full=_mean([r["speed_full"] for r in runs]),
               backward_fraction=sum(r["backward_fraction"] * r["samples"] for r in runs) / samples if samples else None,
               max_overlap=_max([r["overlap"]["max_depth"] for r in runs]),
               spawn_overlaps=[r["spawn_overlaps"] for r in runs],
               spawned=[r["spawned"] for r in runs])
    row["reference_speed"] = float(reference(row["density"])) if row["density"] is not None else None
    return row


def ring(ctx):
    """Fundamental diagram in a 2 m wide ring (r 3..5 m) against Weidmann."""
    g = RING
    area = S.ring_area(g["r_in"], g["r_out"])
    size = area * (SECTOR[1] - SECTOR[0]) / (2 * math.pi)
    per = _ring_runs(ctx, "ring", g, lambda rho: int(round(rho * area)), size)
    for rho, row in per.items():
        _ring_summary(row, M.weidmann)
        ref = row["reference_speed"]
        note = f"ρ̄ = {row['density']:.2f}, Weidmann {ref:.2f}" if ref is not None else "no run"
        if row["spawn_waves"] > 1:
            note += f"; spawned in {row['spawn_waves']} waves"
        if any(row["spawn_overlaps"]):
            note += f"; pairs spawned overlapping > 5 cm: {row['spawn_overlaps']}"
        ctx.targets.add("ring", f"speed at {rho:g} /m² (Weidmann ± {RING_SPEED_TOL})", row["speed"],
                        None if ref is None else ref - RING_SPEED_TOL, None if ref is None else ref + RING_SPEED_TOL,
                        "m/s", note)
        ctx.targets.add("ring", f"backward samples at {rho:g} /m²", row["backward_fraction"], 0.0, BACKWARD_MAX, "")
    deepest = _max([row["max_overlap"] for row in per.values()])
    ctx.targets.add("ring", "max overlap depth, all densities", deepest, unit="m", note="after the warm-up")
    return {"geometry": g, "sector_rad": list(SECTOR), "sector_area_m2": size, "densities": per}


def single_file(ctx):
    """Single file in a 0.8 m wide ring (mid circumference 26 m) against Seyfried et al. 2005."""
    g = SINGLE_FILE
    length = math.pi * (g["r_in"] + g["r_out"])  # mid circumference [m]
    size = length * (SECTOR[1] - SECTOR[0]) / (2 * math.pi)
    per = _ring_runs(ctx, "single-file", g, lambda lam: int(round(lam * length)), size)
    for lam, row in per.items():
        _ring_summary(row, M.seyfried_1d)
        ref = row["reference_speed"]
        note = f"ρ̄ = {row['density']:.2f} /m, Seyfried {ref:.2f}" if ref is not None else "no run"
        ctx.targets.add("single-file", f"speed at {lam:g} /m (Seyfried 2005 ± {RING_SPEED_TOL})", row["speed"],
                        None if ref is None else ref - RING_SPEED_TOL, None if ref is None else ref + RING_SPEED_TOL,
                        "m/s", note)
        ctx.targets.add("single-file", f"backward samples at {lam:g} /m", row["backward_fraction"], 0.0,
                        BACKWARD_MAX, "")
        ctx.targets.add("single-file", f"max overlap depth at {lam:g} /m", row["max_overlap"], unit="m",
                        note="after the warm-up")
    return {"geometry": g, "mid_circumference_m": length, "sector_rad": list(SECTOR), "sector_length_m": size,
            "densities": per}


# --- Bottlenecks ----------------------------------------------------------------------------------
BOTTLENECK_FILE = "040_c_56_h-.txt"       # metres, 25 fps
BOTTLENECK_WIDTHS = [0.5, 0.6, 0.7, 0.8, 1.0, 1.2]
BOTTLENECK_FLOW_TOL = 0.25
BOTTLENECK_GAP_MAX = 5.0
WUPPERTAL_FLOW_050 = 1.15                 # 040_c_56_h-, measured by this script from the data
SPECIFIC_BOTTLENECK_FLOW = 1.9            # 1/(m s): Seyfried et al. 2009, Kretz et al. 2006, Liddle et al. 2011


def bottleneck_trend(width):
    """Expected flow [1/s]: the Wuppertal run at 0.5 m, 1.9 /(m s) times the width above."""
    return WUPPERTAL_FLOW_050 if abs(width - 0.5) < 1e-9 else SPECIFIC_BOTTLENECK_FLOW * width


def _bottleneck_passings(traj, width):
    t = traj.crossings(0.0, (-width / 2, width / 2))
    return t


def bottleneck(ctx):
    """75 persons through 1.1 m long bottlenecks 0.5 ... 1.2 m wide (default body)."""
    with open(os.path.join(SCENARIO_DIR, "bottleneck-040-c-56.json")) as f:
        base = json.load(f)
    duration = 100.0 if ctx.quick else 150.0
    exp = None
    if ctx.data_dir and os.path.isfile(os.path.join(ctx.data_dir, BOTTLENECK_FILE)):
        bt = M.load_text(os.path.join(ctx.data_dir, BOTTLENECK_FILE), 1.0, 25.0)
        t = _bottleneck_passings(bt, 0.5)
        exp = dict(M.flow_and_gaps(t), times=t.tolist())
    out = {"experiment_050": exp, "widths": {}}
    for w in BOTTLENECK_WIDTHS:
        scen = S.bottleneck_width(base, w)
        accepted, message = ctx.runner.check(f"bottleneck-{w:.2f}", scen)
        row = {"width": w, "accepted": accepted, "check": message, "expected_flow": bottleneck_trend(w), "runs": []}
        if accepted:
            for seed, res in zip(ctx.seeds, ctx.runner.run([(f"bottleneck-{w:.2f}", scen, s, duration)
                                                            for s in ctx.seeds])):
                if res.get("error"):
                    row["runs"].append({"seed": seed, "error": res["error"]})
                    continue
                t = _bottleneck_passings(M.load_recording(res["recording"]), w)
                row["runs"].append(dict(M.flow_and_gaps(t), seed=seed, times=t.tolist()))
        runs = [r for r in row["runs"] if "error" not in r]
        row["flow"] = _mean([r["flow"] for r in runs]) if runs else None
        row["longest_gap"] = _max([r["longest_gap"] for r in runs]) if runs else None
        row["passed"] = [r["passed"] for r in runs]
        ctx.targets.add("bottleneck", f"{w:.1f} m accepted by throng check", 1.0 if accepted else 0.0, 1.0, 1.0, "",
                        "" if accepted else message[:120])
        e = row["expected_flow"]
        ctx.targets.add("bottleneck", f"{w:.1f} m flow (trend {e:.2f} ± 25 %)", row["flow"],
                        e * (1 - BOTTLENECK_FLOW_TOL), e * (1 + BOTTLENECK_FLOW_TOL), "1/s",
                        f"passed {row['passed']} of 75" if accepted else "refused")
        ctx.targets.add("bottleneck", f"{w:.1f} m longest gap", row["longest_gap"], 0.0, BOTTLENECK_GAP_MAX, "s")
        out["widths"][f"{w:.1f}"] = row
    return out


# --- Dense room -----------------------------------------------------------------------------------
ROOM_FLOW = (1.3, 2.2)
ROOM_OVERLAP_MAX = 0.03
ROOM_WALK_BACK_MAX = 0.5


def room(ctx):
    """200 agents leave a 10 x 10 m room through a 1 m door: flow, overlaps, walking back."""
    scen = S.dense_room(200, 200 if ctx.quick else 250)
    runs = []
    for seed, res in zip(ctx.seeds, ctx.runner.run([("room", scen, s, None) for s in ctx.seeds])):
        if res.get("error"):
            runs.append({"seed": seed, "error": res["error"]})
            continue
        traj = M.load_recording(res["recording"])
        t = traj.crossings_axis(traj.x, traj.y, S.ROOM_DOOR_LINE_X, +1, (S.ROOM_DOOR[0][1], S.ROOM_DOOR[1][1]))
        in_room = traj.x < S.ROOM_DOOR[0][0]
        runs.append(dict(seed=seed, exited=res["summary"]["agents_exited"], **M.flow_and_gaps(t),
                         overlap=M.max_overlap(traj, 1.0), walk_back=M.walk_back(traj, S.ROOM_DOOR, in_room)))
    ok = [r for r in runs if "error" not in r]
    flow = _mean([r["flow"] for r in ok])
    depth = _max([r["overlap"]["max_depth"] for r in ok])
    back = _max([r["walk_back"]["max_walk_back"] for r in ok])
    ctx.targets.add("room", "door flow", flow, *ROOM_FLOW, "1/s", f"passed {[r['passed'] for r in ok]} of 200")
    ctx.targets.add("room", "max overlap depth after 1 s", depth, 0.0, ROOM_OVERLAP_MAX, "m",
                    f"agents overlapping > 1 cm: {[r['overlap']['agents_over_1cm'] for r in ok]}")
    ctx.targets.add("room", "max walk-back from the door", back, 0.0, ROOM_WALK_BACK_MAX, "m",
                    f"agents over 0.5 m: {[r['walk_back']['agents_over_0_5m'] for r in ok]}")
    return {"runs": runs, "flow": flow, "max_overlap": depth, "max_walk_back": back}


# --- Counter-flow ---------------------------------------------------------------------------------
LANE_MARGIN = 0.2         # lane order must exceed the shuffled baseline by this much
DEADLOCK_SPEED = 0.2      # [m/s]
LANE_FROM_S = 8.0         # the two streams meet after about 10 s


def counter_flow(ctx):
    """60 + 60 agents in opposite directions in a 4 m corridor: lanes and no deadlock."""
    scen = S.counter_flow()
    east = np.array([p["id"].startswith("east") for p in scen["populations"]])
    runs = []
    for seed, res in zip(ctx.seeds, ctx.runner.run([("counterflow", scen, s, None) for s in ctx.seeds])):
        if res.get("error"):
            runs.append({"seed": seed, "error": res["error"]})
            continue
        traj = M.load_recording(res["recording"])
        labels = east[traj.population].astype(int)
        lanes = M.lane_order_series(traj, labels, S.COUNTER_REGION, LANE_FROM_S, seed=seed)
        x0, x1, y0, y1 = S.COUNTER_REGION
        inside = (traj.x >= x0) & (traj.x <= x1) & np.isfinite(traj.speed)
        runs.append(dict(seed=seed, **lanes, exited=res["summary"]["agents_exited"],
                         spawned=res["summary"]["agents_spawned"], mean_speed=float(traj.speed[inside].mean())))
    ok = [r for r in runs if "error" not in r]
    phi = _mean([r["lane_order"] for r in ok])
    base = _mean([r["lane_order_shuffled"] for r in ok])
    ctx.targets.add("counterflow", f"lane order − shuffled baseline (≥ {LANE_MARGIN})",
                    None if phi is None or base is None else phi - base, LANE_MARGIN, None, "",
                    "" if phi is None else f"φ = {phi:.2f}, shuffled {base:.2f}")
    free = [1.0 if r["exited"] == r["spawned"] or r["mean_speed"] > DEADLOCK_SPEED else 0.0 for r in ok]
    ctx.targets.add("counterflow", "no deadlock (all exit or v̄ > 0.2 m/s), runs", _mean(free) if ok else None,
                    1.0, 1.0, "", f"exited {[r['exited'] for r in ok]} of 120, v̄ {[round(r['mean_speed'], 2) for r in ok]}")
    return {"runs": runs, "lane_order": phi, "lane_order_shuffled": base}


# --- The bundled 1 m door ------------------------------------------------------------------------
DOOR_FLOW = (1.0, 2.5)    # as Scenarios.BottleneckFlowThroughOneMetreDoor


def door(ctx):
    """scenarios/bottleneck.json (100 agents, 1 m door at x = 9..10): flow at x = 9.5."""
    with open(os.path.join(ROOT, "scenarios", "bottleneck.json")) as f:
        scen = json.load(f)
    runs = []
    for seed, res in zip(ctx.seeds, ctx.runner.run([("door", scen, s, None) for s in ctx.seeds])):
        if res.get("error"):
            runs.append({"seed": seed, "error": res["error"]})
            continue
        traj = M.load_recording(res["recording"])
        t = traj.crossings_axis(traj.x, traj.y, 9.5, +1)
        runs.append(dict(seed=seed, **M.flow_and_gaps(t)))
    flow = _mean([r["flow"] for r in runs if "error" not in r])
    ctx.targets.add("door", "1 m door flow (scenarios/bottleneck.json)", flow, *DOOR_FLOW, "1/s")
    return {"runs": runs, "flow": flow}


EXPERIMENTS = {"corridor": corridor, "jam": jam, "ring": ring, "single-file": single_file,
               "bottleneck": bottleneck, "room": room, "counterflow": counter_flow, "door": door}
NEEDS_DATA = {"corridor", "jam"}
