#!/usr/bin/env python3
"""Valid glTF scenes shaped to be slow (issue 38): each is within the
2,000,000-triangle limit, yet a naive BVH, edge finder or probe spends
minutes on it. bench/RESULTS.md times `info`, `check` and `simulate` on
them; tests/test_hostile_scenes.cpp builds smaller instances in memory.

  python3 scripts/make-hostile-scenes.py OUT_DIR [--scale 1.0]

Writes OUT_DIR/<shape>.glb for every shape below, each with a sound source
(extras.sound_source, playing every step) and a camera (the listener) next
to the geometry, so that rays meet it. --scale multiplies the triangle
counts (0.1 for a quick run). Python 3 standard library only; deterministic.

  coincident-10k   10,000 copies of one quad's triangles
  coincident-100k  100,000 of them
  slivers-30k      30,000 long thin triangles through one region: every box
                   overlaps every other
  far-30k          30,000 small triangles at coordinates near 1e15
  comb-100k        a comb of 100,000 thin teeth (50,000 slabs, 2 triangles each)
  scatter-2m       2,000,000 tiny triangles scattered through a 100 m cube
"""
import array
import json
import math
import os
import random
import struct
import sys


def glb(path, positions, source_at, camera_at):
    """Writes a GLB with one mesh (non-indexed float positions: a flat list of
    x, y, z per vertex, three vertices per triangle), a source node and a
    camera node looking along -Z (the default view)."""
    pos = array.array("f", positions)
    if sys.byteorder != "little":
        pos.byteswap()
    data = pos.tobytes()
    count = len(positions) // 3
    xs, ys, zs = positions[0::3], positions[1::3], positions[2::3]
    gltf = {
        "asset": {"version": "2.0", "generator": "scripts/make-hostile-scenes.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"name": "hostile", "mesh": 0},
            {"name": "source", "translation": list(source_at),
             "extras": {"sound_source": {"category": "alarm", "max_distance": 40.0, "duration": 10.0,
                                         "interval": 10.0}}},
            {"name": "listener", "camera": 0, "translation": list(camera_at)},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.05}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
        "materials": [{"name": "concrete"}],
        "buffers": [{"byteLength": len(data)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(data)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3",
                       "min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]}],
    }
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    data += b"\0" * (-len(data) % 4)
    with open(path, "wb") as out:
        out.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(data)))
        out.write(struct.pack("<I4s", len(text), b"JSON") + text)
        out.write(struct.pack("<I4s", len(data), b"BIN\0") + data)


def coincident(n):
    quad = [-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, -2, 2, 0, 2, -2, 0, 2]  # two triangles, facing +y
    out = []
    for i in range(n // 2):
        out += quad
    return out, (0.0, 1.0, 0.0), (0.5, 2.0, 0.5)


def slivers(n):
    rng = random.Random(38)
    out = []
    for _ in range(n):
        # A long thin triangle through the middle of a 20 m cube, any direction.
        theta, phi = rng.uniform(0, math.pi), rng.uniform(0, 2 * math.pi)
        d = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
        c = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))
        a = [c[k] - 10 * d[k] for k in range(3)]
        b = [c[k] + 10 * d[k] for k in range(3)]
        w = [a[0] + 0.01, a[1] + 0.01, a[2]]
        out += a + b + w
    return out, (0.0, 0.0, 3.0), (0.0, 0.0, 5.0)


def far(n):
    rng = random.Random(39)
    base = 1e15
    out = []
    for _ in range(n):
        # Float spacing near 1e15 is 2^26 (67 million): in the file, these
        # all round onto one point, and so do the source and the listener.
        x, y, z = base + rng.uniform(0, 1e3), base + rng.uniform(0, 1e3), base + rng.uniform(0, 1e3)
        out += [x, y, z, x + 1.0, y, z, x, y + 1.0, z]
    return out, (base + 500.0, base + 500.0, base + 500.0), (base + 501.0, base + 500.0, base + 500.0)


def comb(n):
    # n teeth 1 mm apart along a 100 m spine, each a thin triangle slanted
    # 45 degrees to a tip 20 m along: every tooth's box overlaps those of
    # the 20,000 teeth beside it, though no two teeth touch.
    out = []
    for i in range(n):
        x = i * 0.001
        out += [x, 0, 0, x + 0.0005, 0, 0, x + 20.0, 20.0, 0.0]
    return out, (50.0, 5.0, 1.0), (50.0, 5.0, 3.0)


def scatter(n):
    rng = random.Random(40)
    out = []
    for _ in range(n):
        x, y, z = rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50)
        out += [x, y, z, x + 0.02, y, z, x, y + 0.02, z]
    return out, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)


SHAPES = {
    "coincident-10k": (coincident, 10_000),
    "coincident-100k": (coincident, 100_000),
    "slivers-30k": (slivers, 30_000),
    "far-30k": (far, 30_000),
    "comb-100k": (comb, 100_000),
    "scatter-2m": (scatter, 2_000_000),
}


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out_dir = sys.argv[1]
    scale = float(sys.argv[sys.argv.index("--scale") + 1]) if "--scale" in sys.argv else 1.0
    os.makedirs(out_dir, exist_ok=True)
    for name, (make, n) in SHAPES.items():
        positions, source, camera = make(max(4, int(n * scale)))
        glb(os.path.join(out_dir, name + ".glb"), positions, source, camera)
        print(f"{name}: {len(positions) // 9} triangles")


if __name__ == "__main__":
    main()
