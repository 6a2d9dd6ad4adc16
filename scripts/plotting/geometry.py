"""Geometry for `throng plot` (docs/plot.md): the walkable area's rings, the default measurement line
in front of each exit and the default measurement area behind it, the grid of heatmap cells.

walkable_rings(wkt)                  every ring (outer and holes) of the walkable area's WKT
inside_walkable(x, y, rings)         even-odd test over all rings (holes excluded)
exit_lines(points, rings, starts)    one default line per exit: 1 m in front of it, across the walkable area
area_in_front(line, rings)           the default measurement area: 2 m deep, upstream of the line
scenario_measurements(scenario)      the scenario's own measurement lines and first area (the defaults when given)
check_line(line, bounds) / check_area(...)   ValueError for a line or area that cannot measure anything
grid(bounds, cell)                   the heatmap's cell edges
"""
import numpy as np

from plot_recording import parse_wkt_polygons  # scripts/plot_recording.py: the WKT reader
from throng_analysis import inside  # python/throng/analysis.py (scripts/plot.py loads it by path)

LINE_OFFSET_M = 1.0  # how far in front of an exit the default line lies [m]: agents vanish on reaching the exit,
#                      often before a recorded frame shows them inside it, so a line on its edge misses some
AREA_DEPTH_M = 2.0   # depth of the default measurement area upstream of the line [m]
AREA_MIN_WIDTH_M = 2.0


def walkable_rings(wkt):
    """Every ring of the walkable area as an (n, 2) array: outer boundaries and holes alike."""
    if not wkt:
        return []
    return [np.asarray(ring, float) for polygon in parse_wkt_polygons(wkt) for ring in polygon if len(ring) >= 3]


def bounds(rings, traj=None):
    """(xmin, ymin, xmax, ymax) of the rings, else of the trajectory, else a unit square."""
    if rings:
        pts = np.vstack(rings)
    elif traj is not None and len(traj):
        pts = traj[["x", "y"]].to_numpy()
    else:
        return (0.0, 0.0, 1.0, 1.0)
    return (float(pts[:, 0].min()), float(pts[:, 1].min()), float(pts[:, 0].max()), float(pts[:, 1].max()))


def inside_walkable(x, y, rings):
    """Which points lie in the walkable area (even-odd over every ring: holes are outside)."""
    x = np.asarray(x, float)
    result = np.zeros(x.shape, bool)
    for ring in rings:
        result ^= inside(x, y, ring)
    return result


def _edges(rings):
    for ring in rings:
        closed = ring if np.allclose(ring[0], ring[-1]) else np.vstack([ring, ring[:1]])
        for a, b in zip(closed[:-1], closed[1:]):
            yield a, b


def _distance_to_boundary(p, rings):
    best = np.inf
    for a, b in _edges(rings):
        d = b - a
        t = np.clip(np.dot(p - a, d) / max(np.dot(d, d), 1e-12), 0.0, 1.0)
        best = min(best, float(np.hypot(*(a + t * d - p))))
    return best


def clip_to_walkable(base, direction, rings):
    """The stretch of the infinite line base + t·direction that lies in the walkable area and holds
    base: ((x0, y0), (x1, y1)), or None when base is not in the walkable area."""
    if not inside_walkable([base[0]], [base[1]], rings)[0]:
        return None
    ts = []
    for a, b in _edges(rings):
        e = b - a
        denom = direction[0] * e[1] - direction[1] * e[0]
        if abs(denom) < 1e-12:
            continue
        w = a - base
        t = (w[0] * e[1] - w[1] * e[0]) / denom
        s = (w[0] * direction[1] - w[1] * direction[0]) / denom
        if -1e-9 <= s <= 1 + 1e-9:
            ts.append(t)
    below = [t for t in ts if t < 0]
    above = [t for t in ts if t > 0]
    if not below or not above:
        return None
    lo, hi = max(below), min(above)
    p0, p1 = base + lo * direction, base + hi * direction
    return ((float(p0[0]), float(p0[1])), (float(p1[0]), float(p1[1])))


def _exit_edge(ring, rings):
    """The exit polygon's longest edge that is not on the walkable boundary (where agents walk in), with
    the unit normal pointing into the exit."""
    centre = ring[:-1].mean(axis=0) if np.allclose(ring[0], ring[-1]) else ring.mean(axis=0)
    best = None
    for a, b in _edges([ring]):
        length = float(np.hypot(*(b - a)))
        free = _distance_to_boundary((a + b) / 2, rings) > 1e-6
        if length > 0 and (best is None or (free, length) > (best[0], best[1])):
            best = (free, length, a, b)
    _, length, a, b = best
    along = (b - a) / length
    normal = np.array([-along[1], along[0]])
    if np.dot(centre - (a + b) / 2, normal) < 0:
        normal = -normal
    return (a + b) / 2, along, normal, length


def _exit_frame(point, rings, start):
    """(middle of the exit's entrance, direction along it, normal into the exit, width) of one exit."""
    wkt = point.get("wkt")
    if isinstance(wkt, str) and wkt.strip():
        ring = np.asarray(parse_wkt_polygons(wkt)[0][0], float)
        return _exit_edge(ring, rings)
    centre = np.array([point["x"], point["y"]], float)
    radius = float(point.get("radius") or 0.0)
    normal = centre - start
    n = float(np.hypot(*normal))
    normal = normal / n if n > 1e-9 else np.array([1.0, 0.0])
    return centre - radius * normal, np.array([-normal[1], normal[0]]), normal, max(2.0 * radius, 1.0)


def exit_lines(points, rings, start):
    """One default measurement line per exit (points: dicts of throng_points rows of kind exit; start: the
    agents' mean first position, which says where a point exit is approached from). Each line lies
    LINE_OFFSET_M in front of the exit's entrance (on it when that spot is not walkable), parallel to it and
    across the whole walkable area there. A list of dicts: name, line ((x0, y0), (x1, y1)), normal (into the
    exit: crossings that way are passings toward it), entrance (its middle) and width [m]."""
    lines = []
    for p in points:
        middle, along, normal, width = _exit_frame(p, rings, np.asarray(start, float))
        for offset in (LINE_OFFSET_M, 0.05, 0.0):
            seg = clip_to_walkable(middle - offset * normal, along, rings)
            if seg is not None:
                break
        if seg is None:
            half = along * width / 2
            seg = (tuple(middle - half), tuple(middle + half))
        lines.append({"name": str(p["id"]), "line": seg, "normal": normal, "entrance": middle, "width": width})
    return lines


def area_in_front(exit_line, rings):
    """The default measurement area: a rectangle AREA_DEPTH_M deep upstream of the exit's line, as wide as the
    exit's entrance (at least AREA_MIN_WIDTH_M), centred on it; None when its centre is not walkable."""
    (x0, y0), (x1, y1) = exit_line["line"]
    a, b = np.array([x0, y0]), np.array([x1, y1])
    along = (b - a) / np.hypot(*(b - a))
    normal = np.asarray(exit_line["normal"], float)
    # The entrance's middle projected onto the line.
    foot = a + np.dot(np.asarray(exit_line["entrance"], float) - a, along) * along
    half = along * max(exit_line["width"], AREA_MIN_WIDTH_M) / 2
    back = -normal * AREA_DEPTH_M
    corners = [foot - half, foot + half, foot + half + back, foot - half + back]
    centre = foot + back / 2
    if not inside_walkable([centre[0]], [centre[1]], rings)[0]:
        return None
    return [(float(c[0]), float(c[1])) for c in corners]


def scenario_measurements(scenario):
    """The scenario's own "measurements" (docs/scenario-format.md): its lines, named by id, passings counted
    both ways, and its first area's corners (None when it has none). The loader checked them."""
    lines, area = [], None
    for m in (scenario or {}).get("measurements", []):
        if "line" in m:
            (x0, y0), (x1, y1) = m["line"]
            lines.append({"name": m["id"], "line": ((float(x0), float(y0)), (float(x1), float(y1))), "normal": None})
        elif "polygon" in m and area is None:
            area = [(float(x), float(y)) for x, y in m["polygon"]]
    return lines, area


def rectangle(spec):
    """x0, y0, x1, y1 -> the rectangle's four corners."""
    x0, y0, x1, y1 = spec
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


def _overlaps(box, world, margin=0.0):
    return not (box[2] < world[0] - margin or box[0] > world[2] + margin or
                box[3] < world[1] - margin or box[1] > world[3] + margin)


def check_line(spec, world):
    """ValueError unless the line x0, y0, x1, y1 has a length and reaches into the world's bounds."""
    x0, y0, x1, y1 = spec
    if np.hypot(x1 - x0, y1 - y0) <= 1e-9:
        raise ValueError(f"--line {x0:g},{y0:g},{x1:g},{y1:g} has no length; expected two different end points")
    if not _overlaps((min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1)), world):
        raise ValueError(f"--line {x0:g},{y0:g},{x1:g},{y1:g} lies outside the walkable area "
                         f"(x {world[0]:g}..{world[2]:g}, y {world[1]:g}..{world[3]:g} m)")
    return ((x0, y0), (x1, y1))


def check_area(spec, world):
    """ValueError unless the rectangle x0, y0, x1, y1 has an area and overlaps the world's bounds."""
    x0, y0, x1, y1 = spec
    if abs(x1 - x0) <= 1e-9 or abs(y1 - y0) <= 1e-9:
        raise ValueError(f"--area {x0:g},{y0:g},{x1:g},{y1:g} has no area; expected two opposite corners of a rectangle")
    if not _overlaps((min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1)), world):
        raise ValueError(f"--area {x0:g},{y0:g},{x1:g},{y1:g} lies outside the walkable area "
                         f"(x {world[0]:g}..{world[2]:g}, y {world[1]:g}..{world[3]:g} m)")
    return rectangle((x0, y0, x1, y1))


def grid(world, cell):
    """Cell edges (xs, ys) covering the world's bounds with square cells of `cell` metres."""
    nx = max(1, int(np.ceil((world[2] - world[0]) / cell)))
    ny = max(1, int(np.ceil((world[3] - world[1]) / cell)))
    return world[0] + cell * np.arange(nx + 1), world[1] + cell * np.arange(ny + 1)
