#!/usr/bin/env bash
# The test suite built by other compilers and configurations (issue 14,
# item 7), each in a build folder of its own, each followed by ctest:
#
#   bash scripts/test-builds.sh [clang] [assert] [scalar]   (default: all three)
#
#   clang   clang++ with -Werror (build-clang/): clang's warnings are not
#           GCC's (e.g. -Wconversion includes -Wsign-conversion there);
#           with -DSOUNDPAINT_EMBREE=ON, the optional Embree traversal.
#   assert  GCC, -O2 with assertions on (build-assert/): no -DNDEBUG, so
#           every assert() runs, and _GLIBCXX_ASSERTIONS, so the standard
#           library checks indices, front() and back() of empty containers,
#           and the like.
#   scalar  -DSOUNDPAINT_SIMD=scalar (build-scalar/): the CPU BVH's vectors
#           as four plain lanes, as on a compiler or CPU without SSE2 or
#           NEON (issue 15). Only the suites that run the CPU BVH, the ray
#           model and the CPU/GPU parity: the rest does not touch simd4.h.
#
# Left out of all, to keep .ci/run within its hour on two cores: the
# benchmarks (scripts/test.sh's build runs their smoke tests) and the tests
# labelled "consumer" (packaging, not the compiler: they build soundpaint
# again, several times over). The examples stay in: the tests run the example
# host.
#
# Each stage prints its wall time. BUILD_PREFIX (default "build-") names
# the folders: BUILD_PREFIX=/tmp/build- builds into /tmp/build-clang, ...
set -euo pipefail
cd "$(dirname "$0")/.."
stages=("$@")
[ ${#stages[@]} -gt 0 ] || stages=(clang assert scalar)
jobs="$(nproc)"
prefix="${BUILD_PREFIX:-build-}"

run_stage() {
  local name="$1" dir="$2"
  shift 2
  local start=$SECONDS
  echo "== $name ($dir/)"
  cmake -S . -B "$dir" -DSOUNDPAINT_WERROR=ON -DSOUNDPAINT_BUILD_BENCH=OFF "$@" >/dev/null
  cmake --build "$dir" -j"$jobs"
  ctest --test-dir "$dir" --output-on-failure -j"$jobs" --timeout 600 --label-exclude consumer
  echo "== $name: $((SECONDS - start)) s"
}

for stage in "${stages[@]}"; do
  case "$stage" in
    clang)
      # clang (and the runtimes fuzz.sh needs anyway), and Embree: this stage
      # also builds the CPU backend's optional Embree traversal, so that its
      # tests run (test_cpu_traversal, and the physics tests' CpuEmbree cases).
      bash scripts/install-deps.sh fuzz embree
      run_stage "clang -Werror, with Embree" "${prefix}clang" -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DSOUNDPAINT_EMBREE=ON
      ;;
    assert)
      # RelWithDebInfo's flags without -DNDEBUG (and without -g, which only
      # makes the build slower here).
      run_stage "assertions (assert, _GLIBCXX_ASSERTIONS)" "${prefix}assert" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 \
        -DCMAKE_CXX_FLAGS=-D_GLIBCXX_ASSERTIONS
      ;;
    scalar)
      start=$SECONDS
      dir="${prefix}scalar"
      echo "== scalar SIMD ($dir/)"
      suites=(test_bvh test_wide_bvh test_bvh_refit test_large_array test_ray_model test_matter test_diffraction
              test_simulation test_gpu_parity test_backends)
      cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DSOUNDPAINT_WERROR=ON -DSOUNDPAINT_BUILD_BENCH=OFF \
        -DSOUNDPAINT_BUILD_EXAMPLES=OFF -DSOUNDPAINT_SIMD=scalar >/dev/null
      cmake --build "$dir" -j"$jobs" --target "${suites[@]}"
      for t in "${suites[@]}"; do
        "$dir/tests/$t" --gtest_brief=1
      done
      echo "== scalar SIMD: ${#suites[@]} suites passed, $((SECONDS - start)) s"
      ;;
    *)
      echo "test-builds.sh: unknown stage '$stage' (clang, assert, scalar)" >&2
      exit 2
      ;;
  esac
done
