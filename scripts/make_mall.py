#!/usr/bin/env python3
"""Writes scenarios/mall.json: the Common Ground shopping mall (Park, Peng, Quek & Cao).

The paper's experiment (§5): a shopping mall with 82 stores and 6 restrooms as potential goals,
1000 characters: 800 in 200 social groups of 2 to 6 members and 200 individuals.

Layout (metres, x east, y north; the building is 250 m x 74 m):
  - two parallel east-west concourses, "hall-a" (north, y 49.6..59.6) and "hall-b" (south,
    y 14.4..24.4), 10 m wide, joined at both ends by 12 m wide courts (west, east) and in the
    middle by three 10 m cross corridors ("cross-1..3" at x 70, 125, 180): a ring with chords;
  - 82 stores (8.1..11.8 m wide, 12..14 m deep), each one walkable room opening onto a
    concourse through a 3..4 m doorway: 22 north of hall-a, 17 south of hall-a, 17 north of
    hall-b, 22 south of hall-b, 2 on each court;
  - 6 restrooms (6 m x 6 m, 2 m doorway): 2 on each court, 2 beside the central cross corridor;
  - 4 entrances (8 m wide vestibules through the outer store rows): north and south at x 125,
    west and east through the courts at y 37. Each has an exit strip at the building's edge
    ("entrance-north" ... kind "exit") and a spawn area just inside it.
Walls are gaps of 0.4 m between walkable rooms (the walkable area is the union of concourses,
rooms and doorways); the only obstacles are kiosks in the concourses.

Points: "store-01".."store-82" (interest, disc r 2.5 m at the room's centre, "category" one of
ten store kinds spread over the mall), "restroom-1".."restroom-6" ("category": "restroom"),
concourse waypoints "hall-a-1..", "hall-b-1..", "cross-1..3", "court-west", "court-east", and the
four entrance exits.

Populations: one per social group ("party-001".."party-200", sizes drawn in [2, 6] and rebalanced
to sum to 800) and individuals in populations of 1..5 ("solo-01".., 200 agents in all). Each
spawns at an entrance ("party", not "group": the viewer numbers groups by the engine's group ids,
and "group 0 (group-001)" read as off by one), starts within the first 120 s, and walks a tour of 3..6 concourse
waypoints (an arc around the ring of halls in one direction, possibly cutting through one cross
corridor: never back and forth) ending at an entrance exit; tours are 250..460 m long, spawn to exit
(about 3.5..6 minutes at 1.27 m/s; with group waits and congestion the core run ends by ~12 min). "interests" (2..4 categories) and "interestsPerAgent" feed the Common
Ground model (docs/social-model.md), configured by the top-level "social" section.

usage: scripts/make_mall.py [--seed N] [--out FILE] [--core-only] [--probe] [--plot PNG] [--stats]

--core-only drops the Common Ground keys ("category", "interests", "interestsPerAgent", "preferences",
"social"). Half the populations get a communication style ("preferences": talkative callers or
gesturers) drawn from their own random stream.
so that the file loads with a parser that does not know them; --probe adds a population whose
goals are every point (a reachability check for `throng check`, not for committing). --plot
draws the layout (needs matplotlib: run with /usr/bin/python3). Deterministic for a given seed.
"""
import argparse
import json
import math
import os
import random
import sys

W = 0.4  # wall thickness: the gap between neighbouring walkable rooms [m]
L = 250.0  # building length (x) [m]
H = 74.0  # building depth (y) [m]
HALL_W = 10.0  # concourse width [m]
COURT_W = 12.0  # court width [m]
CROSS_W = 10.0  # cross-corridor width [m]
CROSS_X = (70.0, 125.0, 180.0)  # cross-corridor centres [m]
ENTRANCE_W = 8.0  # entrance vestibule width [m]
MID_DEPTH = 12.0  # depth of the stores in the middle block [m]
RESTROOM = 6.0  # restroom interior side [m]
POINT_R = 2.5  # store interest point radius [m]
MIN_TOUR, MAX_TOUR = 250.0, 460.0  # tour length, spawn to exit [m]
CATEGORIES = ["clothes", "shoes", "books", "electronics", "food", "toys", "sports", "jewelry", "home", "beauty"]

# Derived y coordinates (see the docstring).
HB0 = 14.4  # hall-b: y HB0 .. HB1
HB1 = HB0 + HALL_W
MS0 = HB1 + W  # middle block, south row: MS0 .. MS0 + MID_DEPTH
MN0 = MS0 + MID_DEPTH + W  # middle block, north row
HA0 = MN0 + MID_DEPTH + W  # hall-a: y HA0 .. HA1
HA1 = HA0 + HALL_W
XC0 = 12.4  # west court: x XC0 .. XC0 + COURT_W (the east court mirrors it)
YMID = (HB0 + HA1) / 2  # the courts' and the west/east entrances' centre line



DESCRIPTION = ('A shopping mall: 1,000 shoppers in groups of one to six come in by the four entrances (green: they leave there too), walk the two halls and courts to shops and restrooms and stay inside a while. When one of a group wants to go somewhere, the group first agrees on a plan (Common Ground): they split up and meet again, or all go along.')

def r2(v):
    return round(v + 0.0, 2)


def rect(x0, y0, x1, y1):
    return [[r2(x0), r2(y0)], [r2(x1), r2(y0)], [r2(x1), r2(y1)], [r2(x0), r2(y1)]]


def room_with_door(x0, y0, x1, y1, side, d0, d1, reach):
    """A room [x0,x1]x[y0,y1] plus a doorway on `side` ('n','s','e','w') spanning d0..d1 along
    that side, reaching `reach` metres out (through the wall, overlapping the concourse by 0.1 m):
    one simple polygon, counter-clockwise."""
    if side == "s":
        return [[x0, y0], [d0, y0], [d0, y0 - reach], [d1, y0 - reach], [d1, y0], [x1, y0], [x1, y1], [x0, y1]]
    if side == "n":
        return [[x0, y0], [x1, y0], [x1, y1], [d1, y1], [d1, y1 + reach], [d0, y1 + reach], [d0, y1], [x0, y1]]
    if side == "e":
        return [[x0, y0], [x1, y0], [x1, d0], [x1 + reach, d0], [x1 + reach, d1], [x1, d1], [x1, y1], [x0, y1]]
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, d1], [x0 - reach, d1], [x0 - reach, d0], [x0, d0]]


def split_widths(rng, length, n, lo, hi):
    """n widths in [lo, hi] with n widths + (n - 1) walls = length, jittered around the mean."""
    mean = (length - (n - 1) * W) / n
    assert lo <= mean <= hi, (length, n, mean)
    span = min(mean - lo, hi - mean, 1.2)
    ws = [mean + rng.uniform(-span, span) for _ in range(n)]
    shift = (sum(ws) - (length - (n - 1) * W)) / n
    ws = [w - shift for w in ws]
    assert all(lo - 1e-9 <= w <= hi + 1e-9 for w in ws), ws
    return ws


class Mall:
    def __init__(self, rng):
        self.rng = rng
        self.walkable = []
        self.obstacles = []
        self.stores = []  # (polygon, centre, facing concourse)
        self.restrooms = []
        self.entrances = {}  # name -> (exit polygon, spawn polygon, anchor waypoint)
        self.waypoints = []  # (id, x, y, r)
        self.layout = {}

    # --- rooms ---------------------------------------------------------------------------------
    def add_row(self, x0, x1, y_front, facing, n, depth_range, restroom_at=None):
        """Stores along x0..x1, fronts at y_front, opening `facing` ('n' or 's') onto a concourse.
        restroom_at: 'west' or 'east' puts a restroom at that end of the row."""
        rooms = []
        if restroom_at == "west":
            rooms.append(("restroom", x0, x0 + RESTROOM))
            x0 += RESTROOM + W
        elif restroom_at == "east":
            rooms.append(("restroom", x1 - RESTROOM, x1))
            x1 -= RESTROOM + W
        x = x0
        for w in split_widths(self.rng, x1 - x0, n, 8.0, 12.0):
            rooms.append(("store", x, x + w))
            x += w + W
        rooms.sort(key=lambda r: r[1])
        for kind, a, b in rooms:
            depth = RESTROOM if kind == "restroom" else (
                depth_range[0] if depth_range[0] == depth_range[1] else round(self.rng.uniform(*depth_range) * 2) / 2)
            door = 2.0 if kind == "restroom" else round(self.rng.uniform(3.0, 4.0), 1)
            mid = (a + b) / 2 + (0 if kind == "restroom" else self.rng.uniform(-1, 1) * max(0.0, (b - a - door) / 2 - 1.5))
            d0, d1 = mid - door / 2, mid + door / 2
            if facing == "s":  # front at the south: the room extends north from y_front
                y0, y1 = y_front, y_front + depth
                poly = room_with_door(a, y0, b, y1, "s", d0, d1, W + 0.1)
            else:
                y0, y1 = y_front - depth, y_front
                poly = room_with_door(a, y0, b, y1, "n", d0, d1, W + 0.1)
            centre = ((a + b) / 2, (y0 + y1) / 2)
            self.add_room(kind, poly, centre, (a, y0, b, y1))

    def add_court_rooms(self, east, y0, y1, spec):
        """Rooms on a court's outer wall between y0 and y1; spec: list of 'store'/'restroom' from
        south to north. West court rooms lie at x < XC0 - W, east court rooms mirror them."""
        sizes = [RESTROOM if k == "restroom" else None for k in spec]
        free = (y1 - y0) - sum(s for s in sizes if s) - (len(spec) - 1) * W
        n_stores = sizes.count(None)
        sizes = [s if s else free / n_stores for s in sizes]
        y = y0
        wall = L - XC0 if east else XC0  # the court's outer wall line
        for kind, s in zip(spec, sizes):
            depth = RESTROOM if kind == "restroom" else MID_DEPTH
            door = 2.0 if kind == "restroom" else 3.5
            mid = y + s / 2
            if east:
                a, b = wall + W, wall + W + depth
                poly = room_with_door(a, y, b, y + s, "w", mid - door / 2, mid + door / 2, W + 0.1)
            else:
                a, b = wall - W - depth, wall - W
                poly = room_with_door(a, y, b, y + s, "e", mid - door / 2, mid + door / 2, W + 0.1)
            self.add_room(kind, poly, ((a + b) / 2, y + s / 2), (a, y, b, y + s))
            y += s + W

    def add_room(self, kind, poly, centre, box):
        poly = [[r2(x), r2(y)] for x, y in poly]
        self.walkable.append(poly)
        (self.restrooms if kind == "restroom" else self.stores).append({"poly": poly, "centre": centre, "box": box})

    # --- the whole mall ------------------------------------------------------------------------
    def build(self):
        xe = L - XC0  # east edge of the halls
        # Concourses: two halls, two courts, three cross corridors (overlapping by 0.1 m).
        self.walkable += [rect(XC0, HA0, xe, HA1), rect(XC0, HB0, xe, HB1),
                          rect(XC0, HB0, XC0 + COURT_W, HA1), rect(xe - COURT_W, HB0, xe, HA1)]
        for c in CROSS_X:
            self.walkable.append(rect(c - CROSS_W / 2, HB1 - 0.1, c + CROSS_W / 2, HA0 + 0.1))
        # Entrances: vestibules through the outer rows / court walls, exit strip at the edge.
        cx, e2 = L / 2, ENTRANCE_W / 2
        vest = {"north": rect(cx - e2, HA1 - 0.1, cx + e2, H), "south": rect(cx - e2, 0, cx + e2, HB0 + 0.1),
                "west": rect(0, YMID - e2, XC0 + 0.1, YMID + e2), "east": rect(xe - 0.1, YMID - e2, L, YMID + e2)}
        ex = {"north": rect(cx - e2, H - 1.5, cx + e2, H), "south": rect(cx - e2, 0, cx + e2, 1.5),
              "west": rect(0, YMID - e2, 1.5, YMID + e2), "east": rect(L - 1.5, YMID - e2, L, YMID + e2)}
        sp = {"north": rect(cx - e2 + 0.6, H - 9.0, cx + e2 - 0.6, H - 2.0),
              "south": rect(cx - e2 + 0.6, 2.0, cx + e2 - 0.6, 9.0),
              "west": rect(2.0, YMID - e2 + 0.6, 9.0, YMID + e2 - 0.6),
              "east": rect(L - 9.0, YMID - e2 + 0.6, L - 2.0, YMID + e2 - 0.6)}
        for k in ("north", "east", "south", "west"):
            self.walkable.append(vest[k])
        # Stores. Outer rows: 11 + 11 either side of the north/south entrance; the middle block:
        # 4 segments between courts and cross corridors, 17 stores + 1 restroom per row.
        outer_w = [(XC0, cx - e2 - W), (cx + e2 + W, xe)]
        for (a, b) in outer_w:
            self.add_row(a, b, HA1 + W, "s", 11, (12.0, 14.0))  # north of hall-a
        mids = [XC0 + COURT_W + W] + [v for c in CROSS_X for v in (c - CROSS_W / 2 - W, c + CROSS_W / 2 + W)] + [
            xe - COURT_W - W]
        segs = [(mids[i], mids[i + 1]) for i in range(0, 8, 2)]
        for i, (a, b) in enumerate(segs):  # south of hall-a (middle block, north row)
            self.add_row(a, b, HA0 - W, "n", [4, 5, 4, 4][i], (MID_DEPTH, MID_DEPTH), "west" if i == 2 else None)
        for i, (a, b) in enumerate(segs):  # north of hall-b (middle block, south row)
            self.add_row(a, b, HB1 + W, "s", [4, 4, 5, 4][i], (MID_DEPTH, MID_DEPTH), "east" if i == 1 else None)
        for (a, b) in outer_w:
            self.add_row(a, b, HB0 - W, "n", 11, (12.0, 14.0))  # south of hall-b
        for east in (False, True):
            self.add_court_rooms(east, HB0, YMID - e2 - W, ["store", "restroom"])
            self.add_court_rooms(east, YMID + e2 + W, HA1, ["restroom", "store"])
        # Waypoints: along both halls (junctions at the cross corridors, the courts' inner edge
        # and the entrances, about 18 m apart in between), the cross corridors and the courts.
        anchors = [XC0 + COURT_W + 3.0] + list(CROSS_X) + [xe - COURT_W - 3.0]
        xs = []
        for a, b in zip(anchors, anchors[1:]):
            n = max(1, math.ceil((b - a) / 20.0))
            xs += [a + (b - a) * i / n for i in range(n)]
        xs.append(anchors[-1])
        self.hall_x = [r2(x) for x in xs]
        ya, yb = (HA0 + HA1) / 2, (HB0 + HB1) / 2
        for i, x in enumerate(self.hall_x):
            self.waypoints.append(("hall-a-%d" % (i + 1), x, ya, POINT_R))
        for i, x in enumerate(self.hall_x):
            self.waypoints.append(("hall-b-%d" % (i + 1), x, yb, POINT_R))
        for i, c in enumerate(CROSS_X):
            self.waypoints.append(("cross-%d" % (i + 1), c, (HB1 + HA0) / 2, POINT_R))
        self.waypoints.append(("court-west", XC0 + COURT_W / 2, YMID, POINT_R))
        self.waypoints.append(("court-east", xe - COURT_W / 2, YMID, POINT_R))
        # Kiosks: 3 m x 2 m on the halls' centre line, halfway between waypoints that are not
        # cross-corridor junctions or the north/south entrances.
        for y in (ya, yb):
            for a, b in zip(self.hall_x, self.hall_x[1:]):
                m = (a + b) / 2
                if all(abs(m - c) > 8 for c in CROSS_X):
                    self.obstacles.append(rect(m - 1.5, y - 1.0, m + 1.5, y + 1.0))
        mid_i = self.hall_x.index(r2(cx))
        anchor = {"north": "hall-a-%d" % (mid_i + 1), "south": "hall-b-%d" % (mid_i + 1),
                  "west": "court-west", "east": "court-east"}
        for k in ("north", "east", "south", "west"):
            self.entrances[k] = (ex[k], sp[k], anchor[k])
        self.layout = {"outer rows": 44, "middle rows": 34, "courts": 4}


# --- tours ---------------------------------------------------------------------------------------
def ring_graph(mall):
    """The ring of concourse waypoints (west court, hall-a west to east, east court, hall-b east to
    west) and the chords through the cross corridors."""
    n = len(mall.hall_x)
    ring = ["court-west"] + ["hall-a-%d" % (i + 1) for i in range(n)] + ["court-east"] + [
        "hall-b-%d" % (i + 1) for i in reversed(range(n))]
    chords = {}
    for j, c in enumerate(CROSS_X):
        i = mall.hall_x.index(r2(c))
        a, b, x = "hall-a-%d" % (i + 1), "hall-b-%d" % (i + 1), "cross-%d" % (j + 1)
        chords[a] = (x, b)
        chords[b] = (x, a)
    return ring, chords


def make_tour(rng, mall, start, pos):
    """A tour from entrance `start`: goals (3..6 waypoints then an entrance exit) and its length."""
    ring, chords = ring_graph(mall)
    anchor_of = {k: v[2] for k, v in mall.entrances.items()}
    entrance_at = {v: k for k, v in anchor_of.items()}
    spawn_c = centroid(mall.entrances[start][1])
    i = ring.index(anchor_of[start])
    d = rng.choice((1, -1))
    target = rng.uniform(MIN_TOUR, 430.0)
    route = [ring[i]]
    turns, before = set(), set()  # route positions of the tour's corners and of the waypoint before each
    dist = math.dist(spawn_c, pos[ring[i]])
    exit_leg = lambda w: math.dist(pos[w], centroid(mall.entrances[entrance_at[w]][0]))

    def to_next_anchor(j):
        """Walking distance from ring[j] on (direction d) to the first entrance waypoint."""
        total = 0.0
        while ring[j] not in entrance_at:
            total += math.dist(pos[ring[j]], pos[ring[(j + d) % len(ring)]])
            j = (j + d) % len(ring)
        return total + exit_leg(ring[j])

    chord_used = False
    for _ in range(2 * len(ring)):
        cur = route[-1]
        if not chord_used and cur in chords and rng.random() < 0.5:
            # A cross corridor cuts the ring: allowed when it lands on a hall not walked yet; the
            # tour then ends at the first entrance after it (so it never walks a hall twice).
            x, other = chords[cur]
            q = ring.index(other)
            total = dist + math.dist(pos[cur], pos[x]) + math.dist(pos[x], pos[other]) + to_next_anchor(q)
            if other not in route and max(MIN_TOUR, target - 100.0) <= total <= MAX_TOUR:
                before.add(len(route) - 1)
                turns.add(len(route))
                route += [x, other]
                dist += math.dist(pos[cur], pos[x]) + math.dist(pos[x], pos[other])
                i = q
                chord_used = True
                target = 0.0
                if other in entrance_at:
                    dist += exit_leg(other)
                    break
                continue
        i = (i + d) % len(ring)
        dist += math.dist(pos[cur], pos[ring[i]])
        if ring[i].startswith("court") and ring[i] != route[0]:
            before.add(len(route) - 1)
            turns.add(len(route))
        route.append(ring[i])
        last = route[-1]
        if last == route[0] or (last in entrance_at and (
                dist + exit_leg(last) >= target or  # far enough, or the next entrance is too far:
                (dist + exit_leg(last) >= MIN_TOUR and dist + to_next_anchor((i + d) % len(ring)) +
                 math.dist(pos[last], pos[ring[(i + d) % len(ring)]]) > MAX_TOUR))):
            dist += exit_leg(last)  # back at the start (a full round) or far enough
            break
    exit_name = entrance_at[route[-1]]
    # Goals are route positions 1 .. len - 2 (the first and last are the entrances' waypoints).
    # Corners and the waypoint before each are goals, so that every leg between two goals runs
    # along one hall or round one corner (the navmesh's shortest path then follows the tour).
    inner = range(1, len(route) - 1)
    chosen = sorted((turns | before) & set(inner))
    if len(chosen) > 6:
        chosen = sorted(turns & set(inner))
    k = min(len(inner), max(len(chosen), rng.randint(3, 6)))
    others = [n for n in inner if n not in chosen]
    while len(chosen) < k and others:
        # evenly spread: the remaining waypoint farthest (in route order) from the chosen ones
        ci = chosen + [0, len(route) - 1]
        best = max(others, key=lambda n: (min(abs(n - c) for c in ci), -n))
        chosen.append(best)
        others.remove(best)
    chosen = [route[n] for n in sorted(chosen)]
    assert all(a != b for a, b in zip(chosen, chosen[1:])), route
    return chosen + ["entrance-" + exit_name], dist


def centroid(poly):
    return (sum(p[0] for p in poly) / len(poly), sum(p[1] for p in poly) / len(poly))


def group_sizes(rng, groups=200, agents=800, lo=2, hi=6):
    sizes = [rng.randint(lo, hi) for _ in range(groups)]
    while sum(sizes) != agents:  # rebalance one random group at a time, staying in [lo, hi]
        i = rng.randrange(groups)
        if sum(sizes) > agents and sizes[i] > lo:
            sizes[i] -= 1
        elif sum(sizes) < agents and sizes[i] < hi:
            sizes[i] += 1
    return sizes


def solo_sizes(rng, agents=200, lo=1, hi=5):
    out = []
    while sum(out) < agents:
        out.append(min(rng.randint(lo, hi), agents - sum(out)))
    return out


def spread_categories(rng, n):
    """n categories, each of the ten about equally often, shuffled until no two consecutive stores
    (in id order, i.e. neighbours along a row) share one."""
    cats = [CATEGORIES[i % len(CATEGORIES)] for i in range(n)]
    for _ in range(1000):
        rng.shuffle(cats)
        if all(a != b for a, b in zip(cats, cats[1:])):
            break
    return cats


def build_scenario(seed, core_only=False, probe=False):
    rng = random.Random(seed)
    mall = Mall(rng)
    mall.build()
    cats = spread_categories(rng, len(mall.stores))
    points = []
    for i, s in enumerate(mall.stores):
        p = {"id": "store-%02d" % (i + 1), "kind": "interest", "position": [r2(s["centre"][0]), r2(s["centre"][1])],
             "radius": POINT_R}
        if not core_only:
            p["category"] = cats[i]
        points.append(p)
    for i, s in enumerate(mall.restrooms):
        p = {"id": "restroom-%d" % (i + 1), "kind": "interest", "position": [r2(s["centre"][0]), r2(s["centre"][1])],
             "radius": 1.5}
        if not core_only:
            p["category"] = "restroom"
        points.append(p)
    for (wid, x, y, r) in mall.waypoints:
        points.append({"id": wid, "kind": "interest", "position": [r2(x), r2(y)], "radius": r})
    for k, (ex, sp, anchor) in mall.entrances.items():
        points.append({"id": "entrance-" + k, "kind": "exit", "polygon": ex})
    pos = {p["id"]: tuple(p["position"]) for p in points if "position" in p}

    populations = []
    tour_lengths = []
    starts_rng = random.Random(seed + 1)
    # Communication styles (Common Ground "preferences": multipliers of the micro-behaviour
    # database's weights), drawn per population from their own stream so nothing else moves.
    style_rng = random.Random(seed + 2)
    styles = [None, None, {"call_out": 2.0, "talk": 2.0, "wave": 0.5},
              {"wave": 2.0, "beckon": 2.0, "point_toward": 1.5, "call_out": 0.5}]
    entr = ["north", "east", "south", "west"]

    def population(pid, groups, size):
        start = entr[rng.randrange(4)]
        goals, length = make_tour(rng, mall, start, pos)
        tour_lengths.append(length)
        p = {"id": pid, "groups": groups, "size": size, "start": round(starts_rng.uniform(0.0, 120.0), 1),
             "spawn": {"polygon": mall.entrances[start][1]}, "goals": goals,
             "speed": {"mean": round(rng.uniform(1.2, 1.34), 2), "sd": 0.15}, "radius": 0.22, "flocking": True}
        interests = rng.sample(CATEGORIES, rng.randint(2, 4))
        if not core_only:
            p["interests"] = interests
            p["interestsPerAgent"] = 2
            style = styles[style_rng.randrange(len(styles))]
            if style:
                p["preferences"] = style
        populations.append(p)

    sizes = group_sizes(rng)
    for i, n in enumerate(sizes):
        population("party-%03d" % (i + 1), 1, n)
    solos = solo_sizes(rng)
    for i, n in enumerate(solos):
        population("solo-%02d" % (i + 1), n, 1)
    if probe:  # every point, one by one (reachability); not part of the committed scenario
        populations.append({"id": "probe", "groups": 1, "size": 1, "spawn": {"polygon": mall.entrances["west"][1]},
                            "goals": [p["id"] for p in points if p["kind"] != "exit"] + ["entrance-east"],
                            "radius": 0.22})

    scenario = {"format": "throng/1", "name": "mall", "description": DESCRIPTION, "seed": seed, "duration": 1800,
                "walkable": mall.walkable, "obstacles": mall.obstacles, "points": points, "populations": populations}
    if not core_only:
        scenario["social"] = {
            "commonGround": True,
            "senses": {"hearing": 7.0, "vision": 25.0, "fieldOfView": 120},
            "needs": [{"category": "restroom", "rate": 0.0008, "expectedVisit": 120}],
            "attraction": {"probability": 0.08, "expectedVisit": 60},
            "coordination": {"turnRate": 3.0, "responseTimeout": 2.0, "maxAttempts": 3},
            "motions": "motions"}
    stats = {"group sizes": sizes, "solo populations": solos, "tour lengths": tour_lengths, "mall": mall}
    return scenario, stats


def check_geometry(scenario, mall):
    """Asserts what the loader does not check: store/restroom points clear of their room's walls."""
    for rooms, prefix, clear in ((mall.stores, "store", 0.5), (mall.restrooms, "restroom", 0.5)):
        for s in rooms:
            x0, y0, x1, y1 = s["box"]
            cx, cy = s["centre"]
            r = POINT_R if prefix == "store" else 1.5
            assert min(cx - x0, x1 - cx, cy - y0, y1 - cy) >= r + clear, (prefix, s["box"])
            assert 8.0 - 1e-6 <= max(x1 - x0, y1 - y0) or prefix == "restroom"
    xs = [p[0] for poly in scenario["walkable"] for p in poly]
    ys = [p[1] for poly in scenario["walkable"] for p in poly]
    assert min(xs) >= 0 and max(xs) <= L and min(ys) >= 0 and max(ys) <= H, (min(xs), max(xs), min(ys), max(ys))
    assert len(mall.stores) == 82 and len(mall.restrooms) == 6


def dumps(scenario):
    """Compact, diff-friendly JSON: one polygon / point / population per line."""
    c = lambda v: json.dumps(v, separators=(", ", ": "))
    lines = ["{"]
    keys = list(scenario)
    for n, k in enumerate(keys):
        v = scenario[k]
        end = "," if n + 1 < len(keys) else ""
        if isinstance(v, list) and v:
            lines.append('  "%s": [' % k)
            lines += ["    " + c(e) + ("," if j + 1 < len(v) else "") for j, e in enumerate(v)]
            lines.append("  ]" + end)
        elif isinstance(v, dict):
            lines.append('  "%s": {' % k)
            lines += ['    "%s": %s' % (kk, c(vv)) + ("," if j + 1 < len(v) else "") for j, (kk, vv) in enumerate(v.items())]
            lines.append("  }" + end)
        else:
            lines.append('  "%s": %s%s' % (k, c(v), end))
    lines.append("}")
    return "\n".join(lines) + "\n"


def plot(scenario, stats, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle, Polygon as MplPolygon
    fig, ax = plt.subplots(figsize=(16, 5.6), dpi=110)
    ax.add_patch(MplPolygon([[0, 0], [L, 0], [L, H], [0, H]], closed=True, facecolor="#8c8c86", edgecolor="none", zorder=0))
    for poly in scenario["walkable"]:
        ax.add_patch(MplPolygon(poly, closed=True, facecolor="#f4f3ee", edgecolor="none", zorder=1))
    for poly in scenario["obstacles"]:
        ax.add_patch(MplPolygon(poly, closed=True, facecolor="#8c8c86", edgecolor="#444", lw=0.5, zorder=2))
    colours = {c: plt.get_cmap("tab10")(i) for i, c in enumerate(CATEGORIES)}
    colours["restroom"] = "#1f3fbf"
    for p in scenario["points"]:
        pid = p["id"]
        if p["kind"] == "exit":
            ax.add_patch(MplPolygon(p["polygon"], closed=True, facecolor="#d62728", edgecolor="black", lw=0.6, zorder=3))
            x, y = centroid(p["polygon"])
            ax.annotate(pid, (x, y), ha="center", va="center", fontsize=7, fontweight="bold", zorder=6,
                        bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="#d62728", lw=0.6))
            continue
        x, y = p["position"]
        if pid.startswith("store") or pid.startswith("restroom"):
            cat = p.get("category", "restroom" if pid.startswith("restroom") else None)
            col = colours.get(cat, "#bbbbbb")
            ax.add_patch(Circle((x, y), p["radius"], facecolor=col, alpha=0.45, edgecolor=col, zorder=3))
            label = pid.replace("store-", "") if pid.startswith("store") else "WC" + pid[-1]
            ax.annotate(label, (x, y), ha="center", va="center", fontsize=5.5, zorder=5,
                        fontweight="bold" if pid.startswith("restroom") else "normal")
        else:
            ax.add_patch(Circle((x, y), p["radius"], facecolor="none", edgecolor="#555", lw=0.6, ls="--", zorder=3))
            ax.annotate(pid, (x, y + p["radius"] + 0.3), ha="center", va="bottom", fontsize=4.5, color="#333", zorder=5)
    handles = [plt.Line2D([], [], marker="o", ls="", color=colours[c], alpha=0.6, label=c) for c in CATEGORIES + ["restroom"]]
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.08), ncol=11, fontsize=7, frameon=False)
    ax.set_xlim(-2, L + 2)
    ax.set_ylim(-2, H + 2)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("mall.json: 82 stores (number, colour = category), 6 restrooms (WC), concourse waypoints (dashed), "
                 "4 entrances (red)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                 epilog="Layout and populations: see the module docstring and docs/mall.md.")
    ap.add_argument("--seed", type=int, default=2012, help="random seed (default 2012); also the scenario's seed")
    ap.add_argument("--out", default=None, help="file to write (default: scenarios/mall.json next to this script)")
    ap.add_argument("--core-only", action="store_true",
                    help="omit the Common Ground keys (category, interests, interestsPerAgent, social)")
    ap.add_argument("--probe", action="store_true", help="add a population visiting every point (validation only)")
    ap.add_argument("--plot", default=None, metavar="PNG", help="also draw the layout (needs matplotlib)")
    ap.add_argument("--stats", action="store_true", help="print group sizes and tour lengths")
    args = ap.parse_args()
    scenario, stats = build_scenario(args.seed, args.core_only, args.probe)
    check_geometry(scenario, stats["mall"])
    text = dumps(scenario)
    json.loads(text)
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios", "mall.json")
    with open(out, "w") as f:
        f.write(text)
    print(os.path.normpath(out))
    if args.stats:
        t = sorted(stats["tour lengths"])
        gs = stats["group sizes"]
        print("groups: %d, %d agents, sizes %s" % (len(gs), sum(gs), {s: gs.count(s) for s in range(2, 7)}))
        print("solo populations: %d, %d agents" % (len(stats["solo populations"]), sum(stats["solo populations"])))
        print("tour length [m]: min %.0f, median %.0f, max %.0f" % (t[0], t[len(t) // 2], t[-1]))
        starts = {}
        for p in scenario["populations"]:
            starts.setdefault(json.dumps(p["spawn"]), 0)
            starts[json.dumps(p["spawn"])] += p["groups"] * p["size"]
        print("agents per spawn:", sorted(starts.values()))
    if args.plot:
        plot(scenario, stats, args.plot)
        print(args.plot)


if __name__ == "__main__":
    sys.exit(main())
