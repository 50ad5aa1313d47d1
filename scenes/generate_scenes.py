#!/usr/bin/env python3
"""Writes soundpaint's demo scenes next to this script (or into --out DIR):
closed_room.gltf (and the same room as closed_room.glb), two_rooms.gltf, and
level.gltf + level.bin. With --big-level DIR it writes only level_big.gltf +
level_big.bin into DIR: the same level (rooms, sources, listener) with finely
tessellated columns, about 250k triangles, for the benchmarks; it is never
committed (scripts/run-benchmarks.sh writes it into its build directory).

Conventions (what the simulation and its tests rely on):
  * glTF 2.0, metres, +Y up, right-handed. Floors have their top at y = 0.
  * Every wall, floor, ceiling and piece of furniture is a closed solid: an
    axis-aligned box (8 corners, 12 triangles) or a capped cylinder, wound
    counter-clockwise seen from outside (outward normals). Solids touch but
    never overlap, and each has real thickness, because a penetrating ray
    measures the thickness from its entry face to the exit face (SPEC 1.3).
    Openings (doors, windows) are gaps between boxes, never holes in a face.
    Every solid is at most 0.3 m thick, within the default W_max of 0.5 m.
  * The acoustic layer of a triangle is its material's name (concrete, brick,
    wood, glass, metal, carpet), except where a node sets
    extras.acoustic_layer (two_rooms.gltf's dividing wall: art material
    "oak_veneer", acoustic layer "wood").
  * Sound sources are nodes with extras.sound_source (SPEC 1.1 fields); their
    position is the node's world translation. The camera node is the listener;
    glTF cameras look down their local -Z axis.
  * Deterministic: no randomness, fixed key order, vertex data rounded to
    float32 once, so re-running writes byte-identical files.

Python 3 standard library only.
"""

import argparse
import base64
import colorsys
import json
import math
import os
import struct

# ---------------------------------------------------------------------------
# Solids


class Solids:
    """Closed solids grouped by material, ready to become one glTF mesh.
    Each solid is also kept as a Shape, for the generator's self-checks."""

    def __init__(self):
        self.by_material = {}  # name -> (positions, indices); dicts keep insertion order
        self.shapes = []

    def _begin(self, material):
        positions, indices = self.by_material.setdefault(material, ([], []))
        return positions, indices, len(positions), len(indices)

    def box(self, material, lo, hi):
        assert all(h - l > 1e-6 for l, h in zip(lo, hi)), ("degenerate box", lo, hi)
        positions, indices, base, first = self._begin(material)
        (x0, y0, z0), (x1, y1, z1) = lo, hi
        positions += [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
                      (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
        # Quads (a, b, c, d) counter-clockwise seen from outside.
        for a, b, c, d in ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (0, 4, 7, 3), (1, 2, 6, 5)):
            indices += [base + a, base + b, base + c, base + a, base + c, base + d]
        self.shapes.append(Shape(material, first, len(indices), tuple(lo), tuple(hi), None))

    def cylinder(self, material, cx, cz, radius, y0, y1, segments, rings):
        """Vertical capped cylinder, `rings` bands high, `segments` around."""
        positions, indices, base, first = self._begin(material)
        for k in range(rings + 1):
            y = y0 + (y1 - y0) * k / rings
            for j in range(segments):
                a = 2.0 * math.pi * j / segments
                positions.append((cx + radius * math.cos(a), y, cz + radius * math.sin(a)))

        def ring(k, j):
            return base + k * segments + j % segments

        for k in range(rings):
            for j in range(segments):
                # (up, tangent) order gives the outward normal (cos a, 0, sin a).
                indices += [ring(k, j), ring(k + 1, j), ring(k + 1, j + 1),
                            ring(k, j), ring(k + 1, j + 1), ring(k, j + 1)]
        bottom, top = len(positions), len(positions) + 1
        positions += [(cx, y0, cz), (cx, y1, cz)]
        for j in range(segments):
            indices += [bottom, ring(0, j), ring(0, j + 1), top, ring(rings, j + 1), ring(rings, j)]
        self.shapes.append(Shape(material, first, len(indices), (cx - radius, y0, cz - radius),
                                 (cx + radius, y1, cz + radius), radius))

    def contains(self, p, margin=0.0):
        """True if point p lies inside (or within `margin` of) any solid."""
        return any(shape.contains(p, margin) for shape in self.shapes)

    def check(self):
        """Every triangle is non-degenerate and faces away from its (convex)
        solid's centre, i.e. the winding is outward."""
        for shape in self.shapes:
            positions, indices = self.by_material[shape.material]
            centre = tuple((l + h) / 2 for l, h in zip(shape.lo, shape.hi))
            for t in range(shape.first, shape.end, 3):
                a, b, c = (positions[i] for i in indices[t:t + 3])
                centroid = tuple((a[i] + b[i] + c[i]) / 3 for i in range(3))
                assert dot(cross(sub(b, a), sub(c, a)), sub(centroid, centre)) > 1e-9, ("inward face", shape)


class Shape:
    def __init__(self, material, first, end, lo, hi, radius):
        self.material, self.first, self.end = material, first, end  # its slice of the material's indices
        self.lo, self.hi, self.radius = lo, hi, radius  # bounds; radius: None for a box

    def contains(self, p, margin):
        if not all(self.lo[i] - margin <= p[i] <= self.hi[i] + margin for i in range(3)):
            return False
        if self.radius is None:
            return True
        cx, cz = (self.lo[0] + self.hi[0]) / 2, (self.lo[2] + self.hi[2]) / 2
        return math.hypot(p[0] - cx, p[2] - cz) <= self.radius + margin


def check_disjoint(*groups):
    """No two solids share interior volume (touching faces are fine);
    cylinders count as their bounding boxes."""
    shapes = [shape for solids in groups for shape in solids.shapes]
    eps = 1e-6
    for i, a in enumerate(shapes):
        for b in shapes[i + 1:]:
            overlap = all(a.lo[k] < b.hi[k] - eps and b.lo[k] < a.hi[k] - eps for k in range(3))
            assert not overlap, ("overlapping solids", (a.lo, a.hi), (b.lo, b.hi))


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(v):
    length = math.sqrt(dot(v, v))
    return (v[0] / length, v[1] / length, v[2] / length)


def look_rotation(forward):
    """Unit quaternion [x, y, z, w] turning the camera's -Z towards `forward`
    without roll: yaw about +Y, then pitch about the camera's X."""
    f = normalize(forward)
    yaw = math.atan2(-f[0], -f[2])
    pitch = math.asin(f[1])
    sy, cy = math.sin(yaw / 2), math.cos(yaw / 2)
    sp, cp = math.sin(pitch / 2), math.cos(pitch / 2)
    return [round(c, 6) for c in (cy * sp, sy * cp, -sy * sp, cy * cp)]


# ---------------------------------------------------------------------------
# glTF writing

# Base colours for rendering; the names are the acoustic layers.
MATERIAL_COLOURS = {
    "concrete": (0.55, 0.55, 0.53), "brick": (0.62, 0.27, 0.18), "wood": (0.55, 0.38, 0.2),
    "oak_veneer": (0.6, 0.44, 0.26), "glass": (0.6, 0.8, 0.9), "metal": (0.7, 0.72, 0.75),
    "carpet": (0.3, 0.22, 0.4),
}


class GltfWriter:
    def __init__(self):
        self.doc = {
            "asset": {"version": "2.0", "generator": "soundpaint scenes/generate_scenes.py"},
            "scene": 0,
            "scenes": [{"name": "Scene", "nodes": []}],
            "nodes": [], "meshes": [], "materials": [], "cameras": [],
            "accessors": [], "bufferViews": [], "buffers": [],
        }
        self.bin = bytearray()
        self.materials = {}
        self.mesh_triangles = []
        self.triangles = 0  # in the world: a mesh counts once per node using it
        self.sources = 0

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data), "target": target}
        self.bin += data
        self.doc["bufferViews"].append(view)
        return len(self.doc["bufferViews"]) - 1

    def _accessor(self, accessor):
        self.doc["accessors"].append(accessor)
        return len(self.doc["accessors"]) - 1

    def material(self, name):
        if name not in self.materials:
            r, g, b = MATERIAL_COLOURS[name]
            alpha = 0.35 if name == "glass" else 1.0
            mat = {"name": name, "pbrMetallicRoughness": {
                "baseColorFactor": [r, g, b, alpha], "metallicFactor": 0.9 if name == "metal" else 0.0,
                "roughnessFactor": 0.2 if name in ("glass", "metal") else 0.8}}
            if alpha < 1.0:
                mat["alphaMode"] = "BLEND"
            self.doc["materials"].append(mat)
            self.materials[name] = len(self.doc["materials"]) - 1
        return self.materials[name]

    def mesh(self, name, solids):
        primitives = []
        for material, (positions, indices) in solids.by_material.items():
            data = b"".join(struct.pack("<3f", *p) for p in positions)
            stored = [struct.unpack_from("<3f", data, 12 * i) for i in range(len(positions))]
            pos = self._accessor({
                "bufferView": self._view(data, 34962), "componentType": 5126, "count": len(positions),
                "type": "VEC3", "min": [min(p[i] for p in stored) for i in range(3)],
                "max": [max(p[i] for p in stored) for i in range(3)]})
            wide = len(positions) > 0xFFFF
            idx_data = struct.pack("<%d%s" % (len(indices), "I" if wide else "H"), *indices)
            idx = self._accessor({"bufferView": self._view(idx_data, 34963),
                                  "componentType": 5125 if wide else 5123, "count": len(indices),
                                  "type": "SCALAR"})
            primitives.append({"attributes": {"POSITION": pos}, "indices": idx,
                               "material": self.material(material), "mode": 4})
        self.mesh_triangles.append(sum(len(ix) // 3 for _, ix in solids.by_material.values()))
        self.doc["meshes"].append({"name": name, "primitives": primitives})
        return len(self.doc["meshes"]) - 1

    def node(self, node, parent=None):
        self.doc["nodes"].append(node)
        index = len(self.doc["nodes"]) - 1
        if parent is None:
            self.doc["scenes"][0]["nodes"].append(index)
        else:
            self.doc["nodes"][parent].setdefault("children", []).append(index)
        if "mesh" in node:
            self.triangles += self.mesh_triangles[node["mesh"]]
        if "sound_source" in node.get("extras", {}):
            self.sources += 1
        return index

    def camera(self, name, position, forward, parent=None):
        self.doc["cameras"].append({"name": name, "type": "perspective", "perspective": {
            "yfov": 0.9, "znear": 0.05, "zfar": 200.0, "aspectRatio": round(16 / 9, 6)}})
        return self.node({"name": name, "camera": len(self.doc["cameras"]) - 1,
                          "translation": list(position), "rotation": look_rotation(forward)}, parent)

    def write(self, path, container):
        """container: "embedded" (base64 data URI), "external" (.bin beside
        the .gltf) or "glb" (binary glTF with a BIN chunk)."""
        doc = dict(self.doc)
        for key in ("cameras", "materials"):
            if not doc[key]:
                del doc[key]
        doc["buffers"] = [{"byteLength": len(self.bin)}]
        if container == "embedded":
            doc["buffers"][0]["uri"] = ("data:application/octet-stream;base64,"
                                        + base64.b64encode(bytes(self.bin)).decode("ascii"))
        elif container == "external":
            doc["buffers"][0]["uri"] = os.path.splitext(os.path.basename(path))[0] + ".bin"
            with open(os.path.join(os.path.dirname(path), doc["buffers"][0]["uri"]), "wb") as f:
                f.write(self.bin)
        if container == "glb":
            text = json.dumps(doc, separators=(",", ":")).encode("ascii")
            text += b" " * (-len(text) % 4)
            body = bytes(self.bin) + b"\0" * (-len(self.bin) % 4)
            with open(path, "wb") as f:
                f.write(struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(text) + 8 + len(body)))
                f.write(struct.pack("<I4s", len(text), b"JSON") + text)
                f.write(struct.pack("<I4s", len(body), b"BIN\0") + body)
        else:
            with open(path, "w", encoding="ascii", newline="\n") as f:
                json.dump(doc, f, indent=1)
                f.write("\n")
        print("%-18s %6d triangles, %2d sources, %d bytes of buffer"
              % (os.path.basename(path), self.triangles, self.sources, len(self.bin)))


def source(name, position, colour, category, **fields):
    extras = {"color": [round(c, 3) for c in colour], "category": category}
    extras.update(fields)
    return {"name": name, "translation": [round(c, 4) for c in position], "extras": {"sound_source": extras}}


# ---------------------------------------------------------------------------
# Scenes


def closed_room(out_dir):
    """One room, inner 6 x 3 x 5 m (x in [-3,3], z in [-2.5,2.5]), 0.2 m concrete shell."""
    t = 0.2
    shell = Solids()
    shell.box("concrete", (-3 - t, -t, -2.5 - t), (3 + t, 0, 2.5 + t))      # floor
    shell.box("concrete", (-3 - t, 3, -2.5 - t), (3 + t, 3 + t, 2.5 + t))   # ceiling
    shell.box("concrete", (-3 - t, 0, -2.5 - t), (3 + t, 3, -2.5))          # north, full length
    shell.box("concrete", (-3 - t, 0, 2.5), (3 + t, 3, 2.5 + t))            # south, full length
    shell.box("concrete", (-3 - t, 0, -2.5), (-3, 3, 2.5))                  # west, between
    shell.box("concrete", (3, 0, -2.5), (3 + t, 3, 2.5))                    # east, between
    shell.check()
    check_disjoint(shell)
    gltf = GltfWriter()
    gltf.node({"name": "Room", "mesh": gltf.mesh("Room", shell)})
    speaker = (1.5, 1.2, -1.0)
    assert not shell.contains(speaker)
    gltf.node(source("Speaker", speaker, (1.0, 0.55, 0.1), "voice", max_distance=20.0))
    gltf.camera("Listener", (-2.2, 1.6, 1.8), sub(speaker, (-2.2, 1.6, 1.8)))
    gltf.write(os.path.join(out_dir, "closed_room.gltf"), "embedded")
    gltf.write(os.path.join(out_dir, "closed_room.glb"), "glb")


def two_rooms(out_dir):
    """Rooms A (x < 0) and B (x > 0), each 5 x 3 x 5 m inside, split by a
    0.1 m wooden wall with a 1 x 2 m door at z in [-0.5, 0.5]."""
    h, t, d = 3.0, 0.2, 0.05  # height, outer thickness, half the divider's thickness
    x_out = 5.0 + d           # inner face of the end walls
    shell = Solids()
    shell.box("concrete", (-x_out - t, -t, -2.5 - t), (x_out + t, 0, 2.5 + t))    # floor
    shell.box("concrete", (-x_out - t, h, -2.5 - t), (x_out + t, h + t, 2.5 + t))  # ceiling
    shell.box("brick", (-x_out - t, 0, -2.5 - t), (x_out + t, h, -2.5))            # long walls
    shell.box("brick", (-x_out - t, 0, 2.5), (x_out + t, h, 2.5 + t))
    shell.box("concrete", (-x_out - t, 0, -2.5), (-x_out, h, 2.5))                 # end walls
    shell.box("concrete", (x_out, 0, -2.5), (x_out + t, h, 2.5))
    shell.box("wood", (-3.6, 0, -2.2), (-2.4, 0.75, -1.4))                         # table in room A
    divider = Solids()
    divider.box("oak_veneer", (-d, 0, -2.5), (d, h, -0.5))
    divider.box("oak_veneer", (-d, 0, 0.5), (d, h, 2.5))
    divider.box("oak_veneer", (-d, 2.0, -0.5), (d, h, 0.5))                        # lintel
    shell.check()
    divider.check()
    check_disjoint(shell, divider)
    gltf = GltfWriter()
    gltf.node({"name": "Shell", "mesh": gltf.mesh("Shell", shell)})
    gltf.node({"name": "DividingWall", "mesh": gltf.mesh("DividingWall", divider),
               "extras": {"acoustic_layer": "wood"}})
    stereo = (2.5, 1.2, 1.0)
    assert not shell.contains(stereo) and not divider.contains(stereo)
    gltf.node(source("Stereo", stereo, (0.2, 0.6, 1.0), "music", max_distance=25.0))
    gltf.camera("Listener", (-3.8, 1.6, 0.8), (1.0, -0.1, -0.3))
    gltf.write(os.path.join(out_dir, "two_rooms.gltf"), "embedded")


# Level: a 4 x 3 grid of 9 x 8 m cells (x in [0, 36], z in [0, 24]) with walls
# centred on the grid lines, 3.2 m high under a 0.2 m ceiling slab.
COLS, ROWS, CELL_X, CELL_Z, HEIGHT, SLAB = 4, 3, 9.0, 8.0, 3.2, 0.2
OUTER = ("brick", 0.3)
# Interior lines: x = 9, 18, 27 and z = 8, 16.
INNER_X = {1: ("concrete", 0.2), 2: ("brick", 0.25), 3: ("concrete", 0.2)}
INNER_Z = {1: ("wood", 0.12), 2: ("concrete", 0.2)}
DOOR_W, DOOR_H, WIN_W, WIN_Y0, WIN_Y1, GLASS = 1.2, 2.2, 1.6, 1.0, 2.2, 0.02


def wall_x(solids, material, thickness, z, x0, x1, openings):
    """Wall along X centred on line z from x0 to x1, y in [-SLAB, HEIGHT].
    openings: (a, b, y0, y1, glass) cut-outs; glass fills a window."""
    _wall(solids, material, thickness, openings, x0, x1,
          lambda a, b, y0, y1, half: ((a, y0, z - half), (b, y1, z + half)))


def wall_z(solids, material, thickness, x, z0, z1, openings):
    _wall(solids, material, thickness, openings, z0, z1,
          lambda a, b, y0, y1, half: ((x - half, y0, a), (x + half, y1, b)))


def _wall(solids, material, thickness, openings, start, end, box_at):
    half = thickness / 2
    cursor = start
    for a, b, y0, y1, glass in sorted(openings):
        assert start < a < b < end
        solids.box(material, *box_at(cursor, a, -SLAB, HEIGHT, half))
        solids.box(material, *box_at(a, b, -SLAB, y0, half))     # sill, or threshold of a door
        solids.box(material, *box_at(a, b, y1, HEIGHT, half))    # lintel
        if glass:
            solids.box("glass", *box_at(a, b, y0, y1, GLASS / 2))
        cursor = b
    solids.box(material, *box_at(cursor, end, -SLAB, HEIGHT, half))


def level(out_dir, name="level", column_segments=32, column_rings=8, triangle_range=(5000, 50000)):
    """The 4 x 3 room level. The column tessellation sets the triangle count
    without changing the layout; the defaults write the bundled level."""
    walls, floors = Solids(), Solids()
    half_out = OUTER[1] / 2
    width, depth = COLS * CELL_X, ROWS * CELL_Z

    def half_z(line):  # half thickness of the wall on z = line * CELL_Z
        return half_out if line in (0, ROWS) else INNER_Z[line][1] / 2

    def half_x(line):
        return half_out if line in (0, COLS) else INNER_X[line][1] / 2

    # Walls along X run the full width between the outer X walls; the outer
    # ones cover the corners. Walls along Z fit between them.
    for line in range(ROWS + 1):
        material, thickness = OUTER if line in (0, ROWS) else INNER_Z[line]
        outer = line in (0, ROWS)
        x0, x1 = (-half_out, width + half_out) if outer else (half_out, width - half_out)
        openings = []
        for col in range(COLS):
            centre = col * CELL_X + CELL_X / 2 + (col % 2 - 0.5) * 1.5
            w = WIN_W if outer else DOOR_W
            y0, y1 = (WIN_Y0, WIN_Y1) if outer else (0.0, DOOR_H)
            openings.append((centre - w / 2, centre + w / 2, y0, y1, outer))
        wall_x(walls, material, thickness, line * CELL_Z, x0, x1, openings)
    for line in range(COLS + 1):
        material, thickness = OUTER if line in (0, COLS) else INNER_X[line]
        outer = line in (0, COLS)
        for row in range(ROWS):
            z0, z1 = row * CELL_Z + half_z(row), (row + 1) * CELL_Z - half_z(row + 1)
            centre = row * CELL_Z + CELL_Z / 2 + (row - 1) * 1.2
            w = WIN_W if outer else DOOR_W
            y0, y1 = (WIN_Y0, WIN_Y1) if outer else (0.0, DOOR_H)
            wall_z(walls, material, thickness, line * CELL_X, z0, z1, [(centre - w / 2, centre + w / 2, y0, y1, outer)])

    # Room floors fill each cell between its walls; carpet rooms lay 0.03 m
    # of carpet on 0.17 m of concrete.
    carpet_rooms = {(0, 1), (1, 2), (2, 0), (3, 1)}
    rooms = {}
    for row in range(ROWS):
        for col in range(COLS):
            lo = (col * CELL_X + half_x(col), row * CELL_Z + half_z(row))
            hi = ((col + 1) * CELL_X - half_x(col + 1), (row + 1) * CELL_Z - half_z(row + 1))
            rooms[(col, row)] = (lo, hi)
            if (col, row) in carpet_rooms:
                floors.box("concrete", (lo[0], -SLAB, lo[1]), (hi[0], -0.03, hi[1]))
                floors.box("carpet", (lo[0], -0.03, lo[1]), (hi[0], 0.0, hi[1]))
            else:
                floors.box("concrete", (lo[0], -SLAB, lo[1]), (hi[0], 0.0, hi[1]))
    floors.box("concrete", (-half_out, HEIGHT, -half_out), (width + half_out, HEIGHT + SLAB, depth + half_out))

    gltf = GltfWriter()
    gltf.node({"name": "Walls", "mesh": gltf.mesh("Walls", walls)})
    gltf.node({"name": "FloorsAndCeiling", "mesh": gltf.mesh("FloorsAndCeiling", floors)})

    # Columns: one mesh each, instanced by node translation (local origin at
    # the column's foot).
    steel, concrete_col = Solids(), Solids()
    steel.cylinder("metal", 0, 0, 0.18, 0, HEIGHT, column_segments, column_rings)
    concrete_col.cylinder("concrete", 0, 0, 0.3, 0, HEIGHT, column_segments, column_rings)
    steel.check()
    concrete_col.check()
    steel_mesh, concrete_mesh = gltf.mesh("SteelColumn", steel), gltf.mesh("ConcreteColumn", concrete_col)
    columns = gltf.node({"name": "Columns"})
    placed = Solids()  # world-space copies, for the clearance checks below
    column_spots = [((1, 1), 3.0, 2.5), ((1, 1), 6.0, 2.5), ((1, 1), 3.0, 5.5), ((1, 1), 6.0, 5.5),
                    ((2, 1), 3.0, 2.5), ((2, 1), 6.0, 2.5), ((2, 1), 3.0, 5.5), ((2, 1), 6.0, 5.5),
                    ((0, 2), 4.5, 4.0), ((3, 0), 4.5, 4.0), ((2, 2), 2.5, 4.0), ((1, 0), 6.5, 4.0),
                    ((3, 2), 4.5, 4.0)]
    for i, ((col, row), lx, lz) in enumerate(column_spots):
        is_steel = row == 1
        x, z = col * CELL_X + lx, row * CELL_Z + lz
        placed.cylinder("x", x, z, 0.3, 0, HEIGHT, 8, 1)
        gltf.node({"name": "Column%02d" % i, "mesh": steel_mesh if is_steel else concrete_mesh,
                   "translation": [x, 0.0, z]}, columns)

    # Furniture per room, in room-local coordinates (origin at the cell corner).
    room_group = gltf.node({"name": "Rooms"})
    furniture_kinds = [
        ("wood", (1.0, 1.2), (2.6, 0.75, 2.0)),   # table
        ("metal", (6.8, 0.6), (7.9, 1.9, 1.1)),   # cabinet
        ("wood", (0.5, 6.6), (3.0, 2.0, 7.1)),    # shelf
        ("wood", (5.5, 6.0), (7.0, 0.45, 7.2)),   # bench
    ]
    for row in range(ROWS):
        for col in range(COLS):
            solids = Solids()
            for k, (material, (x0, z0), (x1, y1, z1)) in enumerate(furniture_kinds):
                if (col + row + k) % 4 == 3:
                    continue  # vary the rooms
                solids.box(material, (x0, 0.0, z0), (x1, y1, z1))
                placed.box("x", (col * CELL_X + x0, 0.0, row * CELL_Z + z0),
                           (col * CELL_X + x1, y1, row * CELL_Z + z1))
            solids.check()
            room = gltf.node({"name": "Room_%d_%d" % (col, row),
                              "translation": [col * CELL_X, 0.0, row * CELL_Z]}, room_group)
            gltf.node({"name": "Furniture_%d_%d" % (col, row), "mesh": gltf.mesh("Furniture", solids)}, room)

    # 15 sources emitting every 250 ms for 100 ms (the paper's benchmark),
    # staggered phases, distinct hues; local positions inside their room.
    sound_spots = [((0, 0), "footsteps", (4.5, 0.3, 4.0)), ((1, 0), "gunfire", (3.0, 1.4, 4.0)),
                   ((2, 0), "voice", (4.5, 1.6, 3.0)), ((3, 0), "machinery", (2.0, 1.0, 5.0)),
                   ((0, 1), "music", (4.5, 1.2, 4.0)), ((1, 1), "voice", (4.5, 1.6, 4.0)),
                   ((2, 1), "alarm", (4.5, 2.8, 4.0)), ((3, 1), "footsteps", (5.0, 0.3, 3.5)),
                   ((0, 2), "water", (2.0, 0.8, 3.0)), ((1, 2), "gunfire", (5.0, 1.4, 3.5)),
                   ((2, 2), "radio", (6.0, 1.1, 3.0)), ((3, 2), "engine", (2.0, 0.9, 2.5)),
                   ((1, 1), "footsteps", (1.5, 0.3, 5.0)), ((2, 0), "door", (8.0, 1.0, 6.5)),
                   ((0, 2), "typing", (7.5, 0.9, 6.5))]
    sources_group = gltf.node({"name": "Sources"})
    for i, ((col, row), category, (lx, y, lz)) in enumerate(sound_spots):
        position = (col * CELL_X + lx, y, row * CELL_Z + lz)
        (lo, hi) = rooms[(col, row)]
        assert lo[0] < position[0] < hi[0] and lo[1] < position[2] < hi[1], ("source outside room", i)
        assert not placed.contains(position, margin=0.1) and not walls.contains(position, margin=0.1), i
        colour = colorsys.hsv_to_rgb(i / len(sound_spots), 0.85, 1.0)
        gltf.node(source("Source%02d_%s" % (i, category), position, colour, category, max_distance=25.0,
                         loudness=1.0, duration=0.1, interval=0.25, phase=round(i * 0.25 / len(sound_spots), 4)),
                  sources_group)
    listener = (2.0, 1.7, 2.0)
    assert not placed.contains(listener, margin=0.1)
    gltf.camera("Listener", listener, (1.0, -0.15, 0.8))
    walls.check()
    floors.check()
    check_disjoint(walls, floors, placed)
    assert triangle_range[0] <= gltf.triangles <= triangle_range[1], gltf.triangles
    gltf.write(os.path.join(out_dir, name + ".gltf"), "external")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)),
                        help="directory to write into (default: this script's directory)")
    parser.add_argument("--big-level", metavar="DIR",
                        help="write only level_big.gltf (about 250k triangles, for benchmarks) into DIR")
    args = parser.parse_args()
    if args.big_level:
        os.makedirs(args.big_level, exist_ok=True)
        # 13 columns of 2 * 128 * 74 + 2 * 128 triangles each, plus the rest of the level.
        level(args.big_level, "level_big", column_segments=128, column_rings=74, triangle_range=(200000, 300000))
        return
    os.makedirs(args.out, exist_ok=True)
    closed_room(args.out)
    two_rooms(args.out)
    level(args.out)


if __name__ == "__main__":
    main()
