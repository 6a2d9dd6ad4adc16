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

    def exit(self, id, polygon=None, position=None, radius=None, width=None, height=None):
        """An exit: reaching it, an agent leaves the simulation. `width` [m]: the opening it stands for
        (exit choice's capacity estimate; populations choose among exits with exits=[...] and
        exitChoice={"rule": "quickest"}). `height` [m]: its floor's, on a multi-level world."""
        return self._point(id, "exit", position, radius, polygon, width=None if width is None else float(width),
                           height=None if height is None else float(height))

    def interest(self, id, polygon=None, position=None, radius=None, height=None):
        """A place agents pass through (a waypoint; also a lift's or escalator's stop). `height` [m]: its
        floor's, on a multi-level world."""
        return self._point(id, "interest", position, radius, polygon, height=None if height is None else float(height))

    def escalator(self, id, start, end, speed=None, headway=None):
        """An escalator from interest point `start` to interest point `end` (one way): people whose
        goals name `start` queue there, ride at `speed` [m/s] (0.5), one every `headway` [s] (0.8),
        and go on from `end` (docs/scenario-format.md, "Lifts and escalators")."""
        return self._transport(id, "escalator", [start, end], speed=speed, headway=headway)

    def elevator(self, id, stops, capacity=None, speed=None, acceleration=None, door_open_time=None,
                 door_close_time=None, transfer_time=None):
        """A lift serving interest points `stops` (2 to 64 floors, both ways): a car for `capacity` people (8) at
        `speed` [m/s] (1.0) with `acceleration` [m/s²] (1.0), doors opening and closing in
        `door_open_time` and `door_close_time` [s] (2, 3), `transfer_time` [s] per person (1.2)."""
        return self._transport(id, "elevator", list(stops), capacity=capacity, speed=speed, acceleration=acceleration,
                               doorOpenTime=door_open_time, doorCloseTime=door_close_time, transferTime=transfer_time)

    def _transport(self, id, kind, stops, **keys):
        t = {"id": str(id), "kind": kind, "stops": [str(s) for s in stops]}
        t.update({k: v for k, v in keys.items() if v is not None})
        self._doc.setdefault("transports", []).append(t)
        return self

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
