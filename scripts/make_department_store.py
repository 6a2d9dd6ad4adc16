#!/usr/bin/env python3
"""Writes scenarios/department_store.json: a two-storey store where shoppers choose by themselves
between the escalators, the lift and the stairs (docs/crowd-model.md, "Choosing a lift, an
escalator or the stairs").

The ground floor and the upper floor are 40 x 30 m, 4.5 m apart; the upper floor has a 12 x 10 m
void in its middle, which two escalators cross (one up, one down, 25 degrees) beside a 3 m wide
stair (29 degrees, its foot on the ground floor to the east, its head on the upper floor to the
west); the lift stands in the north-west corner and serves both floors. Four shops on each floor,
the street door on the south side. No population names a stop among its goals: most groups ride,
each by what it finds quickest (walking, waiting and riding time), and families ride the lift
together; the populations' default share of climbers (stairs.climb) take the stairs when those
are quicker.

Run: python3 scripts/make_department_store.py [OUT] (default scenarios/department_store.json).
"""
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
UP = 4.5  # storey height [m]
STAIR_RUN = UP / 0.5543  # a 29 degree stair (tan 29 = 0.5543): 8.1 m long on the plan


def rect(x0, y0, x1, y1):
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


class Terrain:
    def __init__(self):
        self.vertices, self.walkable, self.obstacles = [], [], []

    def quad(self, corners):
        """A walkable quad: four [x, y, z] corners in order, as two triangles."""
        base = len(self.vertices)
        self.vertices.extend([list(c) for c in corners])
        self.walkable += [[base, base + 1, base + 2], [base, base + 2, base + 3]]

    def floor(self, x0, y0, x1, y1, z):
        self.quad([(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)])

    def rail(self, xa, za, xb, zb, y0, y1, height):
        """A solid railing from (xa, za) to (xb, zb) along x, between y0 and y1, `height` tall: a
        sloped box of 12 obstacle triangles."""
        base = len(self.vertices)
        for x, z in ((xa, za), (xb, zb)):
            self.vertices += [[x, y0, z], [x, y1, z], [x, y1, z + height], [x, y0, z + height]]
        faces = [(0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (3, 2, 6, 7), (0, 3, 7, 4), (1, 5, 6, 2)]
        for a, b, c, d in faces:
            self.obstacles += [[base + a, base + b, base + c], [base + a, base + c, base + d]]


def point(pid, kind, polygon, height, **extra):
    p = {"id": pid, "kind": kind, "polygon": polygon, "height": height}
    p.update(extra)
    return p


def build():
    t = Terrain()
    t.floor(0, 0, 40, 30, 0.0)                 # ground floor
    # Upper floor round the void x 14-26, y 10-20.
    t.floor(0, 0, 40, 10, UP)
    t.floor(0, 20, 40, 30, UP)
    t.floor(0, 10, 14, 20, UP)
    t.floor(26, 10, 40, 20, UP)
    # The stair across the void's south side (y 10.5-13.5): its foot on the ground at x 22.1, its
    # head on the upper floor's west part at x 14.
    t.quad([(14 + STAIR_RUN, 10.5, 0.0), (14 + STAIR_RUN, 13.5, 0.0), (14, 13.5, UP), (14, 10.5, UP)])
    # Its railings, 1 m tall: the stair is entered at its foot, not from the side where its first
    # steps are low enough to step onto (there, people going up cut the corner into those coming
    # down, and two stood 60 s face to face).
    for y0, y1 in ((10.4, 10.5), (13.5, 13.6)):
        t.rail(14 + STAIR_RUN, 0.0, 14, UP, y0, y1, 1.0)

    points = [
        point("street", "exit", rect(18, 0, 22, 1), 0.0),
        point("entrance", "interest", rect(16, 2, 24, 6), 0.0),
        # Ground-floor shops.
        point("food-hall", "interest", rect(2, 2, 8, 8), 0.0),
        point("pharmacy", "interest", rect(32, 2, 38, 8), 0.0),
        point("books", "interest", rect(2, 22, 8, 28), 0.0),
        point("shoes", "interest", rect(32, 22, 38, 28), 0.0),
        # Upper-floor shops.
        point("fashion", "interest", rect(2, 2, 8, 8), UP),
        point("toys", "interest", rect(32, 2, 38, 8), UP),
        point("electronics", "interest", rect(32, 22, 38, 28), UP),
        point("cafe", "interest", rect(16, 24, 24, 28), UP),
        # Transport stops: people step on at a stop's position (its centre).
        point("up-foot", "interest", rect(17, 14, 19, 16), 0.0),
        point("up-head", "interest", rect(26.5, 14, 28.5, 16), UP),
        point("down-head", "interest", rect(11.5, 17, 13.5, 19), UP),
        point("down-foot", "interest", rect(21, 17, 23, 19), 0.0),
        point("lift-ground", "interest", rect(1, 26, 4, 29), 0.0),
        point("lift-upper", "interest", rect(1, 26, 4, 29), UP),
    ]
    transports = [
        {"id": "escalator-up", "kind": "escalator", "stops": ["up-foot", "up-head"]},
        {"id": "escalator-down", "kind": "escalator", "stops": ["down-head", "down-foot"]},
        {"id": "lift", "kind": "elevator", "stops": ["lift-ground", "lift-upper"], "capacity": 8},
    ]
    entrance = {"polygon": rect(16, 2, 24, 6), "height": 0.0}
    upstairs = {"polygon": rect(10, 21, 30, 23.5), "height": UP}
    populations = [
        {"id": "to-fashion", "groups": 60, "size": [1, 2], "spawn": entrance, "start": 0,
         "goals": ["food-hall", "fashion", "street"], "speed": {"mean": 1.34, "sd": 0.26}},
        {"id": "to-electronics", "groups": 60, "size": [1, 2], "spawn": entrance, "start": 20,
         "goals": ["electronics", "books", "street"], "speed": {"mean": 1.34, "sd": 0.26}},
        {"id": "families", "groups": 12, "size": [3, 4], "spawn": entrance, "start": 10,
         "goals": ["toys", "cafe", "shoes", "street"], "speed": {"mean": 1.1, "sd": 0.15}},
        {"id": "leaving-upstairs", "groups": 60, "size": [1, 2], "spawn": upstairs, "start": 0,
         "goals": ["cafe", "pharmacy", "street"], "speed": {"mean": 1.34, "sd": 0.26}},
        {"id": "older-shoppers", "groups": 16, "size": [1, 2], "spawn": upstairs, "start": 5,
         "goals": ["fashion", "food-hall", "street"], "speed": {"mean": 0.8, "sd": 0.1, "min": 0.5, "max": 1.1}},
    ]
    return {
        "format": "throng/1",
        "name": "Department store: escalators, a lift and the stairs, chosen by the shoppers",
        "description": ("Two 40 x 30 m floors 4.5 m apart, joined by two escalators and a stair across "
                        "the void in the middle and a lift for 8 in the north-west corner. No one is "
                        "told how to change floors: most groups ride what they find quickest, counting "
                        "the queues, families ride the lift together, and about a quarter take the "
                        "stairs. Watch the queues at the escalators and the lift's batches."),
        "seed": 1,
        "duration": 600,
        "terrain": {"vertices": t.vertices, "walkable": t.walkable, "obstacles": t.obstacles},
        "points": points,
        "transports": transports,
        "populations": populations,
    }


def main(argv):
    out = argv[1] if len(argv) > 1 else os.path.join(HERE, "..", "scenarios", "department_store.json")
    text = json.dumps(build(), indent=1) + "\n"
    tmp = out + ".tmp"
    with open(tmp, "w") as f:  # then renamed: the scenario is written whole or not at all
        f.write(text)
    os.replace(tmp, out)
    print(f"wrote {os.path.relpath(out)}")


if __name__ == "__main__":
    main(sys.argv)
