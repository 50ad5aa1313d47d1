#!/usr/bin/env bash
# Runs the full benchmark set on a quiet machine and keeps everything it
# measured: bench/raw/*.txt (the printed tables) and bench/raw/*.json (what
# bench/plot.py draws), then redraws bench/plots/*.png when gnuplot is
# installed. About 10 minutes on a 2-core machine with lavapipe; less on
# a faster one (every run is capped in time, see below).
#
#   bash scripts/run-benchmarks.sh            # build into ./build-bench, run, plot
#   BUILD_DIR=build bash scripts/run-benchmarks.sh
#
# What runs (bench/RESULTS_TEMPLATE.md explains the columns):
#  1. bench_step on scenes/level.gltf (9.6k triangles, 15 sources), the
#     paper's workload: budgets 0, 1 (the fixed cost per step), 100, 500,
#     2500 (the paper's) and 10k, 100k (scaling); 2000 steps per run or 10 s,
#     whichever comes first, 5 runs (3 on the big level), both backends.
#  2. The same on level_big.gltf (the same level with ~250k triangles),
#     generated into the build directory by scenes/generate_scenes.py.
#  3. bench_rays: soundpaint's closest_hit against Embree on the same emitted
#     rays, BVH build times, and the backends stepping, on both levels and on
#     generated levels of 10k, 100k and 1M triangles.
#  4. bench_draw: the indicator pass for 20k and 200k indicators at 1280x720.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD_DIR:-build-bench}
RAW=bench/raw
start_all=$SECONDS

echo "== building into $BUILD (Release)"
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j"$(nproc)" --target bench_step bench_rays bench_draw bench_embed
python3 scenes/generate_scenes.py --big-level "$BUILD/scenes"
mkdir -p "$RAW"
BIG="$BUILD/scenes/level_big.gltf"

# run NAME COMMAND...: prints progress, keeps stdout and stderr in $RAW/NAME.txt.
run() {
  local name=$1
  shift
  local start=$SECONDS
  echo "== $name ($(date +%H:%M:%S)): $*"
  "$@" 2>&1 | tee "$RAW/$name.txt"
  echo "== $name: $((SECONDS - start)) s"
}

STEP_ARGS=(--backends cpu,gpu --budgets 0,1,100,500,2500,10000,100000 --steps 2000 --warmup 60
           --max-seconds 10 --pattern paper)
# The bundled level is the headline figure: medians of 5 runs; the big level 3.
run step_level "$BUILD/bench/bench_step" --scene scenes/level.gltf "${STEP_ARGS[@]}" --runs 5 \
  --json "$RAW/step_level.json"
run step_level_big "$BUILD/bench/bench_step" --scene "$BIG" "${STEP_ARGS[@]}" --runs 3 --json "$RAW/step_level_big.json"
run rays "$BUILD/bench/bench_rays" --scenes "scenes/level.gltf,$BIG,gen:10000,gen:100000,gen:1000000" \
  --rays 500000 --budget 2500 --runs 5 --build-runs 3 --backends cpu,gpu --sim-steps 120 --sim-max-seconds 10 \
  --json "$RAW/rays.json"

# The indicator pass alone (issue 4): 20k and 200k indicators at 1280x720.
run draw "$BUILD/bench/bench_draw" --counts 20000,200000 --width 1280 --height 720 --runs 9 --warmup 3

# The integration module (issue 6): render-thread cost of the record calls,
# and refitting a moving door on the level and on a 250k-triangle level.
run embed "$BUILD/bench/bench_embed" --scene scenes/level.gltf --frames 600 --budget 500 --big 250000

if command -v gnuplot >/dev/null; then
  echo "== plots"
  python3 bench/plot.py --out bench/plots "$RAW"/step_level.json "$RAW"/step_level_big.json "$RAW"/rays.json
else
  echo "== no gnuplot: apt-get install -y gnuplot-nox, then"
  echo "   python3 bench/plot.py --out bench/plots $RAW/*.json"
fi
echo "== all done in $((SECONDS - start_all)) s; raw outputs in $RAW/"
