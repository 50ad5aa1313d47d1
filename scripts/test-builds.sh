#!/usr/bin/env bash
# The test suite built plain, without sanitizers, by one compiler (issue 14,
# item 7), in a build folder of its own, followed by ctest:
#
#   bash scripts/test-builds.sh [gcc|clang]...   (default: gcc)
#
# Each build has -Werror, so it holds that compiler's warnings (clang's are
# not GCC's: -Wconversion includes -Wsign-conversion there; some of GCC's
# need the optimiser, hence -O2), and is:
#   - shared (BUILD_SHARED_LIBS=ON): the consumer tests install a
#     libsoundpaint.so and check that it exports sp_* and sp::* only, where
#     the sanitized build installs the static library;
#   - with -DSOUNDPAINT_EMBREE=ON: the CPU backend's optional Embree
#     traversal, so that its tests run (test_cpu_traversal, and the physics
#     tests' CpuEmbree cases);
#   - with -DSOUNDPAINT_SIMD=scalar: the CPU BVH's vectors as four plain
#     lanes, as on a compiler or CPU without SSE2 or NEON (issue 15). The
#     sanitized build (scripts/test.sh) tests the SSE lanes: each lane set
#     once per push.
# A unity build (CMAKE_UNITY_BUILD: eight sources to a translation unit,
# their headers parsed once); scripts/test.sh's sanitized build compiles
# each file alone. NDEBUG, as Release; assertions (and _GLIBCXX_ASSERTIONS) run in
# scripts/test.sh's sanitized build, which replaced the separate assertion
# build (issue 36). scripts/test.sh runs the gcc stage, the clang one is
# for whoever wants clang's warnings without sanitizers.
#
# Left out, as scripts/test.sh's sanitized build runs them: the benchmarks'
# smoke runs; and, as everywhere but scripts/nightly.sh, the tests labelled
# "nightly". BUILD_PREFIX (default "build-") names the folders:
# BUILD_PREFIX=/tmp/build- builds into /tmp/build-gcc.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/build-options.sh
stages=("$@")
[ ${#stages[@]} -gt 0 ] || stages=(gcc)
jobs="$(nproc)"
prefix="${BUILD_PREFIX:-build-}"

for stage in "${stages[@]}"; do
  case "$stage" in
    gcc) compilers=(-DCMAKE_C_COMPILER=gcc -DCMAKE_CXX_COMPILER=g++) ;;
    clang) compilers=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++) ;;
    *)
      echo "test-builds.sh: unknown stage '$stage' (gcc, clang)" >&2
      exit 2
      ;;
  esac
  start=$SECONDS
  dir="${prefix}${stage}"
  echo "== $stage -Werror -O2, shared, with Embree and scalar SIMD lanes ($dir/)"
  bash scripts/install-deps.sh fuzz embree
  cmake -S . -B "$dir" "${sp_launcher[@]}" "${compilers[@]}" -DSOUNDPAINT_WERROR=ON -DSOUNDPAINT_BUILD_BENCH=OFF \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE="-O2 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" \
    -DSOUNDPAINT_EMBREE=ON -DSOUNDPAINT_SIMD=scalar -DBUILD_SHARED_LIBS=ON -DCMAKE_UNITY_BUILD=ON >/dev/null
  cmake --build "$dir" -j"$jobs"
  ctest --test-dir "$dir" --output-on-failure -j"$jobs" --timeout 600 --label-exclude nightly
  echo "== $stage: $((SECONDS - start)) s"
done
