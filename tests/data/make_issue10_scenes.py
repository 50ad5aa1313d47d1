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
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from gltf_boxes import box, write_gltf  # noqa: E402


def write(name, parts, note):
    """parts: list of (material, triangles)."""
    extra_nodes = [
        {"name": "speaker", "translation": [0.0, 1.5, 0.0],
         "extras": {"sound_source": {"category": "voice", "color": [1.0, 0.6, 0.0]}}},
        {"name": "listener", "camera": 0, "translation": [3.0, 1.5, 0.0]},
    ]
    camera = {"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.05}}
    write_gltf(os.path.join(HERE, name), parts, extra_nodes, camera, "tests/data/make_issue10_scenes.py", note=note)


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
