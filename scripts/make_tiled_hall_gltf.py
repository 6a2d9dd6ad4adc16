#!/usr/bin/env python3
"""Writes scenarios/tiled_hall.gltf, a small world file whose meshes have glTF materials (docs/viewer.md,
"glTF materials"): the browser viewer draws them instead of its flat floor and obstacle colours.

Standard library only; reuses make_gallery_gltf.py's builder. A 20 x 12 m hall floored with a
checker-tiled texture (an 8 x 8 PNG written here, embedded as a data: URI, repeated every 2 m), a
red carpet down the middle (a base colour, no texture), two marble plinths and a dark wooden screen
(base colours), a statue to look at, a door and a crowd of visitors. glTF is Y-up: a ground point
(x, y) is the glTF position (x, height, -y). Usage: scripts/make_tiled_hall_gltf.py [output path]
"""
import base64
import struct
import sys
import zlib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_gallery_gltf import Builder, ground, slab, unit_box, write_gltf  # noqa: E402


def png(width, height, pixel):
    """A truecolour PNG of pixel(x, y) -> (r, g, b)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    rows = b"".join(b"\x00" + b"".join(bytes(pixel(x, y)) for x in range(width)) for y in range(height))
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")


def tiles(x, y):
    """Two tiles of 4 x 4 pixels each way: warm sand and slate blue, a darker grout line."""
    if x % 4 == 0 or y % 4 == 0:
        return (96, 88, 80)
    return (214, 190, 140) if (x // 4 + y // 4) % 2 == 0 else (92, 118, 150)


class MaterialBuilder(Builder):
    """The gallery's builder plus texture coordinates and a material per mesh."""

    def textured_mesh(self, name, vertices, triangles, uvs, material):
        index = self.mesh(name, vertices, triangles)
        uv = b"".join(struct.pack("<2f", *t) for t in uvs)
        self.accessors.append({"bufferView": self._view(uv, 34962), "componentType": 5126, "count": len(uvs), "type": "VEC2"})
        primitive = self.meshes[index]["primitives"][0]
        primitive["attributes"]["TEXCOORD_0"] = len(self.accessors) - 1
        primitive["material"] = material
        return index

    def coloured_mesh(self, name, vertices, triangles, material):
        index = self.mesh(name, vertices, triangles)
        self.meshes[index]["primitives"][0]["material"] = material
        return index


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "scenarios" / "tiled_hall.gltf"
    b = MaterialBuilder()
    materials = [
        {"name": "tiles", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 0.8}},
        {"name": "carpet", "pbrMetallicRoughness": {"baseColorFactor": [0.55, 0.05, 0.08, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}},
        {"name": "marble", "pbrMetallicRoughness": {"baseColorFactor": [0.92, 0.92, 0.88, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.4}},
        {"name": "walnut", "pbrMetallicRoughness": {"baseColorFactor": [0.30, 0.18, 0.09, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.7}},
    ]
    floor_v, floor_t = slab(0, 0, 20, 12)
    floor_uv = [(v[0] / 2.0, -v[2] / 2.0) for v in floor_v]  # one texture (two tiles each way) every 2 m
    floor = b.textured_mesh("floor", floor_v, floor_t, floor_uv, 0)
    carpet = b.coloured_mesh("carpet", *slab(2, 5, 18, 7, 0.01), 1)
    marble = b.coloured_mesh("plinth", *unit_box(), 2)
    walnut = b.coloured_mesh("screen", *unit_box(), 3)
    nodes = [
        {"name": "walkable_floor", "mesh": floor},
        {"name": "walkable_carpet", "mesh": carpet},
        {"name": "obstacle_plinth_west", "mesh": marble, "translation": ground(6, 3), "scale": [0.5, 0.6, 0.5]},
        {"name": "obstacle_plinth_east", "mesh": marble, "translation": ground(14, 9), "scale": [0.5, 0.6, 0.5]},
        {"name": "obstacle_screen", "mesh": walnut, "translation": ground(10, 10.5), "scale": [3.0, 1.0, 0.1]},
        {"name": "interest:statue", "translation": ground(10, 3), "extras": {"throng": {"radius": 1.5}}},
        {"name": "exit:door", "translation": ground(19.5, 6), "extras": {"throng": {"radius": 1.0}}},
        {"name": "crowd:visitors", "translation": ground(2, 6), "scale": [1.5, 1.0, 4.0],
         "extras": {"throng": {"groups": 10, "size": [1, 3], "goals": ["statue", "door"], "speed": {"mean": 1.1, "sd": 0.2}}}},
    ]
    image = png(8, 8, tiles)
    looks = {
        "materials": materials,
        "textures": [{"source": 0, "sampler": 0}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(image).decode()}],
        # Nearest filtering keeps the tiles' edges sharp; REPEAT tiles the 2 m texture over the floor.
        "samplers": [{"magFilter": 9728, "minFilter": 9986, "wrapS": 10497, "wrapT": 10497}],
    }
    write_gltf(out, b, nodes, "tiled_hall", {"name": "tiled_hall", "seed": 5, "duration": 120},
               "scripts/make_tiled_hall_gltf.py", looks)


if __name__ == "__main__":
    main()
