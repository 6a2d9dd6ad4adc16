#!/usr/bin/env python3
"""Writes scenarios/two_floors.gltf, the example multi-level throng world (docs/world-files.md).

A JSON glTF 2.0 file with base64 buffers, standard library only (the mesh and node helpers of
make_gallery_gltf.py). glTF is Y-up: a ground point (x, y) at height h is the glTF position
(x, h, -y). The world: a 24 m x 16 m hall at height 0 and, over its back 6 m, a gallery (a
mezzanine, its top surface at 3.0 m: the hall below keeps 3 m of headroom). A straight staircase
(17 steps of 3/18 m x 0.3 m, 2 m wide, the gallery being the 18th) climbs to the gallery's front
edge on the west side; a 2 m wide ramp (14 degrees) runs along that edge on the east side to a
landing. A plinth stands on each floor. Interest points on both floors, an action point (a
balcony over the hall) upstairs, an exit on the ground floor; visitors spawn downstairs and go up
and back down to the exit, gallery guests spawn upstairs and go down.
Usage: scripts/make_two_floor_gltf.py [output path]
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True  # no __pycache__ next to the scripts
sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_gallery_gltf import Builder, ground, slab, unit_box, write_gltf, yaw_quaternion  # noqa: E402

HALL = (0.0, 0.0, 24.0, 16.0)     # x0, y0, x1, y1 at height 0
GALLERY_Y = 10.0                  # the gallery covers y in [10, 16]
GALLERY_H = 3.0                   # its walking surface [m]
STEPS = 18                        # rises from the hall to the gallery (the last one onto the gallery)
STEP_DEPTH = 0.3                  # [m]
STAIR_X = (1.0, 3.0)              # 2 m wide
RAMP = (10.0, 22.0)               # x from the bottom (height 0) to the top (3 m): 12 m run, 14 degrees
RAMP_Y = (8.0, 10.0)              # 2 m wide, along the gallery's front edge
LANDING_X = (22.0, 24.0)          # at the gallery's height, joins the ramp's top to the gallery


def quad(a, b, c, d):
    """Two triangles of the quad a, b, c, d (counter-clockwise seen from above, facing up)."""
    return [a, b, c, d], [(0, 1, 2), (0, 2, 3)]


def staircase():
    """Each step's top as a walkable quad (no risers: the steps' tops are what people walk on)."""
    vertices, triangles = [], []
    rise = GALLERY_H / STEPS
    for k in range(1, STEPS):  # step k at height k * rise; the gallery is the last one
        y1 = GALLERY_Y - (STEPS - 1 - k) * STEP_DEPTH
        v, t = slab(STAIR_X[0], y1 - STEP_DEPTH, STAIR_X[1], y1, k * rise)
        triangles += [(a + len(vertices), b + len(vertices), c + len(vertices)) for a, b, c in t]
        vertices += v
    return vertices, triangles


def ramp():
    x0, x1 = RAMP
    y0, y1 = RAMP_Y
    return quad(ground(x0, y0, 0.0), ground(x1, y0, GALLERY_H), ground(x1, y1, GALLERY_H), ground(x0, y1, 0.0))


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "scenarios" / "two_floors.gltf"
    b = Builder()
    hall = b.mesh("hall", *slab(*HALL))
    gallery = b.mesh("gallery", *slab(HALL[0], GALLERY_Y, HALL[2], HALL[3], GALLERY_H))
    stairs = b.mesh("stairs", *staircase())
    ramp_mesh = b.mesh("ramp", *ramp())
    landing = b.mesh("landing", *slab(LANDING_X[0], RAMP_Y[0], LANDING_X[1], RAMP_Y[1], GALLERY_H))
    box = b.mesh("box", *unit_box())
    up = GALLERY_H
    nodes = [
        {"name": "walkable_hall", "mesh": hall},
        {"name": "walkable_gallery", "mesh": gallery},
        {"name": "walkable_stairs", "mesh": stairs},
        {"name": "walkable_ramp", "mesh": ramp_mesh},
        {"name": "walkable_landing", "mesh": landing},
        # Plinths: 1.2 m x 1.2 m, 1 m high, one on each floor.
        {"name": "obstacle_plinth_hall", "mesh": box, "translation": ground(8, 4), "scale": [0.6, 0.5, 0.6]},
        {"name": "obstacle_plinth_gallery", "mesh": box, "translation": ground(12, 13.5, up), "scale": [0.6, 0.5, 0.6]},
        {"name": "interest:mosaic", "translation": ground(14, 4), "extras": {"throng": {"radius": 1.0}}},
        {"name": "interest:painting_west", "translation": ground(5, 15, up), "extras": {"throng": {"radius": 1.0}}},
        {"name": "interest:painting_east", "translation": ground(19, 15, up), "extras": {"throng": {"radius": 1.0}}},
        {"name": "action:balcony", "translation": ground(12, 11, up), "rotation": yaw_quaternion(0, -1),
         "extras": {"throng": {"action": "look", "duration": 5, "radius": 0.8}}},
        {"name": "exit:door", "translation": ground(23, 1), "extras": {"throng": {"radius": 1.0}}},
        {"name": "crowd:visitors", "translation": ground(4, 2), "scale": [2.0, 1.0, 1.5],
         "extras": {"throng": {"groups": 6, "size": [1, 3],
                               "goals": ["mosaic", "painting_west", "balcony", "painting_east", "door"],
                               "speed": {"mean": 1.3, "sd": 0.15}}}},
        {"name": "crowd:gallery_guests", "translation": ground(17, 13, up), "scale": [2.0, 1.0, 1.5],
         "extras": {"throng": {"groups": 4, "size": [1, 2], "goals": ["mosaic", "door"],
                               "speed": {"mean": 1.2, "sd": 0.15}}}},
        {"name": "Lamp", "translation": [12, 2.8, -5]},
    ]
    about = ("A two-storey hall: visitors come in on the ground floor, go up the stairs or the ramp to the "
             "gallery to look at its two paintings, come back down past the mosaic and leave by the door. "
             "In the plan view those upstairs have a white rim; the orbit view shows both floors.")
    write_gltf(out, b, nodes, "two floors", {"name": "two floors", "seed": 5, "duration": 120, "description": about},
               "scripts/make_two_floor_gltf.py")


if __name__ == "__main__":
    main()
