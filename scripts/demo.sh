#!/usr/bin/env bash
# Setup + demo: installs dependencies, builds, simulates the bundled level and
# draws it: demo-output/level.png, demo-output/indicators.csv, demo-output/stats.json.
# Headless: it writes files only; `soundpaint view` opens the same level in a window.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
mkdir -p demo-output
./build/soundpaint info scenes/level.gltf
./build/soundpaint simulate scenes/level.gltf --steps 240 \
  --indicators demo-output/indicators.csv --stats demo-output/stats.json
./build/soundpaint render scenes/level.gltf --steps 30 --out demo-output/level.png
echo "wrote demo-output/level.png, demo-output/indicators.csv and demo-output/stats.json"
echo "on a desktop, walk through the level and watch sound travel live: ./build/soundpaint view scenes/level.gltf"
