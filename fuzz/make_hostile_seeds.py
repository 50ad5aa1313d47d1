#!/usr/bin/env python3
"""Seeds for fuzz_scene_loader of the level shapes that are slow to check
(issue 38; scripts/make-hostile-scenes.py writes the full-size levels):
each seed is a few kilobytes, and instances a small mesh through many
nodes, or reuses a few vertices through a long index buffer, so that the
fuzzer's mutations of a count, a node or a translation grow or bend the
shape. Writes OUT_DIR/hostile-<shape>.gltf in the fuzz input format
(fuzz/fuzz_input.h): the glTF, the part separator, then the buffer a.bin.

  python3 fuzz/make_hostile_seeds.py fuzz/corpus/fuzz_scene_loader [--scale 1.0]

  coincident  one quad drawn again and again: 250 copies by index, 16 nodes
  slivers     64 long thin triangles through one region, turned by 64 nodes
  far         100 small triangles moved near 1e15 (where floats are 2^26
              apart) by 64 nodes, and one node out at 3e38
  comb        a comb of 100 teeth 1 mm apart, laid end to end by 32 nodes

--scale multiplies the copies and nodes (the default keeps each seed, and
its check, small: the replay test runs them in every build). Python 3
standard library only; deterministic.
"""
import json
import math
import os
import random
import struct
import sys

SEPARATOR = b"\n--8<--\n"


def seed(path, vertices, indices, nodes, source_at, camera_at):
    """A glTF of one mesh (float positions, optional uint8 indices) placed by
    `nodes` (dicts of node properties, "mesh": 0 added), a sound source and a
    camera (the listener)."""
    data = struct.pack("<%df" % len(vertices), *vertices)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": len(data)}]
    count = len(vertices) // 3
    accessors = [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3"}]
    primitive = {"attributes": {"POSITION": 0}}
    if indices:
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(indices)})
        accessors.append({"bufferView": 1, "componentType": 5121, "count": len(indices), "type": "SCALAR"})
        primitive["indices"] = 1
        data += bytes(indices)
    gltf = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes) + 2))}],
        "nodes": [dict(node, mesh=0) for node in nodes] + [
            {"translation": list(source_at), "extras": {"sound_source": {"category": "alarm"}}},
            {"camera": 0, "translation": list(camera_at)},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.05}}],
        "meshes": [{"primitives": [primitive]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(data), "uri": "a.bin"}],
    }
    with open(path, "wb") as out:
        out.write(json.dumps(gltf, separators=(",", ":")).encode() + SEPARATOR + data)


def coincident(scale):
    quad = [-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2]
    return quad, [0, 1, 2, 0, 2, 3] * int(250 * scale), [{}] * int(16 * scale), (0, 1, 0), (0.5, 2, 0.5)


def slivers(scale):
    rng = random.Random(38)
    out = []
    for _ in range(64):
        theta, phi = rng.uniform(0, math.pi), rng.uniform(0, 2 * math.pi)
        d = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
        c = [rng.uniform(-1, 1) for _ in range(3)]
        a = [c[k] - 10 * d[k] for k in range(3)]
        b = [c[k] + 10 * d[k] for k in range(3)]
        out += a + b + [a[0] + 0.01, a[1] + 0.01, a[2]]
    nodes = []
    for i in range(int(64 * scale)):
        half = math.pi * i / (64 * scale) / 2  # turns about y spread over half a turn
        nodes.append({"rotation": [0, round(math.sin(half), 4), 0, round(math.cos(half), 4)]})
    return out, None, nodes, (0, 0, 3), (0, 0, 5)


def far(scale):
    rng = random.Random(39)
    out = []
    for _ in range(100):
        x, y, z = rng.uniform(0, 1e3), rng.uniform(0, 1e3), rng.uniform(0, 1e3)
        out += [x, y, z, x + 1, y, z, x, y + 1, z]
    nodes = [{"translation": [1e15 + 1000 * i, 1e15, 1e15]} for i in range(int(64 * scale))]
    nodes.append({"translation": [3e38, -3e38, 3e38]})
    return out, None, nodes, (1e15 + 500, 1e15 + 500, 1e15 + 500), (1e15 + 501, 1e15 + 500, 1e15 + 500)


def comb(scale):
    out = []
    for i in range(100):
        x = i * 0.001
        out += [x, 0, 0, x + 0.0005, 0, 0, x + 20, 20, 0]
    nodes = [{"translation": [round(0.1 * i, 3), 0, 0]} for i in range(int(32 * scale))]
    return out, None, nodes, (3, 5, 1), (3, 5, 3)


SHAPES = {"coincident": coincident, "slivers": slivers, "far": far, "comb": comb}


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out_dir = sys.argv[1]
    scale = float(sys.argv[sys.argv.index("--scale") + 1]) if "--scale" in sys.argv else 1.0
    os.makedirs(out_dir, exist_ok=True)
    for name, make in SHAPES.items():
        vertices, indices, nodes, source, camera = make(scale)
        path = os.path.join(out_dir, "hostile-" + name + ".gltf")
        seed(path, vertices, indices, nodes, source, camera)
        per_mesh = len(indices) // 3 if indices else len(vertices) // 9
        print(f"{path}: {per_mesh * len(nodes)} triangles, {os.path.getsize(path)} bytes")


if __name__ == "__main__":
    main()
