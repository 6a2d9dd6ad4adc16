"""ScenarioBuilder: a scenario built in code (docs/python.md, docs/scenario-format.md).

Every method returns the builder, so calls chain; to_dict() gives the scenario document and
throng.scenario(builder) validates it (ScenarioError lists every problem). Polygons are lists of
(x, y) pairs in metres, or shapely Polygons where shapely is installed (the exterior ring; holes
become obstacles).
"""
import math


def _points(polygon, what):
    """[(x, y), ...] of a polygon given as pairs or as a shapely Polygon (exterior ring)."""
    exterior = getattr(polygon, "exterior", None)
    coords = list(exterior.coords) if exterior is not None else polygon
    try:
        pts = [[float(p[0]), float(p[1])] for p in coords]
    except (TypeError, IndexError, ValueError):
        raise TypeError(f"{what}: expected a polygon: a list of (x, y) pairs in metres or a shapely Polygon") from None
    for x, y in pts:
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ValueError(f"{what}: coordinates must be finite numbers, got ({x}, {y})")
    return pts


def _holes(polygon):
    return [list(r.coords) for r in getattr(polygon, "interiors", [])]


class ScenarioBuilder:
    """ScenarioBuilder(name="", seed=1, duration=300, dt=0.05): the top level of a scenario."""

    def __init__(self, name="", seed=1, duration=300.0, dt=0.05):
        self._doc = {"format": "throng/1", "name": str(name), "seed": int(seed), "duration": float(duration),
                     "dt": float(dt), "walkable": [], "obstacles": [], "points": [], "populations": []}

    def walkable(self, polygon):
        """Adds an area agents may walk on (the walkable area is the union of these)."""
        self._doc["walkable"].append(_points(polygon, "walkable"))
        for hole in _holes(polygon):
            self.obstacle(hole)
        return self

    def obstacle(self, polygon):
        """Cuts a polygon out of the walkable area."""
        self._doc["obstacles"].append(_points(polygon, "obstacle"))
        return self

    def _point(self, id, kind, position=None, radius=None, polygon=None, **extra):
        point = {"id": str(id), "kind": kind}
        if polygon is not None:
            point["polygon"] = _points(polygon, f"point '{id}'")
        elif position is not None:
            point["position"] = [float(v) for v in position]
            if radius is not None:
                point["radius"] = float(radius)
        point.update({k: v for k, v in extra.items() if v is not None})
        self._doc["points"].append(point)
        return self

    def exit(self, id, polygon=None, position=None, radius=None, width=None):
        """An exit: reaching it, an agent leaves the simulation. `width` [m]: the opening it stands for
        (exit choice's capacity estimate; populations choose among exits with exits=[...] and
        exitChoice={"rule": "quickest"})."""
        return self._point(id, "exit", position, radius, polygon, width=None if width is None else float(width))

    def interest(self, id, polygon=None, position=None, radius=None):
        """A place agents pass through (a waypoint)."""
        return self._point(id, "interest", position, radius, polygon)

    def action(self, id, position=None, radius=None, polygon=None, duration=None, action=None, orientation=None,
               stop=None):
        """A place agents stop at for `duration` seconds, playing `action`, facing `orientation`."""
        return self._point(id, "action", position, radius, polygon, duration=duration, action=action,
                           orientation=None if orientation is None else [float(v) for v in orientation], stop=stop)

    def population(self, id, goals, spawn, groups=1, size=1, speed=None, radius=None, start=None, model=None, **extra):
        """Who spawns where and walks to what. `spawn` is a polygon (or {"point": id} / {"position": [x, y]}),
        `goals` a list of point ids and waypoint choices ({"choose": [ids], "split": ..., "shares": [...]}),
        `speed` a number [m/s] or {"mean": m, "sd": s}, `model` "orca", "avm",
        "cfsm" or {"name": ..., parameter: value}; other keys of docs/scenario-format.md pass through."""
        if isinstance(goals, str):
            goals = [goals]
        pop = {"id": str(id), "groups": int(groups), "size": size if isinstance(size, (list, tuple)) else int(size),
               "goals": [g if isinstance(g, dict) else str(g) for g in goals]}
        pop["spawn"] = spawn if isinstance(spawn, dict) else {"polygon": _points(spawn, f"population '{id}' spawn")}
        for key, value in (("speed", speed), ("radius", radius), ("start", start), ("model", model)):
            if value is not None:
                pop[key] = value
        pop.update(extra)
        self._doc["populations"].append(pop)
        return self

    def set(self, key, value):
        """Sets any other top-level key (steering, social, timeline, navCellSize ...)."""
        self._doc[str(key)] = value
        return self

    def to_dict(self):
        """The scenario document (a deep copy is not made: do not change it while building)."""
        return self._doc
