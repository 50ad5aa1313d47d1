#!/usr/bin/env python3
"""Writes docs/pictures/corner.gltf: an L-shaped corridor for the diffraction
pictures (docs/model.md#diffraction, README "Sound round corners").

Leg one runs along +x (x 0..10, z 0..2.5), leg two along +z from its end
(x 7.5..10, z 2.5..12); 3 m high between a floor and a ceiling slab. The
solid block between the legs has its convex corner edge upright at
x = 7.5, z = 2.5; its top and bottom stand on the slabs, so only that
upright edge (and the walls' ends) is exposed. A voice plays in
leg one; the camera (the listener) stands in leg two looking back towards
the corner, out of the source's sight. Closed boxes, outward fronts, y up.
Python 3 standard library only; re-running writes a byte-identical file.
"""
import base64
import json
import os
import struct

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "pictures", "corner.gltf")

# Corner indices of a box's faces, outward fronts: -z, +z, -y, +y, -x, +x.
FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (0, 4, 7, 3), (1, 2, 6, 5)]


def box(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    tris = []
    for a, b, cc, d in FACES:
        tris += [(c[a], c[b], c[cc]), (c[a], c[cc], c[d])]
    return tris


PARTS = [
    ("concrete", box((-0.3, -0.3, -0.3), (10.3, 0.0, 12.3))),   # floor slab
    ("concrete", box((-0.3, 3.0, -0.3), (10.3, 3.3, 12.3))),    # ceiling slab
    ("brick", box((-0.3, 0.0, 2.5), (7.5, 3.0, 12.3))),         # the block between the legs
    ("brick", box((-0.3, 0.0, -0.3), (10.3, 3.0, 0.0))),        # leg one's outer wall
    ("brick", box((10.0, 0.0, 0.0), (10.3, 3.0, 12.3))),        # the outer corner's wall
    ("brick", box((-0.3, 0.0, 0.0), (0.0, 3.0, 2.5))),          # leg one's end
    ("brick", box((7.5, 0.0, 12.0), (10.0, 3.0, 12.3))),        # leg two's end
]


def main():
    blob = b""
    accessors, views, meshes, nodes, materials = [], [], [], [], []
    material_index = {}
    for material, tris in PARTS:
        if material not in material_index:
            material_index[material] = len(materials)
            materials.append({"name": material})
        data = b"".join(struct.pack("<3f", *v) for t in tris for v in t)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
        xs = [v for t in tris for v in t]
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": len(xs), "type": "VEC3",
                          "min": [min(v[i] for v in xs) for i in range(3)],
                          "max": [max(v[i] for v in xs) for i in range(3)]})
        blob += data
        meshes.append({"primitives": [{"attributes": {"POSITION": len(accessors) - 1},
                                       "material": material_index[material]}]})
        nodes.append({"name": "%s-%d" % (material, len(nodes)), "mesh": len(meshes) - 1})
    nodes.append({"name": "voice", "translation": [3.0, 1.6, 1.25],
                  "extras": {"sound_source": {"category": "voice", "max_distance": 30.0}}})
    # glTF cameras look along -z: from leg two back towards the corner.
    nodes.append({"name": "listener", "camera": 0, "translation": [9.6, 1.7, 9.0]})
    gltf = {
        "asset": {"version": "2.0", "generator": "scripts/make-corner-scene.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.05, "zfar": 100.0,
                                                            "aspectRatio": 1.7777778}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    }
    with open(OUT, "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
