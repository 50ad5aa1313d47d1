#!/usr/bin/env bash
# Regenerates the diffraction picture pair (README "Sound round corners",
# docs/model.md#diffraction): docs/pictures/corner.gltf, an L-shaped
# corridor with a voice in leg one, seen from leg two out of the voice's
# sight, after 60 steps with diffraction off and on (nothing else differs).
#   scripts/render-diffraction-pictures.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
[ -f "$build/CMakeCache.txt" ] || cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"$(nproc)" --target soundpaint_cli
python3 scripts/make-corner-scene.py
for mode in off on; do
  "$build/soundpaint" render docs/pictures/corner.gltf --config "docs/pictures/corner-diffraction-$mode.json" \
    --backend cpu --steps 60 --width 960 --height 540 --look-at 7.3,1.3,2.0 \
    --out "docs/pictures/corner-diffraction-$mode.png"
done
