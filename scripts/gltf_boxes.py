"""Box scenes as glTF 2.0, for the small hand-made scenes of the docs and the
tests (scripts/make-corner-scene.py, tests/data/make_issue10_scenes.py).

Closed boxes with outward fronts, y up; one mesh per part, the material
name its layer. Python 3 standard library only, and deterministic: the same
parts write a byte-identical file.
"""
import base64
import json
import struct

# Corner indices of a box's faces (as tests/support/scene_builder.h), outward
# fronts, named by the way each faces.
FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (0, 4, 7, 3), (1, 2, 6, 5)]
FACE_NAMES = ["-z", "+z", "-y", "+y", "-x", "+x"]


def box(lo, hi, keep=FACE_NAMES):
    """The triangles of the box [lo, hi], only the faces named in `keep`."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    tris = []
    for name, (a, b, cc, d) in zip(FACE_NAMES, FACES):
        if name in keep:
            tris += [(c[a], c[b], c[cc]), (c[a], c[cc], c[d])]
    return tris


def write_gltf(path, parts, extra_nodes, camera, generator, note=None, part_name=lambda material, index: material):
    """Writes `parts` (a list of (material, triangles)) as one mesh each, then
    `extra_nodes` (sources, the listener's camera node) and `camera`.
    part_name(material, node index) names each part's node."""
    blob = b""
    accessors, views, meshes, nodes, materials = [], [], [], [], []
    material_index = {}
    for material, tris in parts:
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
        nodes.append({"name": part_name(material, len(nodes)), "mesh": len(meshes) - 1})
    nodes += extra_nodes
    asset = {"version": "2.0", "generator": generator}
    if note is not None:
        asset["extras"] = {"note": note}
    gltf = {
        "asset": asset,
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "cameras": [camera],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    }
    with open(path, "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
