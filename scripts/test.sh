#!/usr/bin/env bash
# The whole test suite (README's second command; .ci/run calls it). Installs
# what is missing, then three builds, each followed by its tests:
#
#   1. sanitized (build-asan/): GCC with -Werror, AddressSanitizer,
#      UndefinedBehaviorSanitizer and assertions (no NDEBUG, and
#      _GLIBCXX_ASSERTIONS, so the standard library checks indices and
#      empty containers), -O1: what AddressSanitizer advises, and at -O2
#      the sanitizers more than double the compile time (world.cpp 3.4 s
#      plain, 8.3 s sanitized at -O2, 5.7 s at -O1). Every suite, the benchmarks' smoke runs, the
#      examples, the fuzz corpora replayed, the installed package's
#      consumers: all of ctest but the tests labelled "nightly".
#   2. ThreadSanitizer (build-tsan/): the suites where a game's render
#      thread steps while its audio thread plays, emits and moves sources.
#   3. clang (build-clang/, scripts/test-builds.sh clang): clang's warnings
#      with -Werror, the optional Embree traversal, and the CPU BVH's
#      vectors as four plain lanes (-DSOUNDPAINT_SIMD=scalar).
#
# Moved to scripts/nightly.sh: the consumer test that compiles the library
# again with add_subdirectory, and fuzzing each target for minutes (README
# "Tests"). Each build goes through ccache when it is installed
# (install-deps.sh installs it): a CI machine that keeps ~/.cache/ccache
# recompiles only what a push changed.
#
# Each stage prints its wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
# OpenAL Soft, so that the optional OpenAL adapter is built and tested; sox
# and espeak-ng, which make examples/openal's sounds; clang and Embree for
# stage 3; ccache.
bash scripts/install-deps.sh openal sounds fuzz embree ccache
source scripts/build-options.sh
jobs="$(nproc)"
start=$SECONDS

stage_start=$SECONDS
echo "== sanitized: ASan + UBSan + assertions, -Werror (build-asan/)"
cmake -S . -B build-asan "${sp_launcher[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -DCMAKE_CXX_FLAGS=-D_GLIBCXX_ASSERTIONS \
  -DSOUNDPAINT_SANITIZE=ON -DSOUNDPAINT_WERROR=ON >/dev/null
cmake --build build-asan -j"$jobs"
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
ctest --test-dir build-asan --output-on-failure -j"$jobs" --timeout 900 --label-exclude nightly
echo "== sanitized: $((SECONDS - stage_start)) s"

# A game steps on its render thread while its audio thread plays, emits and
# moves sources: those paths run under ThreadSanitizer, with assertions on
# (no NDEBUG), so SoundScene's debug thread check is tested too. Every
# module is instrumented through CMAKE_*_FLAGS; no -Werror here, as GCC
# warns differently under -fsanitize=thread and the builds around hold it.
# -O1 and line tables only (-g1): reports name files and lines, for less
# compile time than -O2 -g.
stage_start=$SECONDS
echo "== ThreadSanitizer (render + audio threads, build-tsan/)"
tsan_tests=(test_capi_threads test_sound_scene)
cmake -S . -B build-tsan "${sp_launcher[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_CXX_FLAGS=-fsanitize=thread \
  -DCMAKE_C_FLAGS=-fsanitize=thread -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread -DSOUNDPAINT_BUILD_BENCH=OFF \
  -DSOUNDPAINT_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build-tsan -j"$jobs" --target "${tsan_tests[@]}"
for t in "${tsan_tests[@]}"; do
  TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 ./build-tsan/tests/"$t" --gtest_brief=1
done
echo "== ThreadSanitizer: ${#tsan_tests[@]} suites clean, $((SECONDS - stage_start)) s"

bash scripts/test-builds.sh clang
echo "== test.sh: every stage passed in $((SECONDS - start)) s"
