#!/usr/bin/python3
"""Draws a throng (or JuPedSim v2) recording: walkable area, points, and every agent's trajectory.

usage: scripts/plot_recording.py RECORDING.sqlite [--out FILE.png] [--title TEXT] [--every N]

Needs Debian's python3-matplotlib (run with /usr/bin/python3). Trajectories are coloured by
population when the recording has throng's tables, else by agent.
"""
import argparse
import re
import sqlite3
import sys


def parse_wkt_polygons(wkt):
    """POLYGON((...),(...)) or MULTIPOLYGON(((...)),((...))) -> list of polygons, each a list of rings."""
    wkt = wkt.strip()
    polys = []
    body = wkt[wkt.index("("):]
    # Split into polygons at ')),((' boundaries for multipolygons.
    if wkt.upper().startswith("MULTIPOLYGON"):
        parts = re.split(r"\)\)\s*,\s*\(\(", body.strip()[2:-2])
    else:
        parts = [body.strip()[1:-1].strip()[1:-1]]
    for part in parts:
        rings = []
        for ring in re.split(r"\)\s*,\s*\(", part):
            pts = []
            for pair in ring.strip("() ").split(","):
                xy = pair.split()
                if len(xy) >= 2:
                    pts.append((float(xy[0]), float(xy[1])))
            rings.append(pts)
        polys.append(rings)
    return polys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("recording")
    ap.add_argument("--out", default=None, help="PNG to write (default: RECORDING.png)")
    ap.add_argument("--title", default=None)
    ap.add_argument("--every", type=int, default=1, help="use every N-th frame (default 1)")
    args = ap.parse_args()
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.patches import Polygon as MplPolygon
    except ImportError:
        sys.exit("plot_recording.py: matplotlib is missing; expected Debian's python3-matplotlib (run with /usr/bin/python3)")
    try:
        db = sqlite3.connect(f"file:{args.recording}?mode=ro", uri=True)
        rows = db.execute("SELECT frame, id, pos_x, pos_y FROM trajectory_data ORDER BY id, frame").fetchall()
    except sqlite3.Error as e:
        sys.exit(f"{args.recording}: {e}; expected a throng or JuPedSim recording")
    tables = {r[0] for r in db.execute("SELECT name FROM sqlite_master WHERE type='table'")}
    population = {}
    if "throng_agents" in tables:
        # Colour by population family: "commuters-wave3" and "commuters-wave4" share a colour.
        population = {aid: re.sub(r"[-_ ]?[A-Za-z]*\d+$", "", pid or "") or pid
                      for aid, pid in db.execute("SELECT id, population_id FROM throng_agents").fetchall()}
    name = args.title
    if name is None:
        meta = dict(db.execute("SELECT key, value FROM metadata").fetchall())
        name = meta.get("throng_scenario_name") or meta.get("name") or args.recording

    fig, ax = plt.subplots(figsize=(10, 7), dpi=100)
    for (wkt,) in db.execute("SELECT wkt FROM geometry"):
        for rings in parse_wkt_polygons(wkt):
            ax.add_patch(MplPolygon(rings[0], closed=True, facecolor="#eeeeea", edgecolor="#333333", lw=1.2, zorder=0))
            for hole in rings[1:]:
                ax.add_patch(MplPolygon(hole, closed=True, facecolor="#9a9a94", edgecolor="#333333", lw=1.0, zorder=1))
    colours = plt.get_cmap("tab10")
    pop_index = {p: i for i, p in enumerate(sorted({v for v in population.values() if v}))}
    track = {}
    last_frame = max((r[0] for r in rows), default=0)
    present = {aid for frame, aid, x, y in rows if frame == last_frame}
    for frame, aid, x, y in rows:
        if frame % args.every == 0:
            track.setdefault(aid, ([], []))
            track[aid][0].append(x)
            track[aid][1].append(y)
    labelled = set()
    for aid, (xs, ys) in track.items():
        pop = population.get(aid)
        c = colours(pop_index.get(pop, aid) % 10)
        label = pop if pop and pop not in labelled else None
        labelled.add(pop)
        ax.plot(xs, ys, lw=0.6, alpha=0.55, color=c, label=label, zorder=2)
        if aid in present:  # where the agents still in the world stand at the end
            ax.plot(xs[-1:], ys[-1:], "o", ms=2.0, color=c, zorder=3)
    if "throng_points" in tables:
        for pid, kind, x, y in db.execute("SELECT id, kind, x, y FROM throng_points"):
            marker = {"exit": "s", "action": "*", "interest": "^"}.get(kind, "o")
            ax.plot([x], [y], marker, color="black", ms=7, zorder=4)
            ax.annotate(pid, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7, zorder=5)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{name}: {len(track)} agents")
    if 0 < len(pop_index) <= 10:
        ax.legend(loc="upper right", fontsize=7, framealpha=0.85)
    out = args.out or (args.recording.rsplit(".", 1)[0] + ".png")
    fig.tight_layout()
    fig.savefig(out)
    print(out)


if __name__ == "__main__":
    main()
