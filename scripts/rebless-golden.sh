#!/usr/bin/env bash
# Regenerates the golden images of tests/test_render.cpp (tests/data/golden/)
# from the current renderer on lavapipe. Run it after an intended change to
# the pictures, look at every rewritten image, then commit them.
#   scripts/rebless-golden.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
[ -f "$build/CMakeCache.txt" ] || cmake -S . -B "$build" >/dev/null
cmake --build "$build" -j"$(nproc)" --target test_render
# Lavapipe is the device the goldens are made on and compared against (CI).
export SOUNDPAINT_DEVICE="${SOUNDPAINT_DEVICE:-llvmpipe}"
SP_REBLESS_GOLDEN=1 "$build/tests/test_render" --gtest_filter='*Golden*'
git status --short tests/data/golden
