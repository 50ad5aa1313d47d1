#!/usr/bin/env python3
"""Runs soundpaint on real game levels and judges its indicators with the
levels' own BSP trees (the oracle beside them: check_indicators.py).

For each map (oa_dm1, kaos2), geometry mode (brushes: collision solids that
touch and overlap; draw: open render meshes) and config (default; and
bench/configs/permissive-walls.json, which lets walls pass sound), it
simulates 240 steps on the CPU backend and prints one row:

  indicators facing matter (% of all) and facing solid (matter or void),
  exits, exits facing matter and facing solid (% of exits), indicators below
  the lowest floor inside matter, exits into rooms the struck side cannot see
  (real transmission through walls), backcast misses per penetration, rays
  in air that struck a back face (% of hits), and ms per step.

  bench/measure_levels.py [--soundpaint build/soundpaint] [--levels ../shared/levels]
                          [--out DIR] [--steps 240]
"""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--soundpaint", default=os.path.join(HERE, "..", "build", "soundpaint"))
    ap.add_argument("--levels", default=os.path.join(HERE, "..", "..", "shared", "levels"))
    ap.add_argument("--out", default="/tmp/soundpaint-levels")
    ap.add_argument("--steps", type=int, default=240)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    configs = {"default": None, "permissive": os.path.join(HERE, "configs", "permissive-walls.json")}
    print("| level | config | indicators | facing matter | facing solid | exits | exits facing matter | "
          "exits facing solid | below floor in matter | into hidden rooms | misses / penetration | "
          "back faces / hit | ms/step |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for level in ("oa_dm1", "kaos2"):
        for mode in ("brushes", "draw"):
            for name, config in configs.items():
                stem = os.path.join(args.out, f"{level}-{mode}-{name}")
                cmd = [args.soundpaint, "simulate", os.path.join(args.levels, f"{level}-{mode}.glb"),
                       "--backend", "cpu", "--steps", str(args.steps), "--indicators", stem + ".csv",
                       "--stats", stem + ".json"]
                if config:
                    cmd += ["--config", config]
                run(cmd)
                judged = subprocess.run([sys.executable, os.path.join(args.levels, "check_indicators.py"),
                                         os.path.join(args.levels, f"{level}.bsp"), stem + ".csv"],
                                        check=True, capture_output=True, text=True).stdout
                d = json.loads(judged)
                s = json.load(open(stem + ".json"))
                hit, ex = d["hit"], d["exit"]
                total = hit["rows"] + ex["rows"]
                layers = s["layers"].values()
                penetrations = sum(l["penetrations"] for l in layers)
                misses = sum(l.get("no_way_out", l.get("backcast_misses", 0)) for l in layers)
                hits = sum(l["hits"] for l in layers)
                back = sum(l.get("back_face_hits", 0) for l in layers)
                print(f"| {level}-{mode} | {name} | {total} | "
                      f"{100 * (hit['facing_matter'] + ex['facing_matter']) / max(1, total):.2f} % | "
                      f"{100 * (hit['facing_solid'] + ex['facing_solid']) / max(1, total):.2f} % | {ex['rows']} | "
                      f"{ex['facing_matter_pct']:.1f} % | {ex['facing_solid_pct']:.1f} % | "
                      f"{hit['below_floor_in_matter'] + ex['below_floor_in_matter']} | "
                      f"{d['exit_pairs']['into_open_not_in_pvs']} | {misses / max(1, penetrations):.2f} | "
                      f"{100 * back / max(1, hits):.2f} % | {s['timing']['ms_per_step_median']:.3f} |")


if __name__ == "__main__":
    main()
