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


def frame_shares(px, py, sx, sy, walkable, cutoff=CUTOFF_M, per_cell=SAMPLES_PER_CELL):
    """Persons per grid cell (nx, ny) for one frame: sum_i n_i,cell / n_i over the agents at (px, py).
    `walkable`: (len(sx), len(sy)) bool mask of the samples that count."""
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
    counted = owner >= 0
    owned = np.bincount(owner[counted], minlength=len(px)).astype(float)
    share = np.zeros(walkable.shape)
    share[counted] = 1.0 / owned[owner[counted]]
    nx, ny = walkable.shape[0] // per_cell, walkable.shape[1] // per_cell
    return share.reshape(nx, per_cell, ny, per_cell).sum(axis=(1, 3))


def voronoi_density(traj, xs, ys, rings, inside_walkable, cutoff=CUTOFF_M, per_cell=SAMPLES_PER_CELL,
                    max_frames=MAX_FRAMES):
    """Mean Voronoi density per grid cell [1/m^2] (nx, ny) over the frames used, and how many were used.
    `traj`: columns frame, x, y; `inside_walkable(x, y, rings)` the walkability test (no rings: all)."""
    sx, sy = sample_lattice(xs, ys, per_cell)
    gx, gy = np.meshgrid(sx, sy, indexing="ij")
    walkable = (inside_walkable(gx.ravel(), gy.ravel(), rings).reshape(gx.shape) if rings
                else np.ones(gx.shape, bool))
    frames = np.unique(traj["frame"].to_numpy())
    if len(frames) > max_frames:
        frames = frames[np.linspace(0, len(frames) - 1, max_frames).round().astype(int)]
    cell = xs[1] - xs[0] if len(xs) > 1 else 1.0
    total = np.zeros((len(xs) - 1, len(ys) - 1))
    by_frame = traj.groupby("frame")
    for f in frames:
        rows = by_frame.get_group(f)
        total += frame_shares(rows["x"].to_numpy(), rows["y"].to_numpy(), sx, sy, walkable, cutoff, per_cell)
    return total / (max(len(frames), 1) * cell * cell), len(frames)
