#!/usr/bin/env bash
# Fuzzes what comes from strangers (README "Security"): builds the libFuzzer
# targets in fuzz/ with clang, AddressSanitizer and UndefinedBehaviorSanitizer
# (every soundpaint module and tinygltf's implementation instrumented) into
# build-fuzz/, then runs each for SECONDS (default 60) from its seed corpus
# and the regression inputs under tests/data/, with its dictionary.
#
#   bash scripts/fuzz.sh [SECONDS] [TARGET...]
#
# A crash, leak, sanitizer report, timeout (10 s) or input needing more than
# 2 GB fails the run; libFuzzer leaves the input as build-fuzz/crash-* (or
# leak-*, timeout-*, oom-*). Copy it to tests/data/issue-<n>-<what>.* to keep
# it as a regression input. New corpus entries accumulate in
# build-fuzz/corpus/<target>/ between runs.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_scene_loader fuzz_config_parser fuzz_capi)
bash scripts/install-deps.sh fuzz

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DSOUNDPAINT_FUZZ=ON -DSOUNDPAINT_BUILD_TESTS=OFF -DSOUNDPAINT_BUILD_BENCH=OFF -DSOUNDPAINT_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]}"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t"
  # Regression inputs: the scene loader's are glTF files, the others' JSON.
  regressions=(tests/data/issue-*.json)
  [ "$t" != fuzz_scene_loader ] || regressions=(tests/data/issue-*.gltf tests/data/issue-*.glb)
  seed_files=""
  for f in "${regressions[@]}"; do [ ! -f "$f" ] || seed_files+="${seed_files:+,}../$f"; done
  echo "== $t: ${seconds} s"
  # The first directory receives new inputs; the seeds are only read.
  status=0
  (cd build-fuzz && "./fuzz/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
     -dict="../fuzz/$t.dict" -print_final_stats=1 ${seed_files:+-seed_inputs="$seed_files"} \
     "corpus/$t" "../fuzz/corpus/$t" >"$t.log" 2>&1) || status=$?
  grep -E "^(INFO: Seed|Done [0-9]+ runs|stat::number_of_executed_units|==[0-9]+==ERROR|SUMMARY)|Test unit written" \
    "build-fuzz/$t.log" || true
  if [ "$status" -ne 0 ]; then
    tail -n 40 "build-fuzz/$t.log"
    echo "== $t FAILED (exit $status); its log: build-fuzz/$t.log"
    exit 1
  fi
done
echo "== fuzz: ${#targets[@]} targets, ${seconds} s each, no crash"
