"""Measurements shared by scripts/validate.py, scripts/verify.py and the unit test (tests/scripts/validation_measures_test.py).

Pure functions of trajectories (numpy arrays); nothing here runs throng. Definitions (after PedPy's
documentation and the papers named in docs/validation.md):
- individual velocity: central difference of the position over +-0.3 s, one-sided at the ends of a
  trajectory (speed = its length);
- classic density: persons inside a measurement area / its area, per frame;
- flow through a line: (N - 1) / (t_N - t_1) from the instants the persons first cross it;
- overlap depth of two bodies: r_i + r_j - |x_i - x_j| for discs (positive when they overlap); for
  the bodies of the anticipation model (avm, the default), ellipses of shoulder breadth 2r across
  the heading and depth q * 2r along it (q its passageRatio, the heading the recording's ori_x,
  ori_y), the mean of the two ellipses' reach along the line of centres minus the distance (as
  tests/support/bodies.hpp);
- walk-back: how much farther from a target an agent is than the closest it has been so far;
- lane order (Rex & Loewen 2007): per agent, ((n_same - n_opp) / (n_same + n_opp))^2 over the agents
  in its lateral slice, averaged over agents and frames.
scripts/verify.py (the RiMEA / NIST verification tests) adds: each agent's spawn and exit time and
exit point (load_agents), the model each population walked with (recording_models), positions
inside a polygon, distance to walls and steps that cross a wall, the time each agent first moves,
per-agent speeds in a stretch of x, and how far group members stray from their group's centre.
"""
import sqlite3

import numpy as np

SPEED_HALF_WINDOW_S = 0.3  # central difference +- this time [s]


def weidmann(rho):
    """Weidmann (1993) fundamental diagram v(rho) [m/s], rho in 1/m^2 (0 at rho >= 5.4)."""
    rho = np.asarray(rho, dtype=float)
    with np.errstate(divide="ignore"):
        v = 1.34 * (1.0 - np.exp(-1.913 * (1.0 / rho - 1.0 / 5.4)))
    return np.clip(v, 0.0, 1.34)


def seyfried_1d(rho):
    """Single-file speed [m/s] at line density rho [1/m] (Seyfried et al. 2005, J. Stat. Mech. P10002):
    their linear relation between required length and speed, 1/rho = 0.36 m + 1.06 s * v."""
    rho = np.asarray(rho, dtype=float)
    with np.errstate(divide="ignore"):
        return np.clip((1.0 / rho - 0.36) / 1.06, 0.0, None)


class Trajectories:
    """Rows (id, frame, x, y) sorted by id then frame, with per-row velocity (vx, vy) and speed
    [m/s]; fps [1/s]; radius: per-row body radius [m] (or None); group: per-row population index."""

    def __init__(self, rows, fps, radius_of=None, population_of=None, ori=None, depth_ratio_of=None):
        """ori: optional (ori_x, ori_y) arrays in the order of `rows`, the heading of each row;
        depth_ratio_of: optional agent id -> body depth over shoulder breadth (1 for a disc), with
        ori the bodies are ellipses (max_overlap)."""
        rows = np.asarray(rows, dtype=float).reshape(-1, 4)
        order = np.lexsort((rows[:, 1], rows[:, 0]))
        rows = rows[order]
        self.ori_x = self.ori_y = None
        if ori is not None:
            self.ori_x = np.asarray(ori[0], float)[order]
            self.ori_y = np.asarray(ori[1], float)[order]
        self.fps = float(fps)
        self.id = rows[:, 0].astype(np.int64)
        self.frame = rows[:, 1].astype(np.int64)
        self.x = rows[:, 2]
        self.y = rows[:, 3]
        self.vx, self.vy = self._velocities()
        self.speed = np.hypot(self.vx, self.vy)
        self.radius = None if radius_of is None else np.array([radius_of[i] for i in self.id], float)
        self.population = None if population_of is None else np.array([population_of[i] for i in self.id], int)
        self.depth_ratio = (None if depth_ratio_of is None or ori is None
                            else np.array([depth_ratio_of.get(i, 1.0) for i in self.id], float))

    def _velocities(self):
        k = max(1, int(round(SPEED_HALF_WINDOW_S * self.fps)))
        n = len(self.id)
        if n == 0:
            return np.zeros(0), np.zeros(0)
        idx = np.arange(n)
        starts = np.r_[0, np.flatnonzero(np.diff(self.id)) + 1]
        ends = np.r_[starts[1:], n] - 1
        person = np.repeat(np.arange(len(starts)), np.diff(np.r_[starts, n]))
        lo = np.maximum(idx - k, starts[person])
        hi = np.minimum(idx + k, ends[person])
        dt = (self.frame[hi] - self.frame[lo]) / self.fps
        with np.errstate(invalid="ignore", divide="ignore"):
            vx = np.where(dt > 0, (self.x[hi] - self.x[lo]) / dt, np.nan)
            vy = np.where(dt > 0, (self.y[hi] - self.y[lo]) / dt, np.nan)
        return vx, vy

    def persons(self):
        return np.unique(self.id)

    def time(self):
        return self.frame / self.fps

    def crossings(self, y_line, x_range=None):
        """Time [s] each person first crosses y = y_line walking in -y (inside x_range if given)."""
        return self.crossings_axis(self.y, self.x, y_line, -1, x_range)

    def crossings_axis(self, along, across, line, direction, span=None):
        """Times [s], sorted, at which persons first cross `along` = line in `direction` (+1/-1),
        with `across` inside span (+-5 cm) if given; interpolated between frames."""
        a = along * direction
        c = line * direction
        same = self.id[1:] == self.id[:-1]
        cross = same & (a[:-1] < c) & (a[1:] >= c)
        if span is not None:
            xm = 0.5 * (across[:-1] + across[1:])
            cross &= (xm >= span[0] - 0.05) & (xm <= span[1] + 0.05)
        i = np.flatnonzero(cross)
        _, first = np.unique(self.id[i], return_index=True)
        rows = i[first]
        a0, a1 = a[rows], a[rows + 1]
        f = self.frame[rows] + (c - a0) / np.where(a0 != a1, a1 - a0, 1.0)
        return np.sort(f / self.fps)

    def area_series(self, area, frames=None):
        """Per frame in [frames]: (frame, density [1/m^2], mean speed [m/s] of those inside, NaN if none)."""
        x0, x1, y0, y1 = area
        inside = (self.x >= x0) & (self.x <= x1) & (self.y >= y0) & (self.y <= y1)
        return self.mask_series(inside, (x1 - x0) * (y1 - y0), self.speed, frames)

    def mask_series(self, inside, size, value, frames=None):
        """Per frame in [frames]: (frame, rows inside / size, mean `value` of those rows, NaN if none)."""
        f_lo, f_hi = frames if frames is not None else (self.frame.min(), self.frame.max())
        all_frames = np.arange(f_lo, f_hi + 1)
        inside = inside & (self.frame >= f_lo) & (self.frame <= f_hi) & np.isfinite(value)
        fr = self.frame[inside] - f_lo
        count = np.bincount(fr, minlength=len(all_frames)).astype(float)
        vsum = np.bincount(fr, weights=value[inside], minlength=len(all_frames))
        with np.errstate(invalid="ignore", divide="ignore"):
            vmean = np.where(count > 0, vsum / count, np.nan)
        return all_frames, count / size, vmean

    def by_frame(self, rows=None):
        """Yields (frame, row indices) for every frame (restricted to the boolean mask `rows`)."""
        sel = np.arange(len(self.id)) if rows is None else np.flatnonzero(rows)
        order = sel[np.argsort(self.frame[sel], kind="stable")]
        frames = self.frame[order]
        cuts = np.flatnonzero(np.diff(frames)) + 1
        for chunk in np.split(order, cuts):
            if len(chunk):
                yield int(self.frame[chunk[0]]), chunk


def load_text(path, scale, fps):
    rows = np.loadtxt(path, comments="#", usecols=(0, 1, 2, 3))
    rows[:, 2:4] *= scale
    return Trajectories(rows, fps)


def load_recording(path):
    """A throng recording: trajectories with each agent's body radius and population index (from
    throng_agents and throng_populations, docs/recording-format.md)."""
    db = sqlite3.connect(path)
    try:
        meta = dict(db.execute("SELECT key, value FROM metadata").fetchall())
        data = np.array(db.execute("SELECT id, frame, pos_x, pos_y, ori_x, ori_y FROM trajectory_data").fetchall(),
                        float).reshape(-1, 6)
        agents = db.execute("SELECT a.id, a.population, p.radius, p.id FROM throng_agents a "
                            "JOIN throng_populations p ON p.idx = a.population").fetchall()
    finally:
        db.close()
    radius_of = {a: r for a, _, r, _ in agents}
    population_of = {a: p for a, p, _, _ in agents}
    ratio = {pop: float(m.get("passageRatio", 1.0)) for pop, m in _model_params(meta).items()
             if m.get("name") == "avm"}
    depth_ratio_of = {a: ratio.get(pid, 1.0) for a, _, _, pid in agents}
    return Trajectories(data[:, :4], float(meta.get("fps", 10.0)), radius_of, population_of,
                        ori=(data[:, 4], data[:, 5]), depth_ratio_of=depth_ratio_of)


def _model_params(meta):
    """Population id -> its model's parameters from the metadata throng_models ({} if absent)."""
    import json
    models = json.loads(meta.get("throng_models", "{}") or "{}")
    return {pop: m for pop, m in models.items() if isinstance(m, dict)}


# --- Flow ----------------------------------------------------------------------------------------
def flow_and_gaps(times):
    """(N - 1) / (t_N - t_1) [1/s], longest and median gap between consecutive passings [s]."""
    t = np.sort(np.asarray(times, float))
    if len(t) < 2 or t[-1] <= t[0]:
        return {"passed": int(len(t)), "flow": 0.0, "longest_gap": None, "median_gap": None}
    gaps = np.diff(t)
    return {"passed": int(len(t)), "flow": float((len(t) - 1) / (t[-1] - t[0])),
            "longest_gap": float(gaps.max()), "median_gap": float(np.median(gaps))}


# --- Rings ---------------------------------------------------------------------------------------
def ring_frame(traj, centre=(0.0, 0.0)):
    """Per row: polar angle [rad, 0..2pi), radius [m] and tangential speed [m/s] (counter-clockwise > 0)."""
    dx, dy = traj.x - centre[0], traj.y - centre[1]
    theta = np.mod(np.arctan2(dy, dx), 2 * np.pi)
    rad = np.hypot(dx, dy)
    with np.errstate(invalid="ignore", divide="ignore"):
        vt = (-dy * traj.vx + dx * traj.vy) / rad
    return theta, rad, vt


def ring_measures(traj, sector, size, t_from, t_to, backward=-0.05, centre=(0.0, 0.0)):
    """Ring experiment between t_from and t_to [s]: classic density in the sector (theta0, theta1)
    [rad] of area `size` (m^2, or m for a line), mean tangential and full speed of those inside, the
    fraction of samples (every agent, every frame in the window) whose tangential speed < backward."""
    theta, _, vt = ring_frame(traj, centre)
    f0, f1 = int(np.ceil(t_from * traj.fps)), int(np.floor(t_to * traj.fps))
    inside = (theta >= sector[0]) & (theta < sector[1])
    _, rho, v_t = traj.mask_series(inside, size, vt, (f0, f1))
    _, _, v_full = traj.mask_series(inside, size, traj.speed, (f0, f1))
    window = (traj.frame >= f0) & (traj.frame <= f1) & np.isfinite(vt)
    samples = int(window.sum())
    back = int((vt[window] < backward).sum())
    return {"density": float(rho.mean()), "speed": float(np.nanmean(v_t)) if np.isfinite(v_t).any() else 0.0,
            "speed_full": float(np.nanmean(v_full)) if np.isfinite(v_full).any() else 0.0,
            "backward_fraction": back / samples if samples else 0.0, "samples": samples,
            "_series": (rho, v_t)}


# --- Bodies --------------------------------------------------------------------------------------
def max_overlap(traj, t_from=0.0):
    """Deepest overlap between two bodies [m] (0 if none) from t_from on, the time it happens and
    how many distinct agents overlap by more than 1 cm at least once."""
    best, when, deep = 0.0, None, set()
    start = int(np.ceil(t_from * traj.fps))
    for frame, rows in traj.by_frame(traj.frame >= start):
        if len(rows) < 2:
            continue
        depth = _depths(traj, rows)
        np.fill_diagonal(depth, -np.inf)
        m = float(depth.max())
        if m > best:
            best, when = m, frame / traj.fps
        i, j = np.nonzero(depth > 0.01)
        deep.update(traj.id[rows][i].tolist())
    return {"max_depth": best, "at_s": when, "agents_over_1cm": len(deep)}


def overlapping_pairs(traj, frame, deeper_than=0.05):
    """Pairs of bodies overlapping by more than `deeper_than` [m] in one frame."""
    rows = np.flatnonzero(traj.frame == frame)
    depth = _depths(traj, rows)
    return int(np.triu(depth > deeper_than, k=1).sum())


def _depths(traj, rows):
    """Overlap depth [m] of every pair of the given rows (one frame): discs, or ellipses along the
    heading where the trajectories have headings and depth ratios."""
    dx = traj.x[rows][None, :] - traj.x[rows][:, None]
    dy = traj.y[rows][None, :] - traj.y[rows][:, None]
    dist = np.hypot(dx, dy)
    reach_sum = traj.radius[rows][:, None] + traj.radius[rows][None, :]
    if traj.depth_ratio is None:
        return reach_sum - dist
    with np.errstate(invalid="ignore", divide="ignore"):
        ux = np.where(dist > 1e-9, dx / dist, 1.0)
        uy = np.where(dist > 1e-9, dy / dist, 0.0)

        def reach(ox, oy, q):
            along = ox * ux + oy * uy
            across = ox * uy - oy * ux
            den = np.sqrt(along * along + q * q * across * across)
            return np.where(den > 1e-9, reach_sum * q / den, reach_sum)

        ox, oy, q = traj.ori_x[rows], traj.ori_y[rows], traj.depth_ratio[rows]
        mine = reach(ox[:, None], oy[:, None], q[:, None])
        theirs = reach(ox[None, :], oy[None, :], q[None, :])
    return 0.5 * (mine + theirs) - dist


def walk_back(traj, target, before=None):
    """Per agent, the largest d(t) - min_{s<=t} d(s), d = distance to the segment `target`
    ((x0, y0), (x1, y1)), over the rows where `before` (a boolean mask) holds. Returns the maximum
    over agents [m], the agent and the number of agents above 0.5 m."""
    (ax, ay), (bx, by) = target
    ex, ey = bx - ax, by - ay
    u = np.clip(((traj.x - ax) * ex + (traj.y - ay) * ey) / (ex * ex + ey * ey), 0.0, 1.0)
    d = np.hypot(traj.x - (ax + u * ex), traj.y - (ay + u * ey))
    keep = np.ones(len(d), bool) if before is None else before
    best, who, over = 0.0, None, 0
    starts = np.r_[0, np.flatnonzero(np.diff(traj.id)) + 1]
    for rows in np.split(np.arange(len(d)), starts[1:]):
        rows = rows[keep[rows]]
        if len(rows) < 2:
            continue
        back = d[rows] - np.minimum.accumulate(d[rows])
        m = float(back.max())
        over += m > 0.5
        if m > best:
            best, who = m, int(traj.id[rows[0]])
    return {"max_walk_back": best, "agent": who, "agents_over_0_5m": int(over)}


# --- Lanes ---------------------------------------------------------------------------------------
def lane_order(xs, ys, labels, slice_half_width=0.3, reach=5.0):
    """Rex & Loewen's lane order parameter of one frame: for each agent, the agents within
    |dy| < slice_half_width and |dx| < reach are its lane neighbours; phi_i = ((n_same - n_opp) /
    (n_same + n_opp))^2; returns (sum of phi_i, agents with neighbours)."""
    dx = np.abs(xs[:, None] - xs[None, :])
    dy = np.abs(ys[:, None] - ys[None, :])
    near = (dx < reach) & (dy < slice_half_width)
    np.fill_diagonal(near, False)
    same = labels[:, None] == labels[None, :]
    n_same = (near & same).sum(axis=1)
    n_opp = (near & ~same).sum(axis=1)
    n = n_same + n_opp
    ok = n > 0
    phi = ((n_same[ok] - n_opp[ok]) / n[ok]) ** 2
    return float(phi.sum()), int(ok.sum())


def lane_order_series(traj, labels, region, t_from, shuffles=5, seed=1, **kw):
    """Mean lane order over the frames from t_from on, of the agents inside region (x0, x1, y0, y1),
    and the same with the direction labels shuffled among the agents of each frame (baseline)."""
    x0, x1, y0, y1 = region
    inside = (traj.x >= x0) & (traj.x <= x1) & (traj.y >= y0) & (traj.y <= y1)
    inside &= traj.frame >= int(np.ceil(t_from * traj.fps))
    rng = np.random.default_rng(seed)
    tot, cnt, tot_s, cnt_s, frames = 0.0, 0, 0.0, 0, 0
    for _, rows in traj.by_frame(inside):
        lab = labels[rows]
        if len(rows) < 4 or len(np.unique(lab)) < 2:
            continue
        frames += 1
        s, c = lane_order(traj.x[rows], traj.y[rows], lab, **kw)
        tot, cnt = tot + s, cnt + c
        for _ in range(shuffles):
            s, c = lane_order(traj.x[rows], traj.y[rows], rng.permutation(lab), **kw)
            tot_s, cnt_s = tot_s + s, cnt_s + c
    return {"lane_order": tot / cnt if cnt else None, "lane_order_shuffled": tot_s / cnt_s if cnt_s else None,
            "frames": frames}


# --- Verification (scripts/verify.py) -------------------------------------------------------------
def load_agents(path):
    """Per agent of a throng recording: population id, group id, spawn and exit time [s] (None if it
    did not exit) and the id of the exit point it left by (throng_agents, throng_events, throng_points)."""
    db = sqlite3.connect(path)
    try:
        fps = float(dict(db.execute("SELECT key, value FROM metadata").fetchall()).get("fps", 10.0))
        points = dict(db.execute("SELECT idx, id FROM throng_points").fetchall())
        exits = dict(db.execute("SELECT agent, a FROM throng_events WHERE kind = 'exit'").fetchall())
        rows = db.execute("SELECT id, population_id, group_id, spawn_frame, exit_frame FROM throng_agents").fetchall()
    finally:
        db.close()
    return {a: {"population": pop, "group": g, "spawn_s": None if s is None else s / fps,
                "exit_s": None if e is None else e / fps, "exit_point": points.get(exits.get(a))}
            for a, pop, g, s, e in rows}


def recording_models(path):
    """Population id -> the name of the avoidance model it walked with (metadata throng_models;
    empty when the recording predates it)."""
    import json
    db = sqlite3.connect(path)
    try:
        row = db.execute("SELECT value FROM metadata WHERE key = 'throng_models'").fetchone()
    finally:
        db.close()
    if not row:
        return {}
    models = json.loads(row[0])
    return {pop: (m["name"] if isinstance(m, dict) else str(m)) for pop, m in models.items()}


def inside_polygon(x, y, polygon):
    """Per point (x, y arrays), whether it lies inside the polygon (even-odd rule; points on an edge
    count as inside within 1 mm)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    inside = np.zeros(x.shape, bool)
    on_edge = np.zeros(x.shape, bool)
    n = len(polygon)
    for k in range(n):
        (ax, ay), (bx, by) = polygon[k], polygon[(k + 1) % n]
        crosses = (ay > y) != (by > y)
        with np.errstate(invalid="ignore", divide="ignore"):
            xc = ax + (y - ay) * (bx - ax) / (by - ay)
        inside ^= crosses & (x < xc)
        ex, ey = bx - ax, by - ay
        u = np.clip(((x - ax) * ex + (y - ay) * ey) / (ex * ex + ey * ey), 0.0, 1.0)
        on_edge |= np.hypot(x - (ax + u * ex), y - (ay + u * ey)) < 1e-3
    return inside | on_edge


def distance_to_edges(x, y, polygons):
    """Per point, the distance [m] to the nearest edge of any of the polygons."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    best = np.full(x.shape, np.inf)
    for poly in polygons:
        n = len(poly)
        for k in range(n):
            (ax, ay), (bx, by) = poly[k], poly[(k + 1) % n]
            ex, ey = bx - ax, by - ay
            u = np.clip(((x - ax) * ex + (y - ay) * ey) / (ex * ex + ey * ey), 0.0, 1.0)
            best = np.minimum(best, np.hypot(x - (ax + u * ex), y - (ay + u * ey)))
    return best


def steps_crossing_edges(traj, polygons):
    """How many steps (an agent's move from one recorded frame to the next) cross an edge of the
    polygons: a body centre that went through a wall between two frames."""
    same = traj.id[1:] == traj.id[:-1]
    px, py, qx, qy = traj.x[:-1][same], traj.y[:-1][same], traj.x[1:][same], traj.y[1:][same]
    count = 0
    for poly in polygons:
        n = len(poly)
        for k in range(n):
            (ax, ay), (bx, by) = poly[k], poly[(k + 1) % n]
            d1 = (bx - ax) * (py - ay) - (by - ay) * (px - ax)
            d2 = (bx - ax) * (qy - ay) - (by - ay) * (qx - ax)
            d3 = (qx - px) * (ay - py) - (qy - py) * (ax - px)
            d4 = (qx - px) * (by - py) - (qy - py) * (bx - px)
            count += int(np.sum((d1 * d2 < 0) & (d3 * d4 < 0)))
    return count


def first_moves(traj, distance=0.1):
    """Per agent, the time [s] it is first more than `distance` [m] from where it was first recorded."""
    out = {}
    starts = np.r_[0, np.flatnonzero(np.diff(traj.id)) + 1]
    for rows in np.split(np.arange(len(traj.id)), starts[1:]):
        if len(rows) == 0:
            continue
        d = np.hypot(traj.x[rows] - traj.x[rows[0]], traj.y[rows] - traj.y[rows[0]])
        moved = np.flatnonzero(d > distance)
        out[int(traj.id[rows[0]])] = float(traj.frame[rows[moved[0]]] / traj.fps) if len(moved) else None
    return out


def departures(traj, target, distance=0.5):
    """Per agent, the time [s] it is first `distance` [m] closer to the point `target` than where it
    was first recorded: when it set off towards it (a waiting person nudged aside by a passer-by does
    not count, unless the nudge is that far towards the target)."""
    tx, ty = target
    out = {}
    starts = np.r_[0, np.flatnonzero(np.diff(traj.id)) + 1]
    for rows in np.split(np.arange(len(traj.id)), starts[1:]):
        if len(rows) == 0:
            continue
        d = np.hypot(traj.x[rows] - tx, traj.y[rows] - ty)
        closer = np.flatnonzero(d < d[0] - distance)
        out[int(traj.id[rows[0]])] = float(traj.frame[rows[closer[0]]] / traj.fps) if len(closer) else None
    return out


def region_speeds(traj, x_range, statistic=np.median):
    """Per agent, the statistic (default median) of its speed [m/s] over the rows with x inside x_range."""
    sel = (traj.x >= x_range[0]) & (traj.x <= x_range[1]) & np.isfinite(traj.speed)
    out = {}
    for a in np.unique(traj.id[sel]):
        out[int(a)] = float(statistic(traj.speed[sel & (traj.id == a)]))
    return out


def group_spread(traj, group_of, t_from=0.0):
    """Per frame from t_from on, for every group with at least two members present, the largest
    distance of a member from the group's centroid [m]; returns the median and the 95th percentile
    over all (group, frame) samples."""
    start = int(np.ceil(t_from * traj.fps))
    groups = np.array([group_of[int(a)] for a in traj.id])
    spreads = []
    for _, rows in traj.by_frame(traj.frame >= start):
        g = groups[rows]
        for gid in np.unique(g):
            r = rows[g == gid]
            if len(r) < 2:
                continue
            cx, cy = traj.x[r].mean(), traj.y[r].mean()
            spreads.append(float(np.hypot(traj.x[r] - cx, traj.y[r] - cy).max()))
    if not spreads:
        return {"median": None, "p95": None, "samples": 0}
    return {"median": float(np.median(spreads)), "p95": float(np.percentile(spreads, 95)), "samples": len(spreads)}
