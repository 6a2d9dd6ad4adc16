#!/usr/bin/env python3
"""Writes scenarios/museum.json: the Musse crowd-model demo (a hall, three galleries, paintings).

Kept as a generator so the geometry (walls with doorways, paintings on walls) stays consistent
when edited; the JSON it writes is what users read and run.
"""
import json
import os
import re

T = 0.3  # wall thickness [m]


def rect(x0, y0, x1, y1):
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


def ip(i, x, y, r):
    return {"id": i, "kind": "interest", "position": [x, y], "radius": r}


def painting(i, x, y, ox, oy):
    return {"id": i, "kind": "action", "position": [x, y], "radius": 1.3, "stop": True, "orientation": [ox, oy],
            "action": "look", "clip": "motions/look.bvh", "duration": 8}


obstacles = []
for (a, b) in [(0, 4), (6, 18), (20, 24)]:  # x = 16: hall | galleries A/B, doors at y 4..6 and 18..20
    obstacles.append(rect(16 - T / 2, a, 16 + T / 2, b))
for (a, b) in [(16, 23), (25, 32)]:  # y = 12: gallery A (north) | B (south), door at x 23..25
    obstacles.append(rect(a, 12 - T / 2, b, 12 + T / 2))
for (a, b) in [(0, 5), (7, 17), (19, 24)]:  # x = 32: A/B | gallery C, doors at y 5..7 and 17..19
    obstacles.append(rect(32 - T / 2, a, 32 + T / 2, b))
obstacles.append(rect(38, 11, 42, 12))  # a bench in gallery C
obstacles.append(rect(12.5, 10.5, 14, 13.5))  # a plinth in the hall

points = [
    ip("hall", 11, 17, 2.5), ip("door-a", 16, 19, 0.9), ip("door-b", 16, 5, 0.9), ip("door-ab", 24, 12, 0.9),
    ip("door-ac", 32, 18, 0.9), ip("door-bc", 32, 6, 0.9), ip("gallery-c", 40, 15, 2.5),
    painting("a1-sunflowers", 20, 22.3, 0, 1), painting("a2-night-watch", 28, 22.3, 0, 1),
    painting("a3-wave", 30.3, 15, 1, 0),
    painting("b1-water-lilies", 20, 1.7, 0, -1), painting("b2-the-kiss", 28, 1.7, 0, -1),
    painting("c1-guernica", 46.3, 19, 1, 0), painting("c2-starry-night", 40, 22.3, 0, 1),
    painting("c3-the-scream", 40, 1.7, 0, -1),
    {"id": "exit", "kind": "exit", "polygon": rect(49, 10, 51, 14)},
]
speed = lambda m, sd: {"mean": m, "sd": sd}
populations = [
    {"id": "school-class", "groups": 1, "size": 6, "spawn": {"polygon": rect(1, 14, 6, 22)},
     "goals": ["hall", "door-a", "a1-sunflowers", "a2-night-watch", "door-ac", "c1-guernica", "exit"],
     "speed": speed(1.2, 0.1), "radius": 0.2, "waitTimeout": 40},
    {"id": "family", "groups": 1, "size": 3, "start": 5, "spawn": {"polygon": rect(1, 2, 6, 8)}, "goals": ["exit"],
     "follow": {"population": "school-class", "group": 0, "mode": "permanent"},
     "speed": speed(1.2, 0.1), "radius": 0.2},
    {"id": "couples", "groups": 4, "size": 2, "start": 10, "spawn": {"polygon": rect(1, 2, 12, 8)},
     "goals": ["door-b", "b1-water-lilies", "b2-the-kiss", "door-bc", "c3-the-scream", "exit"],
     "speed": speed(1.1, 0.15), "radius": 0.2},
    {"id": "friends", "groups": 3, "size": [2, 4], "start": 20, "spawn": {"polygon": rect(1, 8, 6, 16)},
     "goals": ["hall", "door-a", "a3-wave", "door-ab", "b2-the-kiss", "door-bc", "c2-starry-night", "exit"],
     "paths": "bezier", "speed": speed(1.2, 0.15), "radius": 0.2},
    {"id": "wanderers", "groups": 3, "size": [1, 3], "start": 15, "spawn": {"polygon": rect(1, 1, 12, 23)},
     "goals": "auto", "autoNearDistance": 3, "speed": speed(1.0, 0.15), "radius": 0.2},
    {"id": "guided-tour", "groups": 1, "size": 5, "spawn": {"polygon": rect(9, 2, 14, 7)}, "goals": ["exit"],
     "guide": {"script": [{"time": 2, "position": [12, 6]}, {"time": 15, "position": [17, 5]},
                          {"time": 30, "position": [27, 3.5]}, {"time": 55, "position": [29, 4]},
                          {"time": 75, "position": [33, 6]}, {"time": 100, "position": [40, 19.5]},
                          {"time": 125, "position": [44, 18]}],
               "distance": 1.5, "release": 150},
     "speed": speed(1.1, 0.1), "radius": 0.2},
    {"id": "solo-visitors", "groups": 10, "size": [1, 2], "start": 30, "spawn": {"polygon": rect(1, 1, 12, 23)},
     "goals": ["hall", "door-b", "b1-water-lilies", "door-ab", "a2-night-watch", "door-ac", "c1-guernica", "exit"],
     "sociological": {"enabled": True, "meetDistance": 1.2, "changeGroupRate": 0.01, "followAgentRate": 0.015,
                      "followDuration": 12, "leaderChangeRate": 0.02},
     "speed": speed(1.25, 0.2), "radius": 0.2},
]
DESCRIPTION = ('A museum of three rooms joined by doors. Visitors in groups (a school class, a family, couples, friends, a guided tour, people alone) come in at the hall, stand in front of the paintings (orange discs), pass the doors (blue rings) and leave by the green exit on the right. Groups wait for their members; the tour follows its guide.')
museum = {"format": "throng/1", "name": "museum", "description": DESCRIPTION, "seed": 1997, "duration": 300,
          "walkable": [rect(0, 0, 48, 24), rect(48, 10, 51, 14)],
          "obstacles": obstacles, "points": points, "populations": populations}

s = json.dumps(museum, indent=2)
s = re.sub(r'\[\s*(-?[\d.]+),\s*(-?[\d.]+)\s*\]', r'[\1, \2]', s)
s = re.sub(r'\[\s*((?:\[-?[\d.]+, -?[\d.]+\],?\s*)+)\]', lambda m: '[' + re.sub(r'\s+', ' ', m.group(1)).strip() + ']', s)
s = re.sub(r'\[\s*((?:\[\[[^\[\]]*\]\],?\s*)+)\]',
           lambda m: '[\n    ' + re.sub(r'\],\s*\[\[', '],\n    [[', m.group(1).strip()) + '\n  ]', s)
s = re.sub(r'\{\s*"time": ([\d.]+),\s*"position": (\[[^\]]*\])\s*\}', r'{"time": \1, "position": \2}', s)
json.loads(s)
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios", "museum.json")
with open(out, "w") as f:
    f.write(s + "\n")
print(os.path.normpath(out))
