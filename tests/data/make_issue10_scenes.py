#!/usr/bin/env python3
"""Writes the regression scenes of issue 10 (matter-aware penetration) next
to this script. Each reproduces, in a few boxes, how a real level broke the
paper's backcast; tests/test_cli.cpp runs `simulate` and `check` on them.

  issue-10-touching-brushes.gltf   collision geometry: a 0.2 m wall brush
      standing against a 0.3 m one (they touch at x = 1.2) and a floor slab
      with a trim lying on it; closed, consistently wound boxes.
  issue-10-render-mesh.gltf        the same place as a render mesh: the
      faces against the void and against other solids removed (the walls'
      far sides, the floor's underside, the trim's bottom).

Glass is not involved; layers are the material names. Python 3 standard
library only; re-running writes byte-identical files.
"""
import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# Face corner indices of a box (as tests/support/scene_builder.h), outward
# fronts: -z, +z, -y, +y, -x, +x.
FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (0, 4, 7, 3), (1, 2, 6, 5)]
NAMES = ["-z", "+z", "-y", "+y", "-x", "+x"]


def box(lo, hi, keep=NAMES):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    tris = []
    for name, (a, b, cc, d) in zip(NAMES, FACES):
        if name in keep:
            tris += [(c[a], c[b], c[cc]), (c[a], c[cc], c[d])]
    return tris


def write(name, parts, note):
    """parts: list of (material, triangles)."""
    blob = b""
    accessors, views, meshes, nodes, materials = [], [], [], [], []
    for material, tris in parts:
        data = b"".join(struct.pack("<3f", *v) for t in tris for v in t)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
        xs = [v for t in tris for v in t]
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": len(xs), "type": "VEC3",
                          "min": [min(v[i] for v in xs) for i in range(3)],
                          "max": [max(v[i] for v in xs) for i in range(3)]})
        blob += data
        materials.append({"name": material})
        meshes.append({"primitives": [{"attributes": {"POSITION": len(accessors) - 1},
                                       "material": len(materials) - 1}]})
        nodes.append({"name": material, "mesh": len(meshes) - 1})
    nodes.append({"name": "speaker", "translation": [0.0, 1.5, 0.0],
                  "extras": {"sound_source": {"category": "voice", "color": [1.0, 0.6, 0.0]}}})
    nodes.append({"name": "listener", "camera": 0, "translation": [3.0, 1.5, 0.0]})
    gltf = {
        "asset": {"version": "2.0", "generator": "tests/data/make_issue10_scenes.py", "extras": {"note": note}},
        "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
        "materials": materials, "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.05}}],
        "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    }
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


def main():
    wall_a = ((1.0, 0.0, -3.0), (1.2, 3.0, 3.0))
    wall_b = ((1.2, 0.0, -3.0), (1.5, 3.0, 3.0))
    floor = ((-4.0, -0.3, -4.0), (4.0, 0.0, 4.0))
    trim = ((-1.0, 0.0, -1.0), (0.0, 0.05, 1.0))
    write("issue-10-touching-brushes.gltf",
          [("concrete", box(*wall_a) + box(*wall_b) + box(*floor)), ("wood", box(*trim))],
          "collision brushes: wall brushes touching at x = 1.2, a trim lying on the floor")
    write("issue-10-render-mesh.gltf",
          [("concrete", box(*wall_a, keep=["-x", "+y", "-z", "+z"]) + box(*wall_b, keep=["+y", "-z", "+z"])
            + box(*floor, keep=["+y"])),
           ("wood", box(*trim, keep=["+x", "-x", "+y", "-z", "+z"]))],
          "render mesh: faces against the void and against other solids removed")


if __name__ == "__main__":
    main()
