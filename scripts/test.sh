#!/usr/bin/env bash
# The whole test suite: installs dependencies if missing; runs the CPU-side
# suites (bad scene and config input, BVH, ray model, simulation) under
# AddressSanitizer + UndefinedBehaviorSanitizer, and the two-thread ones
# (render and audio thread) under ThreadSanitizer; then builds with -Werror
# and runs every test through ctest, whose summary closes the output.
set -euo pipefail
cd "$(dirname "$0")/.."
# OpenAL Soft too, so that the optional OpenAL adapter is built and tested,
# and sox and espeak-ng, which make examples/openal's sounds.
bash scripts/install-deps.sh openal sounds

echo "== sanitizers (ASan + UBSan, optimised build in build-asan/)"
sanitized_tests=(test_scene test_config test_bvh test_wide_bvh test_bvh_refit test_ray_model test_simulation test_sound_scene test_capi
                 test_signal test_capi_signal
                 test_scene_confinement test_scene_limits test_config_limits test_thread_pool test_build_workers test_memory_estimate
                 test_allocations test_output_path test_capi_untrusted test_capi_threads test_hostile_scenes)
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSOUNDPAINT_SANITIZE=ON -DSOUNDPAINT_WERROR=ON \
  -DSOUNDPAINT_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j"$(nproc)" --target "${sanitized_tests[@]}"
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
# test_hostile_scenes' GPU case is left out: lavapipe's JIT leaks under
# LeakSanitizer. The CPU cases are the ones that reach hostile arithmetic.
for t in "${sanitized_tests[@]}"; do
  ./build-asan/tests/"$t" --gtest_brief=1 --gtest_filter=-HostileScenesGpu.*
done
echo "== sanitizers: ${#sanitized_tests[@]} suites clean"

# A game steps on its render thread while its audio thread plays, emits and
# moves sources: those paths run under ThreadSanitizer, with assertions on
# (no NDEBUG), so SoundScene's debug thread check is tested too. Every
# module is instrumented through CMAKE_*_FLAGS; no -Werror here, as GCC
# warns differently under -fsanitize=thread and the builds above hold it.
echo "== ThreadSanitizer (render + audio threads, build-tsan/)"
tsan_tests=(test_capi_threads test_sound_scene)
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g" -DCMAKE_CXX_FLAGS=-fsanitize=thread -DCMAKE_C_FLAGS=-fsanitize=thread \
  -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread -DSOUNDPAINT_BUILD_BENCH=OFF -DSOUNDPAINT_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build-tsan -j"$(nproc)" --target "${tsan_tests[@]}"
for t in "${tsan_tests[@]}"; do
  TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 ./build-tsan/tests/"$t" --gtest_brief=1
done
echo "== ThreadSanitizer: ${#tsan_tests[@]} suites clean"

echo "== full suite (Release, -Werror, build/)"
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 600
