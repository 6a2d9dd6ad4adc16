"""The figures of `throng plot` (docs/plot.md), each written to a PNG with matplotlib's Agg backend:

trajectories(...)  every agent's path over the walkable area, the exits, measurement lines and area
heatmap(...)       a grid of cell values (mean density, mean speed) over the walkable area
passings(...)      cumulative passings N(t) at each measurement line and the flow in windows
fundamental(...)   density against mean speed in the measurement area, with Weidmann's curve

Each takes the matplotlib module (pyplot, with Agg already chosen) and a path, and writes the file in
one step: to PATH.tmp, then renamed, so a crash never leaves half a PNG under the final name.
"""
import os

import numpy as np

from plot_recording import parse_wkt_polygons

DPI = 110
COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"]
MAX_SEGMENTS = 2_000_000  # trajectory plot: at most this many path segments (every k-th frame beyond)


def _save(plt, fig, path):
    tmp = path + ".tmp"
    fig.savefig(tmp, format="png", dpi=DPI)
    plt.close(fig)
    os.replace(tmp, path)


def _world_figure(plt, world, extra_width=0.0):
    """A figure sized to the world's aspect ratio (at most 12 x 9 inches, at least 5 high)."""
    w, h = max(world[2] - world[0], 1e-3), max(world[3] - world[1], 1e-3)
    scale = min(10.0 / w, 7.5 / h)
    fig, ax = plt.subplots(figsize=(max(w * scale, 4.0) + 1.5 + extra_width, max(h * scale, 3.5) + 1.0))
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    return fig, ax


def draw_walkable(ax, wkt, filled=True):
    """The walkable area: filled light with its holes (obstacles) grey, or as outlines only."""
    from matplotlib.patches import Polygon
    for rings in parse_wkt_polygons(wkt) if wkt else []:
        ax.add_patch(Polygon(rings[0], closed=True, facecolor="#eeeeea" if filled else "none",
                             edgecolor="#333333", lw=1.2, zorder=0 if filled else 4))
        for hole in rings[1:]:
            ax.add_patch(Polygon(hole, closed=True, facecolor="#9a9a94" if filled else "none",
                                 edgecolor="#333333", lw=1.0, zorder=1 if filled else 4))


def draw_measurement(ax, lines, area):
    """The measurement lines (red, named) and area (blue, dashed)."""
    from matplotlib.patches import Polygon
    for m in lines:
        (x0, y0), (x1, y1) = m["line"]
        ax.plot([x0, x1], [y0, y1], color="#d62728", lw=2.2, zorder=6)
        ax.annotate(m["name"], ((x0 + x1) / 2, (y0 + y1) / 2), textcoords="offset points", xytext=(4, 4),
                    color="#d62728", fontsize=8, zorder=7)
    if area is not None:
        ax.add_patch(Polygon(area, closed=True, facecolor="none", edgecolor="#1f3fbf", lw=1.8, ls="--", zorder=6))


def _paths(traj, every):
    """Per population index: a list of (n, 2) arrays, one per agent."""
    t = traj[traj["frame"] % every == 0] if every > 1 else traj
    t = t.sort_values(["id", "frame"])
    ids = t["id"].to_numpy()
    xy = t[["x", "y"]].to_numpy()
    cuts = np.flatnonzero(ids[1:] != ids[:-1]) + 1
    return ids[np.r_[0, cuts]] if len(ids) else ids, np.split(xy, cuts) if len(ids) else []


def trajectories(plt, path, traj, wkt, world, population_of, exits, lines, area, title):
    """Every agent's path, coloured by population (legend), over the walkable area."""
    from matplotlib.collections import LineCollection
    fig, ax = _world_figure(plt, world)
    draw_walkable(ax, wkt)
    every = max(1, int(np.ceil(len(traj) / MAX_SEGMENTS)))
    ids, paths = _paths(traj, every)
    names = sorted({population_of.get(int(i), "") for i in ids})
    colour = {n: COLOURS[k % len(COLOURS)] for k, n in enumerate(names)}
    for name in names:
        segs = [p for i, p in zip(ids, paths) if population_of.get(int(i), "") == name and len(p) > 1]
        ax.add_collection(LineCollection(segs, colors=colour[name], linewidths=0.6, alpha=0.6, zorder=2,
                                         label=name or "agents"))
    for e in exits:
        ax.add_patch(_exit_patch(e))
    draw_measurement(ax, lines, area)
    ax.set_xlim(world[0] - 0.5, world[2] + 0.5)
    ax.set_ylim(world[1] - 0.5, world[3] + 0.5)
    ax.set_title(f"{title}: {len(ids)} agents")
    if 0 < len(names) <= 12:
        ax.legend(loc="upper right", fontsize=7, framealpha=0.85)
    fig.tight_layout()
    _save(plt, fig, path)


def _exit_patch(point):
    from matplotlib.patches import Circle, Polygon
    wkt = point.get("wkt")
    if isinstance(wkt, str) and wkt.strip():
        return Polygon(parse_wkt_polygons(wkt)[0][0], closed=True, facecolor="#2ca02c", alpha=0.35, zorder=3)
    return Circle((point["x"], point["y"]), max(float(point.get("radius") or 0), 0.3), facecolor="#2ca02c",
                  alpha=0.35, zorder=3)


def heatmap(plt, path, values, xs, ys, wkt, world, label, title, cmap):
    """values[i, j] for the cell xs[i]..xs[i+1], ys[j]..ys[j+1]; NaN cells are left blank."""
    fig, ax = _world_figure(plt, world, extra_width=1.0)
    mesh = ax.pcolormesh(xs, ys, np.ma.masked_invalid(values).T, cmap=cmap, shading="flat", zorder=1)
    fig.colorbar(mesh, ax=ax, label=label, shrink=0.85)
    draw_walkable(ax, wkt, filled=False)
    ax.set_xlim(world[0] - 0.5, world[2] + 0.5)
    ax.set_ylim(world[1] - 0.5, world[3] + 0.5)
    ax.set_title(title)
    fig.tight_layout()
    _save(plt, fig, path)


def passings(plt, path, series, window, title):
    """series: per line (name, n_t DataFrame, flow DataFrame): N(t) above, the windowed flow below."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    for k, (name, nt, fl) in enumerate(series):
        c = COLOURS[k % len(COLOURS)]
        top.step(nt["time"], nt["cumulative_pedestrians"], where="post", color=c, label=name)
        if len(fl):
            bottom.stairs(fl["flow"].to_numpy(), np.r_[fl["start"].to_numpy(), fl["end"].to_numpy()[-1:]],
                          color=c, label=name)
    top.set_ylabel("cumulative passings N(t)")
    bottom.set_ylabel(f"flow [1/s] ({window:g} s windows)")
    bottom.set_xlabel("time [s]")
    top.set_title(title)
    top.legend(loc="upper left", fontsize=8)
    top.grid(alpha=0.3)
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    _save(plt, fig, path)


def fundamental(plt, path, fd, weidmann, title):
    """Density against mean speed per frame (fd: DataFrame density, speed) and Weidmann's v(rho)."""
    fig, ax = plt.subplots(figsize=(7.5, 5.5))
    top = max(2.0, float(fd["density"].max()) * 1.15 if len(fd) else 2.0)
    rho = np.linspace(0.05, top, 200)
    ax.plot(rho, weidmann(rho), color="#444444", lw=1.5, label="Weidmann (1993)")
    ax.scatter(fd["density"], fd["speed"], s=10, alpha=0.55, color="#1f77b4", label=f"measured ({len(fd)} frames)")
    ax.set_xlim(0, top)
    ax.set_ylim(0, max(1.6, float(fd["speed"].max()) * 1.1 if len(fd) else 1.6))
    ax.set_xlabel("classic density [1/m²]")
    ax.set_ylabel("mean speed [m/s]")
    ax.set_title(title)
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    _save(plt, fig, path)
