#!/usr/bin/env python3
"""Writes scenarios/gallery.gltf, the example throng world file (docs/world-files.md).

A JSON glTF 2.0 file with base64 buffers, standard library only. glTF is Y-up: a ground point
(x, y) of the scenario is the glTF position (x, height, -y). The gallery: an L-shaped floor made of
two overlapping slabs (their union is the walkable area), three plinths and a wall (obstacles),
interest points at paintings, a bench action point, an exit, and two crowds (autonomous visitors,
a guided tour). Usage: scripts/make_gallery_gltf.py [output path]
"""
import base64
import json
import math
import struct
import sys
from pathlib import Path


def ground(x, y, h=0.0):
    """glTF translation of the ground point (x, y) at height h."""
    return [x, h, -y]


def yaw_quaternion(facing_x, facing_y):
    """Rotation about +Y turning the node's local +Z (glTF forward) to face ground direction (fx, fy)."""
    # Local +Z maps to ground (0, -1); the yaw angle a about Y maps +Z to (sin a, 0, cos a) = ground (sin a, -cos a).
    a = math.atan2(facing_x, -facing_y)
    return [0.0, math.sin(a / 2), 0.0, math.cos(a / 2)]


class Builder:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors, self.meshes = [], [], []

    def _view(self, blob, target):
        while len(self.data) % 4:
            self.data.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(blob), "target": target})
        self.data += blob
        return len(self.views) - 1

    def mesh(self, name, vertices, triangles):
        pos = b"".join(struct.pack("<3f", *v) for v in vertices)
        idx = b"".join(struct.pack("<3H", *t) for t in triangles)
        lo = [min(v[i] for v in vertices) for i in range(3)]
        hi = [max(v[i] for v in vertices) for i in range(3)]
        self.accessors.append({"bufferView": self._view(pos, 34962), "componentType": 5126, "count": len(vertices),
                               "type": "VEC3", "min": lo, "max": hi})
        self.accessors.append({"bufferView": self._view(idx, 34963), "componentType": 5123,
                               "count": 3 * len(triangles), "type": "SCALAR"})
        n = len(self.accessors)
        self.meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": n - 2}, "indices": n - 1}]})
        return len(self.meshes) - 1


def slab(x0, y0, x1, y1, h=0.0):
    """A horizontal rectangle on the ground (two triangles, facing up)."""
    v = [ground(x0, y0, h), ground(x1, y0, h), ground(x1, y1, h), ground(x0, y1, h)]
    return v, [(0, 1, 2), (0, 2, 3)]


def unit_box():
    """A cube from -1 to 1 (scale the node to size it)."""
    v = [[x, y, z] for x in (-1, 1) for y in (0, 2) for z in (-1, 1)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return v, [t for a, b, c, d in faces for t in ((a, b, c), (a, c, d))]


def write_gltf(out, b, nodes, scene_name, scene_extras, generator, looks=None):
    """Writes a .gltf with every node in its one scene, the builder's meshes and one embedded buffer;
    `looks` (materials, textures, images, samplers), when given, go after the meshes."""
    gltf = {
        "asset": {"version": "2.0", "generator": "throng " + generator},
        "scene": 0,
        "scenes": [{"name": scene_name, "nodes": list(range(len(nodes))), "extras": {"throng": scene_extras}}],
        "nodes": nodes,
        "meshes": b.meshes,
        **(looks or {}),
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{"byteLength": len(b.data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(b.data)).decode()}],
    }
    out.write_text(json.dumps(gltf, indent=1) + "\n")
    print(f"wrote {out}")


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "scenarios" / "gallery.gltf"
    b = Builder()
    hall = b.mesh("hall", *slab(0, 0, 30, 12))
    wing = b.mesh("wing", *slab(20, 10, 30, 25))
    box = b.mesh("box", *unit_box())
    nodes = [
        {"name": "walkable_hall", "mesh": hall},
        {"name": "walkable_wing", "mesh": wing},
        {"name": "obstacle_plinth_1", "mesh": box, "translation": ground(8, 6), "scale": [0.6, 1.0, 0.6]},
        {"name": "obstacle_plinth_2", "mesh": box, "translation": ground(14, 6), "scale": [0.6, 1.0, 0.6]},
        {"name": "obstacle_wall", "mesh": box, "translation": ground(25, 17.5), "scale": [0.2, 1.5, 3.0],
         "rotation": yaw_quaternion(1, 1)},
        {"name": "interest:painting_a", "translation": ground(5, 11), "extras": {"throng": {"radius": 1.0}}},
        {"name": "interest:painting_b", "translation": ground(17, 1), "extras": {"throng": {"radius": 1.0}}},
        {"name": "interest:sculpture", "translation": ground(25, 22), "extras": {"throng": {"radius": 1.5}}},
        {"name": "action:bench", "translation": ground(11, 9), "rotation": yaw_quaternion(0, -1),
         "extras": {"throng": {"action": "sit", "duration": 8, "radius": 0.6, "category": "rest"}}},
        {"name": "exit:door", "translation": ground(29, 24), "extras": {"throng": {"radius": 1.0}}},
        {"name": "crowd:visitors", "translation": ground(3, 6), "scale": [2.0, 1.0, 4.0],
         "extras": {"throng": {"groups": 8, "size": [1, 3], "goals": ["painting_a", "bench", "painting_b", "sculpture", "door"],
                               "speed": {"mean": 1.2, "sd": 0.2}}}},
        {"name": "crowd:tour", "translation": ground(15, 3), "scale": [1.5, 1.0, 1.5],
         "extras": {"throng": {"groups": 1, "size": 6, "goals": ["door"],
                               "guide": {"script": [{"time": 0, "position": [15, 3]}, {"time": 12, "position": [25, 8]},
                                                    {"time": 30, "position": [25, 21]}]}}}},
        {"name": "Lamp", "translation": [15, 4, -6]},
    ]
    write_gltf(out, b, nodes, "gallery", {"name": "gallery", "seed": 3, "duration": 120}, "scripts/make_gallery_gltf.py")


if __name__ == "__main__":
    main()
