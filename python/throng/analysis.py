"""Measurements on trajectories, after PedPy's definitions (Mohcine Chraibi et al., PedPy; the
Jülich measurement methods of Zhang et al. 2011), on DataFrames with columns frame, id, x, y
(Recording.trajectory) and a frame rate fps [Hz]. Areas are polygons (lists of (x, y) in metres, or
shapely Polygons); lines are ((x0, y0), (x1, y1)).

classic_density(traj, area)                  N inside / area, per frame [1/m²]
individual_speed(traj, fps, frame_step=5)    central differences over ±frame_step frames [m/s]
mean_speed(traj, speeds, area)               mean speed of those inside, per frame [m/s]
crossings(traj, line)                        who crossed the line when, in which direction
n_t(traj, line, fps)                         cumulative crossings per frame (the N-t diagram)
flow(crossing_frames, fps, window)           crossings per second in consecutive windows [1/s]
fundamental_diagram(traj, area, fps, ...)    density and mean speed per frame, side by side
"""
import numpy as np
import pandas as pd


def _ring(area):
    """(n, 2) array of a polygon's vertices (a shapely Polygon's exterior ring)."""
    exterior = getattr(area, "exterior", None)
    pts = np.asarray(list(exterior.coords) if exterior is not None else area, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 3:
        raise ValueError("expected a polygon: at least 3 (x, y) vertices [m]")
    if np.allclose(pts[0], pts[-1]):
        pts = pts[:-1]
    return pts


def polygon_area(area):
    """Area of a simple polygon [m²] (shoelace formula)."""
    p = _ring(area)
    x, y = p[:, 0], p[:, 1]
    return float(abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))) / 2.0)


def inside(x, y, area):
    """Boolean array: which points (x[i], y[i]) lie inside the polygon (even-odd rule; a point on an
    edge may count either way, as with any floating-point test)."""
    p = _ring(area)
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    result = np.zeros(x.shape, bool)
    x0, y0 = p[:, 0], p[:, 1]
    x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
    for ax, ay, bx, by in zip(x0, y0, x1, y1):
        straddles = (ay > y) != (by > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            cross_x = ax + (y - ay) * (bx - ax) / (by - ay)
        result ^= straddles & (x < cross_x)
    return result


def _check(traj):
    missing = {"frame", "id", "x", "y"} - set(traj.columns)
    if missing:
        raise ValueError(f"trajectory is missing columns {sorted(missing)}; expected frame, id, x, y (Recording.trajectory)")


def classic_density(traj, area):
    """DataFrame indexed by frame with column density = (agents inside) / area [1/m²], for every frame
    of the trajectory (0 where nobody is inside)."""
    _check(traj)
    a = polygon_area(area)
    if a <= 0:
        raise ValueError("the measurement area has no area")
    mask = inside(traj["x"].to_numpy(), traj["y"].to_numpy(), area)
    frames = np.sort(traj["frame"].unique())
    counts = traj.loc[mask].groupby("frame").size().reindex(frames, fill_value=0)
    return pd.DataFrame({"density": counts.to_numpy() / a}, index=pd.Index(frames, name="frame"))


def individual_speed(traj, fps, frame_step=5):
    """DataFrame id, frame, speed [m/s], v_x, v_y: the displacement from frame - frame_step to
    frame + frame_step over 2 frame_step / fps seconds (frames without both neighbours are left out,
    PedPy's SpeedCalculation.BORDER_EXCLUDE)."""
    _check(traj)
    if fps <= 0 or frame_step < 1:
        raise ValueError("fps must be > 0 and frame_step >= 1")
    t = traj[["id", "frame", "x", "y"]].sort_values(["id", "frame"])
    before = t.copy()
    before["frame"] += frame_step
    after = t.copy()
    after["frame"] -= frame_step
    m = t.merge(before, on=["id", "frame"], suffixes=("", "_b")).merge(after, on=["id", "frame"], suffixes=("", "_a"))
    dt = 2.0 * frame_step / fps
    m["v_x"] = (m["x_a"] - m["x_b"]) / dt
    m["v_y"] = (m["y_a"] - m["y_b"]) / dt
    m["speed"] = np.hypot(m["v_x"], m["v_y"])
    return m[["id", "frame", "speed", "v_x", "v_y"]].reset_index(drop=True)


def mean_speed(traj, speeds, area):
    """DataFrame indexed by frame with column speed: the mean individual speed of the agents inside
    the area in that frame [m/s] (frames with nobody inside, or no speed yet, are 0, as in PedPy)."""
    _check(traj)
    mask = inside(traj["x"].to_numpy(), traj["y"].to_numpy(), area)
    frames = np.sort(traj["frame"].unique())
    m = traj.loc[mask, ["id", "frame"]].merge(speeds[["id", "frame", "speed"]], on=["id", "frame"])
    mean = m.groupby("frame")["speed"].mean().reindex(frames, fill_value=0.0)
    return pd.DataFrame({"speed": mean.to_numpy()}, index=pd.Index(frames, name="frame"))


def crossings(traj, line):
    """DataFrame id, frame, direction: each time an agent's step from one frame to the next crosses
    the segment `line` ((x0, y0), (x1, y1)); frame is the first frame on the other side, direction +1
    when it crosses to the left of the line's direction x0 → x1, -1 to the right."""
    _check(traj)
    (ax, ay), (bx, by) = line
    ex, ey = bx - ax, by - ay
    if ex == 0 and ey == 0:
        raise ValueError("the measurement line has no length")
    t = traj[["id", "frame", "x", "y"]].sort_values(["id", "frame"])
    ids = t["id"].to_numpy()
    x, y, f = t["x"].to_numpy(), t["y"].to_numpy(), t["frame"].to_numpy()
    same = ids[1:] == ids[:-1]
    side = ex * (y - ay) - ey * (x - ax)  # > 0: left of the line's direction
    s0, s1 = side[:-1], side[1:]
    changes = same & (np.sign(s0) != np.sign(s1)) & (s1 != 0)
    # Where along the line the step crosses it: within the segment?
    with np.errstate(divide="ignore", invalid="ignore"):  # steps along the line: k is not finite, not a crossing
        k = s0 / (s0 - s1)
        cx = x[:-1] + k * (x[1:] - x[:-1])
        cy = y[:-1] + k * (y[1:] - y[:-1])
        u = ((cx - ax) * ex + (cy - ay) * ey) / (ex * ex + ey * ey)
    hit = changes & (u >= 0.0) & (u <= 1.0)
    idx = np.flatnonzero(hit)
    return pd.DataFrame({"id": ids[idx + 1], "frame": f[idx + 1], "direction": np.where(s1[idx] > 0, 1, -1)})


def n_t(traj, line, fps, direction=None):
    """DataFrame indexed by frame: cumulative_pedestrians (crossings so far, optionally only those
    with the given direction +1/-1) and time [s], for every frame of the trajectory."""
    c = crossings(traj, line)
    if direction is not None:
        c = c[c["direction"] == direction]
    frames = np.sort(traj["frame"].unique())
    per_frame = c.groupby("frame").size().reindex(frames, fill_value=0)
    return pd.DataFrame({"cumulative_pedestrians": per_frame.cumsum().to_numpy(), "time": frames / float(fps)},
                        index=pd.Index(frames, name="frame"))


def flow(crossing_frames, fps, window):
    """DataFrame start, end [s], crossings, flow [1/s]: crossings counted in consecutive windows of
    `window` seconds from the first crossing's window on."""
    if window <= 0 or fps <= 0:
        raise ValueError("window and fps must be > 0")
    t = np.sort(np.asarray(crossing_frames["frame"], float)) / fps
    if len(t) == 0:
        return pd.DataFrame(columns=["start", "end", "crossings", "flow"])
    start = np.floor(t[0] / window) * window
    edges = np.arange(start, t[-1] + window + 1e-9, window)
    counts, _ = np.histogram(t, bins=edges)
    return pd.DataFrame({"start": edges[:-1], "end": edges[1:], "crossings": counts, "flow": counts / window})


def fundamental_diagram(traj, area, fps, frame_step=5):
    """DataFrame indexed by frame: density [1/m²] and speed [m/s] (classic_density and mean_speed in
    the same area), over the frames where someone is inside."""
    d = classic_density(traj, area)
    v = mean_speed(traj, individual_speed(traj, fps, frame_step), area)
    fd = d.join(v)
    return fd[fd["density"] > 0]
