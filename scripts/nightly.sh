#!/usr/bin/env bash
# The slow checks that .ci/run leaves to a nightly job (README "Tests"):
#
#   bash scripts/nightly.sh [SECONDS]
#
#   1. The ctest tests labelled "nightly", which compile the library again
#      (tests/consumer/CMakeLists.txt): consumer_add_subdirectory, soundpaint
#      added with add_subdirectory to a fresh Debug project, and
#      consumer_shared, a shared build installed apart whose exports must
#      be sp_* and sp::* only. The tests build what
#      they need themselves, so their build folder (build-nightly/) is only
#      configured.
#   2. Every fuzz target for SECONDS each (default 600), from its corpus and
#      the regression inputs (scripts/fuzz.sh, its build in build-fuzz/).
#      Each push replays the corpora only: the fuzz_*_replay tests.
#
# Each stage prints its wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
bash scripts/install-deps.sh fuzz

start=$SECONDS
echo "== consumer tests labelled nightly (build-nightly/)"
cmake -S . -B build-nightly -DCMAKE_BUILD_TYPE=Release -DSOUNDPAINT_WERROR=ON >/dev/null
ctest --test-dir build-nightly --output-on-failure -L nightly --timeout 3600
echo "== nightly consumer tests: $((SECONDS - start)) s"

start=$SECONDS
echo "== fuzz: every target for ${seconds} s (build-fuzz/)"
bash scripts/fuzz.sh "$seconds"
echo "== fuzz: $((SECONDS - start)) s"
