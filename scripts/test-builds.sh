#!/usr/bin/env bash
# The test suite built by another compiler (issue 14, item 7), in a build
# folder of its own, followed by ctest:
#
#   bash scripts/test-builds.sh [clang]
#
#   clang   clang++ with -Werror (build-clang/): clang's warnings are not
#           GCC's (e.g. -Wconversion includes -Wsign-conversion there);
#           with -DSOUNDPAINT_EMBREE=ON, the optional Embree traversal; and
#           with -DSOUNDPAINT_SIMD=scalar, the CPU BVH's vectors as four
#           plain lanes, as on a compiler or CPU without SSE2 or NEON (issue
#           15). GCC's build (scripts/test.sh, sanitized) tests the SSE lanes,
#           this one the scalar lanes: each lane set once per push. And
#           shared (BUILD_SHARED_LIBS=ON): the consumer tests install a
#           libsoundpaint.so and check that it exports sp_* and sp::* only,
#           where GCC's build installs the static library. -O1 (with
#           NDEBUG, as Release): what it checks is warnings and results,
#           not speed, and -O1 compiles in less time than -O3.
#
# Assertions (no NDEBUG, _GLIBCXX_ASSERTIONS) run in scripts/test.sh's
# sanitized build, which replaced the separate assertion build (issue 36).
# Left out, as scripts/test.sh's build runs them: the benchmarks' smoke runs;
# and, as everywhere but scripts/nightly.sh, the tests labelled "nightly".
#
# BUILD_PREFIX (default "build-") names the folder: BUILD_PREFIX=/tmp/build-
# builds into /tmp/build-clang.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/build-options.sh
stages=("$@")
[ ${#stages[@]} -gt 0 ] || stages=(clang)
jobs="$(nproc)"
prefix="${BUILD_PREFIX:-build-}"

for stage in "${stages[@]}"; do
  case "$stage" in
    clang)
      start=$SECONDS
      dir="${prefix}clang"
      echo "== clang -Werror, shared, with Embree and scalar SIMD lanes ($dir/)"
      # clang (and the runtimes fuzz.sh needs anyway), and Embree: this stage
      # also builds the CPU backend's optional Embree traversal, so that its
      # tests run (test_cpu_traversal, and the physics tests' CpuEmbree cases).
      bash scripts/install-deps.sh fuzz embree
      cmake -S . -B "$dir" "${sp_launcher[@]}" -DSOUNDPAINT_WERROR=ON -DSOUNDPAINT_BUILD_BENCH=OFF \
        -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE="-O1 -DNDEBUG" \
        -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DSOUNDPAINT_EMBREE=ON \
        -DSOUNDPAINT_SIMD=scalar -DBUILD_SHARED_LIBS=ON >/dev/null
      cmake --build "$dir" -j"$jobs"
      ctest --test-dir "$dir" --output-on-failure -j"$jobs" --timeout 600 --label-exclude nightly
      echo "== clang: $((SECONDS - start)) s"
      ;;
    *)
      echo "test-builds.sh: unknown stage '$stage' (clang)" >&2
      exit 2
      ;;
  esac
done
