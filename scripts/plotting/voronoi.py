"""Voronoi density per grid cell for `throng plot --density voronoi` (docs/plot.md): PedPy's Voronoi
density of an area M, rho_V = sum_i |V_i & M| / |V_i| / |M|, with M each grid cell and V_i the
Voronoi cell of agent i -- the walkable ground nearer to i than to anyone else -- cut to the circle
of radius CUTOFF_M around i (PedPy's `Cutoff`: without it a lone walker's cell is the whole hall).
The cells are rasterised, as the viewer's density map does (web/viewer/src/crowd/voronoi.js): the
walkable area is sampled SAMPLES_PER_CELL x SAMPLES_PER_CELL times per grid cell (sample centres
inside the walkable area), each sample belongs to the nearest agent within the cut-off (ties: the
lower row of the frame), |V_i| is its count of samples and |V_i & M| the count of those in M. The
density is averaged over at most MAX_FRAMES recorded frames spread evenly over the recording (every
frame when it has fewer). Needs numpy only.

`throng plot --speed voronoi` draws Steffen and Seyfried's (2010) Voronoi speed on the same grid:
the speed field v(x) = v_i on V_i averaged over each cell, sum_i v_i |V_i & M| / sum_i |V_i & M| --
over the part of the cell someone's (cut) cell covers. PedPy divides by |M| instead, which reads a
cell half beyond everyone's cut-off as half the speed; where the cells cover M the two agree.
An agent without a speed in a frame (the first and last frames of its trajectory) still owns its
Voronoi cell, but that ground counts for neither sum.
"""
import numpy as np

CUTOFF_M = 2.0
SAMPLES_PER_CELL = 2
MAX_FRAMES = 200


def sample_lattice(xs, ys, per_cell=SAMPLES_PER_CELL):
    """Sample centres (sx of nx*k, sy of ny*k) for cell edges xs, ys."""
    cell = xs[1] - xs[0] if len(xs) > 1 else 1.0
    step = cell / per_cell
    nx, ny = len(xs) - 1, len(ys) - 1
    return xs[0] + (np.arange(nx * per_cell) + 0.5) * step, ys[0] + (np.arange(ny * per_cell) + 0.5) * step


def frame_owners(px, py, sx, sy, walkable, cutoff=CUTOFF_M):
    """Which agent (its index in px, py) owns each sample (len(sx), len(sy)): the nearest within
    `cutoff` (ties: the lower index), -1 for none or for samples not `walkable`."""
    step = sx[1] - sx[0] if len(sx) > 1 else 1.0
    best = np.full(walkable.shape, np.inf)
    owner = np.full(walkable.shape, -1, dtype=np.int64)
    r = int(np.ceil(cutoff / step))
    for i, (x, y) in enumerate(zip(px, py)):
        ci = int(np.floor((x - sx[0]) / step + 0.5))
        cj = int(np.floor((y - sy[0]) / step + 0.5))
        i0, i1 = max(ci - r, 0), min(ci + r + 1, len(sx))
        j0, j1 = max(cj - r, 0), min(cj + r + 1, len(sy))
        if i0 >= i1 or j0 >= j1:
            continue
        d2 = (sx[i0:i1, None] - x) ** 2 + (sy[None, j0:j1] - y) ** 2
        window = best[i0:i1, j0:j1]
        closer = (d2 < window) & (d2 <= cutoff * cutoff)
        window[closer] = d2[closer]
        owner[i0:i1, j0:j1][closer] = i
    owner[~walkable] = -1
    return owner


def _per_cell(values, per_cell):
    """Sums a (nx*k, ny*k) sample array over each grid cell: (nx, ny)."""
    nx, ny = values.shape[0] // per_cell, values.shape[1] // per_cell
    return values.reshape(nx, per_cell, ny, per_cell).sum(axis=(1, 3))


def frame_shares(px, py, sx, sy, walkable, cutoff=CUTOFF_M, per_cell=SAMPLES_PER_CELL):
    """Persons per grid cell (nx, ny) for one frame: sum_i n_i,cell / n_i over the agents at (px, py).
    `walkable`: (len(sx), len(sy)) bool mask of the samples that count."""
    owner = frame_owners(px, py, sx, sy, walkable, cutoff)
    counted = owner >= 0
    owned = np.bincount(owner[counted], minlength=len(px)).astype(float)
    share = np.zeros(walkable.shape)
    share[counted] = 1.0 / owned[owner[counted]]
    return _per_cell(share, per_cell)


def frame_speed_sums(px, py, v, sx, sy, walkable, cutoff=CUTOFF_M, per_cell=SAMPLES_PER_CELL):
    """One frame's Voronoi speed per grid cell as (covered samples, sum of their owners' speeds),
    each (nx, ny); v: the agents' speeds, NaN for one without (its samples count for neither)."""
    owner = frame_owners(px, py, sx, sy, walkable, cutoff)
    v = np.asarray(v, float)
    counted = owner >= 0
    counted[counted] = np.isfinite(v[owner[counted]])
    speed = np.zeros(walkable.shape)
    speed[counted] = v[owner[counted]]
    return _per_cell(counted.astype(float), per_cell), _per_cell(speed, per_cell)


def _lattice(xs, ys, rings, inside_walkable, per_cell):
    """The sample centres (sx, sy) and which of them are walkable."""
    sx, sy = sample_lattice(xs, ys, per_cell)
    gx, gy = np.meshgrid(sx, sy, indexing="ij")
    walkable = (inside_walkable(gx.ravel(), gy.ravel(), rings).reshape(gx.shape) if rings
                else np.ones(gx.shape, bool))
    return sx, sy, walkable


def _frames_used(traj, max_frames):
    """The recording's frames, thinned evenly to at most max_frames."""
    frames = np.unique(traj["frame"].to_numpy())
    if len(frames) > max_frames:
        frames = frames[np.linspace(0, len(frames) - 1, max_frames).round().astype(int)]
    return frames


def voronoi_density(traj, xs, ys, rings, inside_walkable, cutoff=CUTOFF_M, per_cell=SAMPLES_PER_CELL,
                    max_frames=MAX_FRAMES):
    """Mean Voronoi density per grid cell [1/m^2] (nx, ny) over the frames used, and how many were used.
    `traj`: columns frame, x, y; `inside_walkable(x, y, rings)` the walkability test (no rings: all)."""
    sx, sy, walkable = _lattice(xs, ys, rings, inside_walkable, per_cell)
    frames = _frames_used(traj, max_frames)
    cell = xs[1] - xs[0] if len(xs) > 1 else 1.0
    total = np.zeros((len(xs) - 1, len(ys) - 1))
    by_frame = traj.groupby("frame")
    for f in frames:
        rows = by_frame.get_group(f)
        total += frame_shares(rows["x"].to_numpy(), rows["y"].to_numpy(), sx, sy, walkable, cutoff, per_cell)
    return total / (max(len(frames), 1) * cell * cell), len(frames)


def voronoi_speed(traj, speeds, xs, ys, rings, inside_walkable, cutoff=CUTOFF_M, per_cell=SAMPLES_PER_CELL,
                  max_frames=MAX_FRAMES):
    """Mean Voronoi speed per grid cell [m/s] (nx, ny; NaN where no Voronoi cell with a speed ever
    lay) over the frames used (as voronoi_density), and how many were used. `traj`: columns id,
    frame, x, y (every agent, for the cells); `speeds`: columns id, frame, speed (those with one)."""
    sx, sy, walkable = _lattice(xs, ys, rings, inside_walkable, per_cell)
    frames = _frames_used(traj, max_frames)
    rows = traj[traj["frame"].isin(frames)].merge(speeds[["id", "frame", "speed"]], on=["id", "frame"], how="left")
    area = np.zeros((len(xs) - 1, len(ys) - 1))
    total = np.zeros_like(area)
    for _, r in rows.groupby("frame"):
        a, t = frame_speed_sums(r["x"].to_numpy(), r["y"].to_numpy(), r["speed"].to_numpy(), sx, sy, walkable,
                                cutoff, per_cell)
        area += a
        total += t
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(area > 0, total / area, np.nan), len(frames)
