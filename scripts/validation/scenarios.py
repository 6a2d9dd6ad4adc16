"""Scenario generators for scripts/validate.py (docs/validation.md describes each set-up).

Every function returns a scenario as a dict in throng's format (docs/scenario-format.md). No body
radius is written unless asked for: agents get the engine's default body. Desired speed
N(1.34, 0.26) m/s (Weidmann) everywhere.
"""
import copy
import math

SPEED = {"mean": 1.34, "sd": 0.26}
SPEED_MAX = 2.5  # the scenario format's default clip of the speed distribution [m/s]


def _arc(radius, a0, a1, n):
    return [[radius * math.cos(a0 + (a1 - a0) * i / n), radius * math.sin(a0 + (a1 - a0) * i / n)]
            for i in range(n + 1)]


def _circle(radius, n):
    return [[round(radius * math.cos(2 * math.pi * i / n), 6), round(radius * math.sin(2 * math.pi * i / n), 6)]
            for i in range(n)]


def ring_area(r_in, r_out):
    return math.pi * (r_out * r_out - r_in * r_in)


def ring(r_in, r_out, agents, duration, slabs=12, name="ring", vertices=96, pad=0.3, aim="lane"):
    """Annulus r_in..r_out around (0, 0); agents walk counter-clockwise forever: `slabs` radial
    interest points span the width, `pad` metres short of the walls (every target on the navmesh:
    targets in its eroded margin stall agents for seconds), and each of the `slabs` populations (one
    per sector between two slabs, agents spread evenly over the sectors) visits the slabs ahead of it
    in order, enough laps that nobody finishes within `duration`."""
    step = 2 * math.pi / slabs
    half = 0.2  # tangential half-thickness of a slab [m]
    points = []
    for k in range(slabs):
        a = k * step
        c, s = math.cos(a), math.sin(a)
        inner = (r_in + pad, r_out - pad)
        poly = [[r * c - t * s, r * s + t * c] for r, t in ((inner[0], -half), (inner[1], -half),
                                                            (inner[1], half), (inner[0], half))]
        points.append({"id": f"slab{k}", "kind": "interest", "aim": aim,
                       "polygon": [[round(x, 6), round(y, 6)] for x, y in poly]})
    lap = 2 * math.pi * (r_in + r_out) / 2
    laps = int(math.ceil(SPEED_MAX * duration / lap)) + 2
    pops = []
    for k in range(slabs):
        n = agents // slabs + (1 if k < agents % slabs else 0)
        if n == 0:
            continue
        a0, a1 = k * step, (k + 1) * step
        poly = _arc(r_in, a0, a1, 6) + _arc(r_out, a1, a0, 6)
        goals = [f"slab{(k + 1 + i) % slabs}" for i in range(laps * slabs)]
        pops.append({"id": f"sector{k}", "groups": n, "size": 1,
                     "spawn": {"polygon": [[round(x, 6), round(y, 6)] for x, y in poly]},
                     "goals": goals, "speed": dict(SPEED)})
    return {"format": "throng/1", "name": name, "seed": 1, "duration": duration,
            "walkable": [_circle(r_out, vertices)], "obstacles": [_circle(r_in, vertices)],
            "points": points, "populations": pops}


def in_waves(scenario, waves, every):
    """A copy where each population spawns in `waves` parts `every` seconds apart (for densities
    above what `throng check` accepts in one spawn: agents x pi r^2 / 0.5 per spawn area)."""
    if waves <= 1:
        return copy.deepcopy(scenario)
    s = copy.deepcopy(scenario)
    pops = []
    for p in scenario["populations"]:
        for w in range(waves):
            n = p["groups"] // waves + (1 if w < p["groups"] % waves else 0)
            if n:
                pops.append(dict(copy.deepcopy(p), id=f"{p['id']}-w{w}", groups=n, start=p.get("start", 0) + w * every))
    s["populations"] = pops
    return s


def bottleneck_width(base, width):
    """The 040_c_56 bottleneck (scenarios/validation/bottleneck-040-c-56.json) with another width:
    1.1 m long (y from -1.1 to 0), entrance corners chamfered 0.15 m like the original; the body
    radius key removed (engine default)."""
    s = copy.deepcopy(base)
    h = width / 2
    s["walkable"] = [[[-3.5, -2], [3.5, -2], [3.5, -1.1], [h, -1.1], [h, -0.15], [h + 0.15, 0], [2.8, 0],
                      [2.8, 6.7], [-2.8, 6.7], [-2.8, 0], [-h - 0.15, 0], [-h, -0.15], [-h, -1.1], [-3.5, -1.1]]]
    s["name"] = f"bottleneck {width:.2f} m wide, 1.1 m long, 75 persons (after 040_c_56_h-)"
    for p in s["populations"]:
        p.pop("radius", None)
    return s


ROOM_DOOR = ((10.0, 4.5), (10.0, 5.5))  # the door's segment in the room's wall
ROOM_DOOR_LINE_X = 10.1                  # measurement line, the middle of the 0.2 m thick wall


def dense_room(agents=200, duration=250):
    """10 x 10 m room, 1 m wide door (a 0.2 m thick wall) in the middle of its east wall, then a
    4 m wide, 3.8 m long corridor to the exit; agents spread over the room."""
    walk = [[0, 0], [10, 0], [10, 4.5], [10.2, 4.5], [10.2, 3], [14, 3], [14, 7], [10.2, 7], [10.2, 5.5],
            [10, 5.5], [10, 10], [0, 10]]
    return {"format": "throng/1", "name": f"dense room: {agents} agents, 10 x 10 m, 1 m door", "seed": 1,
            "duration": duration, "walkable": [walk], "obstacles": [],
            "points": [{"id": "exit", "kind": "exit", "polygon": [[13.5, 3], [14, 3], [14, 7], [13.5, 7]]}],
            "populations": [{"id": "room", "groups": agents, "size": 1,
                             "spawn": {"polygon": [[0.3, 0.3], [9.7, 0.3], [9.7, 9.7], [0.3, 9.7]]},
                             "goals": ["exit"], "speed": dict(SPEED)}]}


COUNTER_LENGTH, COUNTER_WIDTH = 30.0, 4.0
COUNTER_REGION = (5.0, 25.0, 0.0, 4.0)  # where lanes are measured (x0, x1, y0, y1)


def counter_flow(per_side=60, waves=6, every=4.0, duration=90):
    """4 m wide, 30 m long corridor; `per_side` agents walk east and as many west, entering near
    the two ends (x 1.2-4.5 m and 25.5-28.8 m) in `waves` waves `every` seconds apart; the exits are
    the last metre at each end. Population names start with the direction."""
    L, W = COUNTER_LENGTH, COUNTER_WIDTH
    pops = []
    for side, spawn, exit_id in (("east", [[1.2, 0.2], [4.5, 0.2], [4.5, W - 0.2], [1.2, W - 0.2]], "exit-east"),
                                 ("west", [[L - 4.5, 0.2], [L - 1.2, 0.2], [L - 1.2, W - 0.2], [L - 4.5, W - 0.2]],
                                  "exit-west")):
        for w in range(waves):
            n = per_side // waves + (1 if w < per_side % waves else 0)
            pops.append({"id": f"{side}-{w}", "groups": n, "size": 1, "start": w * every,
                         "spawn": {"polygon": spawn}, "goals": [exit_id], "speed": dict(SPEED)})
    return {"format": "throng/1", "name": f"counter-flow, {per_side} + {per_side} agents, 4 m corridor",
            "seed": 1, "duration": duration, "walkable": [[[0, 0], [L, 0], [L, W], [0, W]]], "obstacles": [],
            "points": [{"id": "exit-east", "kind": "exit", "polygon": [[L - 1, 0], [L, 0], [L, W], [L - 1, W]]},
                       {"id": "exit-west", "kind": "exit", "polygon": [[0, 0], [1, 0], [1, W], [0, W]]}],
            "populations": pops}


def with_model(scenario, model=None, radius=None):
    """A copy where every population walks with `model` (a name or a {"name": ...} object) and,
    if given, has body radius `radius`."""
    s = copy.deepcopy(scenario)
    for p in s.get("populations", []):
        if model is not None:
            p["model"] = copy.deepcopy(model)
        if radius is not None:
            p["radius"] = radius
    return s
