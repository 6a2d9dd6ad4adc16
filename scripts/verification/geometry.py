"""Geometry of the verification tests (scripts/verify.py): the scenarios' shared numbers (corridor
lengths, door positions, measurement lines and areas) and the builders that write
verification/<suite>/*.json (scripts/verification/make_scenarios.py). The measurement code reads
the same constants, so a scenario and the check of it cannot drift apart.

Everything is throng's scenario format (docs/scenario-format.md); no body radius or model is set,
so every test runs with the engine's defaults unless `--model` overrides them.
"""
import math

FLAT_SPEED = 1.33            # RiMEA 1's walking speed [m/s]
SPEED = {"mean": 1.34, "sd": 0.26}  # Weidmann (1993), where a test sets no speed

# --- RiMEA 1 / NIST 2.1: a straight corridor --------------------------------------------------------
CORRIDOR = {"length": 43.0, "width": 2.0, "start_x": 2.0, "end_x": 42.0}   # measured between x 2 and 42


def rect(x0, y0, x1, y1):
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


def scenario(name, walkable, points, populations, duration, obstacles=None, **extra):
    s = {"format": "throng/1", "name": name, "seed": 1, "duration": duration, "walkable": walkable}
    if obstacles:
        s["obstacles"] = obstacles
    s["points"] = points
    s["populations"] = populations
    s.update(extra)
    return s


def exit_point(pid, polygon, **kw):
    return dict({"id": pid, "kind": "exit", "polygon": polygon}, **kw)


def population(pid, groups, spawn, goals, speed=None, **kw):
    p = {"id": pid, "groups": groups, "size": 1, "spawn": spawn, "goals": goals}
    if speed is not None:
        p["speed"] = speed
    p.update(kw)
    return p


def corridor(name, speed):
    c = CORRIDOR
    return scenario(name, [rect(0, 0, c["length"], c["width"])],
                    [exit_point("end", rect(c["length"] - 0.5, 0, c["length"], c["width"]))],
                    [population("walker", 1, {"position": [0.6, c["width"] / 2]}, ["end"], speed)], 80)


# --- RiMEA 2, 3, 13 / NIST 2.2, 2.3: stairs ----------------------------------------------------------
# A flight of STEPS steps (tread x riser) between two landings, as one walkable quad per step top.
STAIR = {"steps": 30, "tread": 0.29, "riser": 0.17, "foot_x": 5.0, "landing": 5.0}
STAIR_WEIDMANN = {"up": 0.610, "down": 0.694}   # horizontal speed on stairs, Weidmann (1993) [m/s]


def stair_top_x():
    return STAIR["foot_x"] + STAIR["steps"] * STAIR["tread"]


def stair_height():
    return STAIR["steps"] * STAIR["riser"]


def stair_length():
    """Length along the slope of the flight [m]."""
    return math.hypot(stair_top_x() - STAIR["foot_x"], stair_height())


def _quad(verts, tris, corners):
    base = len(verts)
    verts.extend(corners)
    tris.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]])


def stair_terrain(width, lower_from=0.0):
    """Lower landing x lower_from..foot, the flight, the upper landing; y 0..width."""
    verts, tris = [], []
    s, foot, top, h = STAIR, STAIR["foot_x"], stair_top_x(), stair_height()
    _quad(verts, tris, [[lower_from, 0, 0], [foot, 0, 0], [foot, width, 0], [lower_from, width, 0]])
    for k in range(s["steps"]):
        x0, x1, z = foot + k * s["tread"], foot + (k + 1) * s["tread"], round((k + 1) * s["riser"], 6)
        x0, x1 = round(x0, 6), round(x1, 6)
        _quad(verts, tris, [[x0, 0, z], [x1, 0, z], [x1, width, z], [x0, width, z]])
    top_end = round(top + s["landing"], 6)
    _quad(verts, tris, [[round(top, 6), 0, h], [top_end, 0, h], [top_end, width, h], [round(top, 6), width, h]])
    return {"vertices": verts, "walkable": tris, "obstacles": []}, top_end


def stairs(name, up):
    terrain, top_end = stair_terrain(2.0)
    h = round(stair_height(), 6)
    low = ([0.5, 1.0, 0.0], rect(0, 0, 0.6, 2.0), 0.0)
    high = ([top_end - 0.5, 1.0, h], rect(top_end - 0.6, 0, top_end, 2.0), h)
    start, goal = (low, high) if up else (high, low)
    return scenario(name, [], [exit_point("end", goal[1], height=goal[2])],
                    [population("walker", 1, {"position": start[0]}, ["end"], FLAT_SPEED)], 80, terrain=terrain)


# NIST 2.4: one sloped quad 10 m long along its slope between two 5 m landings, 2 m wide. A gentle
# ramp (1:12, the steepest most building codes allow) is level ground to throng; a steep one (20°,
# above nav::NavMeshConfig::stairSlopeDeg = 15°) is walked at the population's "stairs" factors.
RAMP = {"length": 10.0, "width": 2.0, "foot_x": 5.0, "landing": 5.0, "speed": 1.0,
        "gentle": math.degrees(math.atan(1 / 12)), "steep": 20.0, "steep_factors": {"up": 0.8, "down": 0.9}}


def ramp_top_x(slope_deg):
    return RAMP["foot_x"] + RAMP["length"] * math.cos(math.radians(slope_deg))


def ramp(name, up, slope_deg, factors=None):
    r = RAMP
    w, foot, top = r["width"], r["foot_x"], round(ramp_top_x(slope_deg), 6)
    h = round(r["length"] * math.sin(math.radians(slope_deg)), 6)
    end = round(top + r["landing"], 6)
    verts, tris = [], []
    _quad(verts, tris, [[0, 0, 0], [foot, 0, 0], [foot, w, 0], [0, w, 0]])
    _quad(verts, tris, [[foot, 0, 0], [top, 0, h], [top, w, h], [foot, w, 0]])
    _quad(verts, tris, [[top, 0, h], [end, 0, h], [end, w, h], [top, w, h]])
    low = ([0.5, w / 2, 0.0], rect(0, 0, 0.6, w), 0.0)
    high = ([end - 0.5, w / 2, h], rect(end - 0.6, 0, end, w), h)
    start, goal = (low, high) if up else (high, low)
    extra = {} if factors is None else {"stairs": factors}
    return scenario(name, [], [exit_point("end", goal[1], height=goal[2])],
                    [population("walker", 1, {"position": start[0]}, ["end"], r["speed"], **extra)], 80,
                    terrain={"vertices": verts, "walkable": tris, "obstacles": []})


# RiMEA 13: a 10 x 10 m room, its crowd entering a 2 m corridor (the bottleneck) that ends at the foot of
# a flight up as wide as itself; the exit lies on the upper landing.
STAIR_JAM = {"width": 2.0, "corridor": 12.0, "room": 10.0, "agents": 250}


def stair_jam(name):
    """RiMEA 13: room -> 12 m corridor -> 2 m wide flight up (the steps of test 2) -> exit."""
    j = STAIR_JAM
    w, foot = j["width"], STAIR["foot_x"]
    terrain, top_end = stair_terrain(w, lower_from=foot - j["corridor"])
    x1 = foot - j["corridor"]
    x0, yc = x1 - j["room"], w / 2
    _quad(terrain["vertices"], terrain["walkable"],
          [[x0, yc - j["room"] / 2, 0], [x1, yc - j["room"] / 2, 0], [x1, yc + j["room"] / 2, 0], [x0, yc + j["room"] / 2, 0]])
    h = round(stair_height(), 6)
    spawn = rect(x0 + 0.3, yc - j["room"] / 2 + 0.3, x1 - 0.5, yc + j["room"] / 2 - 0.3)
    return scenario(name, [], [exit_point("up", rect(top_end - 0.6, 0, top_end, w), height=h)],
                    [population("crowd", j["agents"], {"polygon": spawn}, ["up"], SPEED)], 300, terrain=terrain)


# --- RiMEA 5 / NIST 1.1: pre-movement times ---------------------------------------------------------
PREMOVEMENT = {"room": (8.0, 5.0), "times": [10.0 + 10.0 * k for k in range(10)]}


def premovement(name):
    """Ten persons at fixed places in an 8 x 5 m room with a 1 m door, all present from t = 0; person k
    leaves at 10 + 10k s (uniform over 10..100 s): ten populations, each with a pre-movement time of
    exactly that (a uniform distribution from t to t), so the measurement knows each one's time."""
    w, h = PREMOVEMENT["room"]
    walk = [[0, 0], [w, 0], [w, 2.0], [w + 2, 2.0], [w + 2, 3.0], [w, 3.0], [w, h], [0, h]]
    pops = []
    for k, t in enumerate(PREMOVEMENT["times"]):
        x, y = 1.0 + 1.5 * (k % 5), 1.5 if k < 5 else 3.5
        pops.append(population(f"person{k}", 1, {"position": [x, y]}, ["door"], FLAT_SPEED,
                               preMovement={"distribution": "uniform", "min": t, "max": t}))
    return scenario(name, [walk], [exit_point("door", rect(w + 1.5, 2.0, w + 2, 3.0))], pops, 160)


# --- RiMEA 6 and 15: round a left corner -------------------------------------------------------------
def corner_walls(width, leg):
    """L-shaped corridor: east along y 0..width up to x = leg, then north along x leg-width..leg up to
    y = leg. The inner corner is (leg - width, width)."""
    return [[0, 0], [leg, 0], [leg, leg], [leg - width, leg], [leg - width, width], [0, width]]


CORNER_SMALL = {"width": 2.0, "leg": 12.0, "agents": 20}
CORNER_LARGE = {"width": 5.0, "leg": 40.0, "agents": 500}


def corner(name, geo, spawn_len):
    w, leg = geo["width"], geo["leg"]
    return scenario(name, [corner_walls(w, leg)], [exit_point("end", rect(leg - w, leg - 0.5, leg, leg))],
                    [population("crowd", geo["agents"], {"polygon": rect(0.3, 0.3, spawn_len, w - 0.3)}, ["end"],
                                SPEED)], 900)


# --- RiMEA 7 / NIST 2.10: speed groups ---------------------------------------------------------------
# Walking speed ranges on the flat per group (Weidmann 1993, as tabulated for RiMEA 7) [m/s].
SPEED_GROUPS = [("under-30", 0.58, 1.61, 15), ("30-to-50", 1.41, 1.54, 15), ("over-50", 0.68, 1.41, 15),
                ("impaired", 0.46, 0.76, 5)]
# "wide": the same 50 in one end of a hall 200 m wide whose whole far wall is the exit (a wide goal area:
# the spot each aims at inside it must lie near straight ahead, not along the strip).
DEMOGRAPHICS = {"length": 60.0, "width": 10.0, "wide": 200.0, "spawn_to": 12.0, "measure": (20.0, 50.0)}


def demographics(name, width=None):
    d = DEMOGRAPHICS
    hall = d["width"] if width is None else width
    pops = [population(gid, n, {"polygon": rect(0.3, 0.3, d["spawn_to"], d["width"] - 0.3)}, ["end"],
                       {"mean": round((lo + hi) / 2, 3), "sd": round((hi - lo) / 4, 3), "min": lo, "max": hi})
            for gid, lo, hi, n in SPEED_GROUPS]
    return scenario(name, [rect(0, 0, d["length"], hall)],
                    [exit_point("end", rect(d["length"] - 0.5, 0, d["length"], hall))], pops, 150)


# --- RiMEA 8: parameter analysis (desired speed) ------------------------------------------------------
SENSITIVITY_SPEEDS = [0.8, 1.0, 1.2, 1.4, 1.6]


def office_floor(name):
    """An office floor: six 5 x 5 m rooms (10 persons each) off a 2 m corridor, one 1 m door each,
    a 1.2 m exit at the corridor's east end."""
    walk = [rect(0, 5.2, 31.2, 7.2)]
    for k in range(3):
        x0 = 0.2 + 5.2 * k
        walk.append(rect(x0, 0, x0 + 5, 5))            # south rooms
        walk.append(rect(x0 + 2, 5, x0 + 3, 5.2))      # their doors
        walk.append(rect(x0, 7.4, x0 + 5, 12.4))       # north rooms
        walk.append(rect(x0 + 2, 7.2, x0 + 3, 7.4))
    walk.append(rect(31.2, 5.6, 33.2, 6.8))
    pops = []
    for k in range(3):
        x0 = 0.2 + 5.2 * k
        pops.append(population(f"south{k}", 10, {"polygon": rect(x0 + 0.3, 0.3, x0 + 4.7, 4.7)}, ["exit"], SPEED))
        pops.append(population(f"north{k}", 10, {"polygon": rect(x0 + 0.3, 7.7, x0 + 4.7, 12.1)}, ["exit"], SPEED))
    return scenario(name, walk, [exit_point("exit", rect(32.6, 5.6, 33.2, 6.8))], pops, 300)


# --- RiMEA 9: a large room, four doors ---------------------------------------------------------------
HALL = {"w": 30.0, "h": 20.0, "doors": {"west-south": ("w", 4.0), "west-north": ("w", 16.0),
                                           "east-south": ("e", 4.0), "east-north": ("e", 16.0)}, "agents": 1000}


def hall(name, closed):
    """30 x 20 m hall, four 1 m doors (two in each short wall, centred 4 m from the corners), an exit
    area 1 m beyond each open door. throng has no exit choice yet, so each quarter of the hall (250
    persons) heads for its nearest open door."""
    w, h = HALL["w"], HALL["h"]
    walk, points = [rect(0, 0, w, h)], []
    for did, (side, y) in HALL["doors"].items():
        if did in closed:
            continue
        x0, x1 = (-1.2, 0) if side == "w" else (w, w + 1.2)
        walk.append(rect(x0, y - 0.5, x1, y + 0.5))
        ex0, ex1 = (-1.2, -0.7) if side == "w" else (w + 0.7, w + 1.2)
        points.append(exit_point(did, rect(ex0, y - 0.5, ex1, y + 0.5)))
    open_doors = [d for d in HALL["doors"] if d not in closed]
    pops = []
    for qid, (qx, qy) in {"sw": (0, 0), "nw": (0, 1), "se": (1, 0), "ne": (1, 1)}.items():
        cx, cy = (qx + 0.5) * w / 2, (qy + 0.5) * h / 2

        def dist(d):
            side, y = HALL["doors"][d]
            return math.hypot(cx - (0 if side == "w" else w), cy - y)
        goal = min(open_doors, key=dist)
        x0, y0 = qx * w / 2, qy * h / 2
        pops.append(population(qid, HALL["agents"] // 4, {"polygon": rect(x0 + 0.5, y0 + 0.5, x0 + w / 2 - 0.5,
                                                                          y0 + h / 2 - 0.5)}, [goal], SPEED))
    return scenario(name, walk, points, pops, 1800)


# --- RiMEA 10 / NIST 3.1: assigned exits -------------------------------------------------------------
ROOMS = {"count": 12, "size": 4.0, "corridor": (3.0, 2.0)}  # corridor: y from, width
# Persons per room and the exit each room is assigned (west, east); rooms 0-5 south, 6-11 north.
ROOM_ASSIGNMENT = [(8, "west"), (5, "east"), (6, "west"), (8, "east"), (5, "west"), (7, "east"),
                   (6, "east"), (8, "west"), (5, "east"), (7, "west"), (6, "east"), (5, "west")]


def assigned_exits(name):
    n, s = ROOMS["count"] // 2, ROOMS["size"]
    cy, cw = ROOMS["corridor"]
    length = n * (s + 0.2) + 0.2
    walk = [rect(-2.0, cy, length + 2.0, cy + cw)]
    pops = []
    for k in range(ROOMS["count"]):
        col, north = k % n, k >= n
        x0 = 0.2 + col * (s + 0.2)
        y0 = cy + cw + 0.2 if north else cy - 0.2 - s
        walk.append(rect(x0, y0, x0 + s, y0 + s))
        walk.append(rect(x0 + 1.5, cy + cw, x0 + 2.5, cy + cw + 0.2) if north else rect(x0 + 1.5, cy - 0.2, x0 + 2.5, cy))
        count, goal = ROOM_ASSIGNMENT[k]
        pops.append(population(f"room{k}", count, {"polygon": rect(x0 + 0.3, y0 + 0.3, x0 + s - 0.3, y0 + s - 0.3)},
                               [goal], SPEED))
    points = [exit_point("west", rect(-2.0, cy, -1.5, cy + cw)),
              exit_point("east", rect(length + 1.5, cy, length + 2.0, cy + cw))]
    return scenario(name, walk, points, pops, 300)


# --- RiMEA 11: two exits, which one is used -----------------------------------------------------------
CHOICE = {"w": 20.0, "h": 10.0, "doors": {"near": 2.0, "far": 8.0}, "agents": 300, "spawn": (5.0, 0.3, 19.7, 6.0),
          "close_at": 15.0}


def exit_choice(name):
    """A 20 x 10 m room with two 1 m doors in its east wall (centred at y 2 and 8 m), both into one
    2 m deep exit hall, an exit just behind each door; 300 persons start in the south-east half,
    nearer the south door, and choose their exit by the quickest rule (walking time and the queue
    ahead; docs/crowd-model.md "Tactical level: exit choice")."""
    w, h = CHOICE["w"], CHOICE["h"]
    walk = [rect(0, 0, w, h), rect(w + 0.2, 0, w + 2.2, h)]
    exits = []
    for door, y in CHOICE["doors"].items():
        walk.append(rect(w, y - 0.5, w + 0.2, y + 0.5))
        exits.append(exit_point(door, rect(w + 0.6, y - 0.5, w + 1.6, y + 0.5), width=1.0))
    x0, y0, x1, y1 = CHOICE["spawn"]
    return scenario(name, walk, exits,
                    [population("crowd", CHOICE["agents"], {"polygon": rect(x0, y0, x1, y1)}, [], SPEED,
                                exits=list(CHOICE["doors"]), exitChoice={"rule": "quickest"})], 300)


def dynamic_exits(name):
    """NIST 4.1: RiMEA 11's room and crowd choosing by the quickest rule; the north ("far") exit
    closes for good at CHOICE["close_at"] s (the scenario timeline's "close")."""
    s = exit_choice(name)
    s["timeline"] = [{"time": CHOICE["close_at"], "close": "far"}]
    return s


AFFILIATION = {"agents": 40}


def affiliation(name, familiar):
    """NIST 3.3: RiMEA 11's room with 40 persons (few enough that walking, not queueing, decides),
    who know only the north ("far") exit when `familiar`: their exit choice (quickest rule) prices
    the unknown south door at the default familiarity, twice its cost; the control run knows both."""
    s = exit_choice(name)
    s["populations"][0]["groups"] = AFFILIATION["agents"]
    if familiar:
        s["populations"][0]["exitChoice"]["familiar"] = ["far"]
    return s


INFLUENCE = {"choosers": 30, "leaders": 15, "herding": 0.8}


def social_influence(name, herding):
    """NIST 3.2: RiMEA 11's room with 30 persons choosing their exit (quickest rule) among 15 who all
    walk to the north ("far") exit; with `herding` the choosers weigh where the people within 5 m
    are heading (herding 0.8), without it (the control run) they do not."""
    s = exit_choice(name)
    chooser = s["populations"][0]
    chooser["id"], chooser["groups"] = "choosers", INFLUENCE["choosers"]
    if herding:
        chooser["exitChoice"]["herding"] = INFLUENCE["herding"]
    x0, y0, x1, y1 = CHOICE["spawn"]
    s["populations"].append(population("leaders", INFLUENCE["leaders"], {"polygon": rect(x0, y0, x1, y1)}, ["far"], SPEED))
    return s


# --- RiMEA 12 / NIST 5.1: two bottlenecks in a row ----------------------------------------------------
BOTTLENECKS = {"agents": 150, "first": (10.0, 20.0), "second": 30.0, "door_y": (4.5, 5.5),
               "area_first": (8.0, 10.0, 4.0, 6.0), "area_second": (28.0, 30.0, 4.0, 6.0)}


def bottlenecks(name):
    """Room A (10 x 10 m, 150 persons) -> a 1 m wide, 10 m long corridor -> room B (10 x 10 m) -> a
    1 m wide, 2 m long door -> the exit."""
    b = BOTTLENECKS
    y0, y1 = b["door_y"]
    f0, f1 = b["first"]
    walk = [[0, 0], [f0, 0], [f0, y0], [f1, y0], [f1, 0], [f1 + 10, 0], [f1 + 10, y0], [f1 + 12, y0], [f1 + 12, y1],
            [f1 + 10, y1], [f1 + 10, 10], [f1, 10], [f1, y1], [f0, y1], [f0, 10], [0, 10]]
    return scenario(name, [walk], [exit_point("exit", rect(f1 + 11.5, y0, f1 + 12, y1))],
                    [population("crowd", b["agents"], {"polygon": rect(0.3, 0.3, 9.7, 9.7)}, ["exit"], SPEED)], 400)


# --- RiMEA 16 / NIST 2.8: counter-flow through a corridor ---------------------------------------------
COUNTER = {"forward": 50, "against": [0, 10, 25, 50], "corridor": (10.0, 20.0), "door_y": (4.0, 6.0)}


def counter_flow(name, against):
    """Two 10 x 10 m rooms joined by a 10 m long, 2 m wide corridor; 50 persons walk from the west
    room to an exit at the far side of the east room, `against` persons the other way."""
    c0, c1 = COUNTER["corridor"]
    y0, y1 = COUNTER["door_y"]
    walk = [[0, 0], [c0, 0], [c0, y0], [c1, y0], [c1, 0], [c1 + 10, 0], [c1 + 10, 10], [c1, 10], [c1, y1], [c0, y1],
            [c0, 10], [0, 10]]
    pops = [population("forward", COUNTER["forward"], {"polygon": rect(0.5, 0.5, 6.0, 9.5)}, ["east"], SPEED)]
    if against:
        pops.append(population("against", against, {"polygon": rect(c1 + 4.0, 0.5, c1 + 9.5, 9.5)}, ["west"], SPEED))
    points = [exit_point("east", rect(c1 + 9.5, 0, c1 + 10, 10)), exit_point("west", rect(0, 0, 0.5, 10))]
    return scenario(name, [walk], points, pops, 400)


# --- NIST 2.9: groups --------------------------------------------------------------------------------
def groups(name):
    """40 groups of 2 to 4 people cross a 6 m wide, 40 m long hall."""
    return scenario(name, [rect(0, 0, 40, 6)], [exit_point("end", rect(39.5, 0, 40, 6))],
                    [{"id": "groups", "groups": 40, "size": [2, 4], "spawn": {"polygon": rect(0.3, 0.3, 12, 5.7)},
                      "goals": ["end"], "speed": SPEED}], 200)


# --- NIST 5.2: maximum flow through a door ----------------------------------------------------------
DOOR_ROOM = {"agents": 200, "door": (10.0, 4.5, 5.5), "line_x": 10.1}


def door_room(name):
    """200 persons leave a 10 x 10 m room through a 1 m door (0.2 m thick wall)."""
    walk = [[0, 0], [10, 0], [10, 4.5], [10.2, 4.5], [10.2, 3], [14, 3], [14, 7], [10.2, 7], [10.2, 5.5],
            [10, 5.5], [10, 10], [0, 10]]
    return scenario(name, [walk], [exit_point("exit", rect(13.5, 3, 14, 7))],
                    [population("room", DOOR_ROOM["agents"], {"polygon": rect(0.3, 0.3, 9.7, 9.7)}, ["exit"],
                                SPEED)], 300)


# --- RiMEA 14: a short route over stairs or a longer flat one ----------------------------------------
ROUTES = {"steps": 18, "agents": 20, "detour_y": (4.0, 6.0)}


def route_choice(name):
    """A start floor (x 0..10) and a goal floor (x 30..40), both 2 m wide at height 0, joined by a
    short route that goes down 18 steps (3 m) to a lower corridor and up 18 steps again, and by a
    flat detour 2 m to the north (y 4..6, 6 m longer). At Weidmann's speeds (1.34 m/s flat, 0.694 /
    0.61 m/s horizontal down / up a flight) the detour is the quicker: about 31 s against 35 s."""
    verts, tris = [], []
    s, n = STAIR, ROUTES["steps"]
    run = n * s["tread"]
    low = -round(n * s["riser"], 6)
    _quad(verts, tris, [[0, 0, 0], [10, 0, 0], [10, 2, 0], [0, 2, 0]])
    for k in range(n):
        x0, x1 = round(10 + k * s["tread"], 6), round(10 + (k + 1) * s["tread"], 6)
        z = -round((k + 1) * s["riser"], 6)
        _quad(verts, tris, [[x0, 0, z], [x1, 0, z], [x1, 2, z], [x0, 2, z]])
    a, b = round(10 + run, 6), round(30 - run, 6)
    _quad(verts, tris, [[a, 0, low], [b, 0, low], [b, 2, low], [a, 2, low]])
    for k in range(n):
        x0, x1 = round(b + k * s["tread"], 6), round(b + (k + 1) * s["tread"], 6)
        z = round(low + (k + 1) * s["riser"], 6)
        _quad(verts, tris, [[x0, 0, z], [x1, 0, z], [x1, 2, z], [x0, 2, z]])
    _quad(verts, tris, [[30, 0, 0], [40, 0, 0], [40, 2, 0], [30, 2, 0]])
    y0, y1 = ROUTES["detour_y"]
    for x0, x1, ya, yb in ((8, 10, 2, y0), (8, 32, y0, y1), (30, 32, 2, y0)):
        _quad(verts, tris, [[x0, ya, 0], [x1, ya, 0], [x1, yb, 0], [x0, yb, 0]])
    return scenario(name, [], [exit_point("goal", rect(39.4, 0, 40, 2), height=0)],
                    [population("walkers", ROUTES["agents"], {"polygon": rect(0.5, 0.3, 6.0, 1.7), "height": 0},
                                ["goal"], SPEED)], 200, terrain={"vertices": verts, "walkable": tris, "obstacles": []})


# --- ISO 20414 tests that differ from RiMEA's and NIST's ---------------------------------------------
# ISO 7: one slow person ahead of ten faster ones in a 2 m corridor: they must overtake it.
OVERTAKING = {"length": 50.0, "width": 2.0, "slow_x": 8.0, "slow_speed": 0.6, "slow_radius": 0.25, "others": 10,
              "others_speed": {"mean": 1.34, "sd": 0.15, "min": 1.1, "max": 1.6}, "measure": (10.0, 45.0)}


def overtaking(name):
    o = OVERTAKING
    w, length = o["width"], o["length"]
    return scenario(name, [rect(0, 0, length, w)], [exit_point("end", rect(length - 0.5, 0, length, w))],
                    [population("slow", 1, {"position": [o["slow_x"], w / 2]}, ["end"], o["slow_speed"],
                                radius=o["slow_radius"]),
                     population("others", o["others"], {"polygon": rect(0.3, 0.3, 5.0, w - 0.3)}, ["end"],
                                o["others_speed"])], 120)


# ISO 12: a crowd walks down a 2 m wide flight (the steps of RiMEA 2) from a 10 x 10 m room on the
# upper floor; the flow on the flight against the SFPE Handbook's maximum specific flow on stairs.
STAIR_FLOW = {"width": 2.0, "room": 10.0, "agents": 120, "lower": 5.0,
              # SFPE Handbook (Gwynne & Rosenbaum, 5th ed.): 1.01 /(s·m effective width) on a 7/11 stair
              # (0.178 m riser, 0.279 m tread; ours 0.17 / 0.29), effective width = width − 2 × 0.15 m.
              "sfpe_max": 1.01, "boundary": 0.15}


def stair_flow(name):
    """Room (upper floor) -> 5 m landing -> 2 m wide flight down -> 5 m lower landing -> exit."""
    f = STAIR_FLOW
    w = f["width"]
    terrain, top_end = stair_terrain(w, lower_from=STAIR["foot_x"] - f["lower"])
    h = round(stair_height(), 6)
    x0, x1, yc = top_end, round(top_end + f["room"], 6), w / 2
    _quad(terrain["vertices"], terrain["walkable"],
          [[x0, yc - f["room"] / 2, h], [x1, yc - f["room"] / 2, h], [x1, yc + f["room"] / 2, h],
           [x0, yc + f["room"] / 2, h]])
    spawn = rect(x0 + 0.5, yc - f["room"] / 2 + 0.3, x1 - 0.3, yc + f["room"] / 2 - 0.3)
    lo = STAIR["foot_x"] - f["lower"]
    return scenario(name, [], [exit_point("down", rect(lo, 0, lo + 0.6, w), height=0.0)],
                    [{"id": "crowd", "groups": f["agents"], "size": 1, "spawn": {"polygon": spawn, "height": h},
                      "goals": ["down"], "speed": SPEED}], 400, terrain=terrain)


# ISO 13: a 2 m wide corridor; a crowd at three densities in its first 20 m walks to its far end, and
# flow, density and speed are measured in x 30 .. 40.
CORRIDOR_FD = {"length": 60.0, "width": 2.0, "fill": 20.0, "densities": [0.5, 1.0, 2.0], "zone": (30.0, 40.0),
               # SFPE Handbook: at most 1.3 persons /(s·m effective width) in a corridor, walls' boundary
               # layer 0.2 m each side.
               "sfpe_max": 1.3, "boundary": 0.2}


def corridor_fd(name, rho):
    c = CORRIDOR_FD
    w, n = c["width"], int(round(rho * c["fill"] * c["width"]))
    return scenario(name, [rect(0, 0, c["length"], w)], [exit_point("end", rect(c["length"] - 0.5, 0, c["length"], w))],
                    [population("crowd", n, {"polygon": rect(0.2, 0.2, c["fill"], w - 0.2)}, ["end"], SPEED)], 200)


# ISO 17: a building of two floors. The persons are on the upper floor; one exit (below) is on the
# ground floor just beneath them, nearer than any other as the crow flies, but the only way down is a
# flight at the far (west) end of the upper floor, and the ground floor leads back east under the
# room to that exit; the other exit (east) is a door out of the upper floor itself, at its east end
# (onto a footbridge, as a building on a slope has). Each person chooses by walking distance (the
# "nearest" rule).
LAYOUT = {"w": 30.0, "d": 10.0, "steps": 18, "door_y": 5.0, "door_w": 2.0, "stair_y": (4.0, 6.0), "landing": 3.0,
          "corridor_y": (0.0, 3.5), "below_x": (11.5, 13.5), "spawn": (11.0, 2.0, 14.0, 8.0), "agents": 20}


def layout_height():
    """The upper floor's height: the flight's 18 risers of RiMEA 2's steps [m]."""
    return round(LAYOUT["steps"] * STAIR["riser"], 6)


def layout_exits():
    """Each exit's centre as [x, y, z] (the measurement compares distances to them)."""
    g, h = LAYOUT, layout_height()
    bx0, bx1 = g["below_x"]
    return {"below": [(bx0 + bx1) / 2, -0.75, 0.0], "east": [g["w"] + 0.75, g["door_y"], h]}


def route_layout(name):
    """Upper floor (x 0..w, y 0..d at the flight's height) with a 2 m door and 1 m of footbridge east
    (exit "east"); at its west end a 2 m wide flight of 18 steps down westward to a ground landing,
    from which a 3.5 m corridor runs east under the room's south side to a 2 m door in its south
    wall (exit "below"), beneath the persons. The doors are as wide as the flight, so that what the
    test sees is the choice, not a queue (in 1 m doors cfsm's persons jam for good)."""
    g, s, h = LAYOUT, STAIR, layout_height()
    verts, tris = [], []
    w, d, y = g["w"], g["d"], g["door_y"]
    sy0, sy1 = g["stair_y"]
    run = round(g["steps"] * s["tread"], 6)
    _quad(verts, tris, [[0, 0, h], [w, 0, h], [w, d, h], [0, d, h]])                      # upper floor
    dw = g["door_w"] / 2
    _quad(verts, tris, [[w, y - dw, h], [w + 1, y - dw, h], [w + 1, y + dw, h], [w, y + dw, h]])  # bridge
    for k in range(g["steps"]):                                                            # the flight
        x0, x1, z = round(-run + k * s["tread"], 6), round(-run + (k + 1) * s["tread"], 6), round((k + 1) * s["riser"], 6)
        _quad(verts, tris, [[x0, sy0, z], [x1, sy0, z], [x1, sy1, z], [x0, sy1, z]])
    cy0, cy1 = g["corridor_y"]
    lx = round(-run - g["landing"], 6)
    _quad(verts, tris, [[lx, cy1, 0], [-run, cy1, 0], [-run, sy1, 0], [lx, sy1, 0]])           # ground landing
    _quad(verts, tris, [[lx, cy0, 0], [w, cy0, 0], [w, cy1, 0], [lx, cy1, 0]])               # ground corridor
    bx0, bx1 = g["below_x"]
    _quad(verts, tris, [[bx0, -1, 0], [bx1, -1, 0], [bx1, 0, 0], [bx0, 0, 0]])               # its south door
    exits = [exit_point("below", rect(bx0, -1.0, bx1, -0.5), height=0.0),
             exit_point("east", rect(w + 0.5, y - dw, w + 1.0, y + dw), height=h)]
    x0, y0, x1, y1 = g["spawn"]
    return scenario(name, [], exits,
                    [population("crowd", g["agents"], {"polygon": rect(x0, y0, x1, y1), "height": h}, [], SPEED,
                                exits=["below", "east"], exitChoice={"rule": "nearest"})], 200,
                    terrain={"vertices": verts, "walkable": tris, "obstacles": []})


# NIST 2.6: a 20 x 8 m room whose left half is full of smoke with carbon monoxide (a fractional
# effective dose of 1 a minute, ISO 13571); ten persons of each kind (pre-movement time, limit).
INCAPACITATION = {"co": 35000.0, "extinction": 1.0, "smoke_x": 10.0, "per_population": 10,
                  "kinds": {  # id: (spawn rectangle, pre-movement [s], incapacitation dose)
                      "stay": ((1.0, 0.5, 9.0, 3.5), 90.0, 1.0),
                      "susceptible": ((1.0, 0.5, 9.0, 3.5), 90.0, 0.3),
                      "leave": ((1.0, 5.0, 9.0, 7.5), 20.0, 1.0),
                      "clear": ((11.0, 5.0, 18.0, 7.5), 90.0, 1.0)}}


def incapacitation(name):
    c = INCAPACITATION
    pops = []
    for pid, (box, wait, dose) in c["kinds"].items():
        pops.append(population(pid, c["per_population"], {"polygon": rect(*box)}, ["exit"],
                               preMovement={"distribution": "uniform", "min": wait, "max": wait},
                               incapacitationDose=dose))
    return scenario(name, [rect(0, 0, 20, 8)], [exit_point("exit", rect(19.5, 4.5, 20, 8))], pops, 150,
                    smoke=[{"polygon": rect(0, 0, c["smoke_x"], 8), "extinction": c["extinction"], "co": c["co"]}])


# NIST 2.7 (ISO 20414 test 20) and ISO 20414 test 21: two 12 x 10 m floors 4 m apart, joined by
# nothing walkable. The lift's stops, its lobbies (where people queue: room for all 28), stand one
# over the other at x 0.5..3, y 2..8; the escalator runs from
# the ground floor's stop at x 0.5..2 to the upper floor's at x 7.5..9 (7 m across, 4 m up). The
# lift carries 28 persons down from the upper floor, the escalator 20 up from the ground floor;
# each then leaves by its floor's exit at x 10.5..12.
TRANSPORT_FLOORS = {"size": (12.0, 10.0), "heights": (0.0, 4.0), "exit_x": (10.5, 12.0), "exit_y": (3.0, 7.0)}
LIFT = {"agents": 28, "spawn": (4.0, 1.0, 9.0, 9.0), "stop": (0.5, 2.0, 3.0, 8.0),  # the stop: the lift lobby
        "capacity": 8, "speed": 1.0, "acceleration": 1.0, "door_open": 2.0, "door_close": 3.0, "transfer": 1.2}
ESCALATOR = {"agents": 20, "spawn": (3.0, 2.0, 7.0, 8.0), "low": (0.5, 4.0, 2.0, 6.0), "high": (7.5, 4.0, 9.0, 6.0),
             "speed": 0.5, "headway": 0.8}


def _two_floors():
    w, d = TRANSPORT_FLOORS["size"]
    verts, tris = [], []
    for z in TRANSPORT_FLOORS["heights"]:
        _quad(verts, tris, [[0, 0, z], [w, 0, z], [w, d, z], [0, d, z]])
    return {"vertices": verts, "walkable": tris, "obstacles": []}


def _floor_exit(pid, z):
    x0, x1 = TRANSPORT_FLOORS["exit_x"]
    y0, y1 = TRANSPORT_FLOORS["exit_y"]
    return exit_point(pid, rect(x0, y0, x1, y1), height=z)


def _stop(pid, box, z):
    return {"id": pid, "kind": "interest", "polygon": rect(*box), "height": z}


def lift(name):
    g, (low, high) = LIFT, TRANSPORT_FLOORS["heights"]
    points = [_stop("lift-low", g["stop"], low), _stop("lift-high", g["stop"], high), _floor_exit("exit", low)]
    transports = [{"id": "lift", "kind": "elevator", "stops": ["lift-low", "lift-high"], "capacity": g["capacity"],
                   "speed": g["speed"], "acceleration": g["acceleration"], "doorOpenTime": g["door_open"],
                   "doorCloseTime": g["door_close"], "transferTime": g["transfer"]}]
    pops = [population("upstairs", g["agents"], {"polygon": rect(*g["spawn"]), "height": high}, ["lift-high", "exit"], SPEED)]
    return scenario(name, [], points, pops, 400, terrain=_two_floors(), transports=transports)


def escalator(name):
    g, (low, high) = ESCALATOR, TRANSPORT_FLOORS["heights"]
    points = [_stop("escalator-low", g["low"], low), _stop("escalator-high", g["high"], high), _floor_exit("exit", high)]
    transports = [{"id": "escalator", "kind": "escalator", "stops": ["escalator-low", "escalator-high"],
                   "speed": g["speed"], "headway": g["headway"]}]
    pops = [population("downstairs", g["agents"], {"polygon": rect(*g["spawn"]), "height": low}, ["escalator-low", "exit"],
                       SPEED)]
    return scenario(name, [], points, pops, 200, terrain=_two_floors(), transports=transports)
