#!/usr/bin/env bash
# The whole test suite (README's second command; .ci/run calls it). Installs
# what is missing, then three builds, each followed by its tests:
#
#   1. sanitized (build-asan/): clang with -Werror, AddressSanitizer,
#      UndefinedBehaviorSanitizer (no recovery) and assertions (no NDEBUG,
#      and _GLIBCXX_ASSERTIONS, so the standard library checks indices and
#      empty containers), -O1, what AddressSanitizer advises. Every suite,
#      the benchmarks' smoke runs, the examples, the fuzz corpora replayed,
#      the installed package's consumers: all of ctest but the tests
#      labelled "nightly".
#   2. ThreadSanitizer (build-tsan/, clang): the suites where a game's
#      render thread steps while its audio thread plays, emits and moves
#      sources.
#   3. GCC (build-gcc/, scripts/test-builds.sh gcc): GCC's warnings with
#      -Werror at -O2 (some need the optimiser), shared, the optional
#      Embree traversal, and the CPU BVH's vectors as four plain lanes
#      (-DSOUNDPAINT_SIMD=scalar); every test again.
#
# Why clang sanitizes and GCC builds plain, not the other way round: the
# sanitizers cost GCC more (test_simulation.cpp at -O1: GCC 11.1 s
# sanitized, 4.6 s plain; clang 6.9 s and 4.0 s), and .ci/run has to fit in
# 15 minutes on two cores (bench/RESULTS.md section 29).
#
# Moved to scripts/nightly.sh: the consumer tests that compile the library
# again (add_subdirectory, a shared build of its own), and fuzzing each
# target for minutes (README "Tests"). Each build goes through ccache when
# it is installed (install-deps.sh installs it): a CI machine that keeps
# ~/.cache/ccache recompiles only what a push changed.
#
# The ThreadSanitizer and GCC builds are unity builds (CMAKE_UNITY_BUILD: a
# module's sources compiled eight to a translation unit, their headers
# parsed once, which is most of a plain build's time); the sanitized build,
# where code generation costs most, compiles each file alone, so a file
# that misses an include still fails here.
#
# Each stage prints its wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
# OpenAL Soft, so that the optional OpenAL adapter is built and tested; sox
# and espeak-ng, which make examples/openal's sounds; clang and its
# sanitizer runtimes, Embree for stage 3, ccache.
bash scripts/install-deps.sh openal sounds fuzz embree ccache
source scripts/build-options.sh
jobs="$(nproc)"
start=$SECONDS

stage_start=$SECONDS
echo "== sanitized: clang, ASan + UBSan + assertions, -Werror (build-asan/)"
cmake -S . -B build-asan "${sp_launcher[@]}" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -DCMAKE_CXX_FLAGS=-D_GLIBCXX_ASSERTIONS \
  -DSOUNDPAINT_SANITIZE=ON -DSOUNDPAINT_WERROR=ON >/dev/null
cmake --build build-asan -j"$jobs"
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
ctest --test-dir build-asan --output-on-failure -j"$jobs" --timeout 900 --label-exclude nightly
echo "== sanitized: $((SECONDS - stage_start)) s"

# A game steps on its render thread while its audio thread plays, emits and
# moves sources: those paths run under ThreadSanitizer, with assertions on
# (no NDEBUG), so SoundScene's debug thread check is tested too. Every
# module is instrumented through CMAKE_*_FLAGS; no -Werror here, as the
# builds around hold it. clang, -O1 and line tables only (-g1): reports
# name files and lines, for less compile time than GCC at -O2 -g.
stage_start=$SECONDS
echo "== ThreadSanitizer: clang, render + audio threads (build-tsan/)"
tsan_tests=(test_capi_threads test_sound_scene)
cmake -S . -B build-tsan "${sp_launcher[@]}" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_UNITY_BUILD=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_CXX_FLAGS=-fsanitize=thread \
  -DCMAKE_C_FLAGS=-fsanitize=thread -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread -DSOUNDPAINT_BUILD_BENCH=OFF \
  -DSOUNDPAINT_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build-tsan -j"$jobs" --target "${tsan_tests[@]}"
for t in "${tsan_tests[@]}"; do
  TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 ./build-tsan/tests/"$t" --gtest_brief=1
done
echo "== ThreadSanitizer: ${#tsan_tests[@]} suites clean, $((SECONDS - stage_start)) s"

bash scripts/test-builds.sh gcc
echo "== test.sh: every stage passed in $((SECONDS - start)) s"
