#!/usr/bin/env bash
# Regenerates docs/level.png, the README's picture: the bundled level after
# 30 steps (0.5 s), seen through the scene's camera from the listener's
# room. It shows the sources' colours on every surface around the listener,
# light through both doorways, and the music source's exit indicators on
# the listener's side of the wooden wall to the right.
#   scripts/render-readme-picture.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
[ -f "$build/CMakeCache.txt" ] || cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"$(nproc)" --target soundpaint_cli
mkdir -p docs
# The CPU backend is the reference (the GPU backend gives the same indicators
# on lavapipe); drawing uses Vulkan either way.
"$build/soundpaint" render scenes/level.gltf --backend cpu --steps 60 --seed 1 --width 1280 --height 720 \
  --out docs/level.png
