#!/usr/bin/env bash
# The whole test suite: installs dependencies if missing, builds with
# -Werror, runs every test through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 600
