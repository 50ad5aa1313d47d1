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
import os

from gltf_boxes import box, write_gltf

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "pictures", "corner.gltf")


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
    extra_nodes = [
        {"name": "voice", "translation": [3.0, 1.6, 1.25],
         "extras": {"sound_source": {"category": "voice", "max_distance": 30.0}}},
        # glTF cameras look along -z: from leg two back towards the corner.
        {"name": "listener", "camera": 0, "translation": [9.6, 1.7, 9.0]},
    ]
    camera = {"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.05, "zfar": 100.0,
                                                     "aspectRatio": 1.7777778}}
    write_gltf(OUT, PARTS, extra_nodes, camera, "scripts/make-corner-scene.py",
               part_name=lambda material, index: "%s-%d" % (material, index))


if __name__ == "__main__":
    main()
