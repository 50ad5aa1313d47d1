#!/usr/bin/env bash
# Fuzzes what comes from strangers (README "Security"): builds the libFuzzer
# targets in fuzz/ with clang, AddressSanitizer and UndefinedBehaviorSanitizer
# (every soundpaint module and tinygltf's implementation instrumented) into
# build-fuzz/, then runs each for SECONDS (default 60) from its seed corpus
# and the regression inputs under tests/data/, with its dictionary.
#
#   bash scripts/fuzz.sh [--timeout S] [--build-dir DIR] [SECONDS] [TARGET...]
#
#   --timeout S      an input that runs longer than S seconds (default 10) is
#                    a finding: slow inputs are hangs to a player (a level
#                    that takes minutes to check), so lower it to hunt them,
#                    e.g. --timeout 2
#   --build-dir DIR  build and run in DIR instead of build-fuzz/
#   TARGET           fuzz_scene_loader, fuzz_config_parser,
#                    fuzz_display_config, fuzz_capi (default: all four)
#
# A crash, leak, sanitizer report, timeout or input needing more than 2 GB
# fails the run; libFuzzer leaves the input as build-fuzz/crash-* (or
# leak-*, timeout-*, oom-*). Copy it to
# tests/data/issue-<n>-<what>.* to keep it as a regression input. New
# corpus entries accumulate in build-fuzz/corpus/<target>/ between runs.
set -euo pipefail
cd "$(dirname "$0")/.."
timeout_s=10
build=build-fuzz
while [ $# -gt 0 ]; do
  case "$1" in
    --timeout)
      [ $# -ge 2 ] && [[ "$2" =~ ^[1-9][0-9]*$ ]] || {
        echo "fuzz.sh: --timeout needs a whole number of seconds > 0" >&2
        exit 2
      }
      timeout_s="$2"
      shift 2
      ;;
    --build-dir)
      [ $# -ge 2 ] && [ -n "$2" ] || {
        echo "fuzz.sh: --build-dir needs a folder" >&2
        exit 2
      }
      build="$2"
      shift 2
      ;;
    -*)
      echo "fuzz.sh: unknown option '$1' (--timeout S, --build-dir DIR)" >&2
      exit 2
      ;;
    *) break ;;
  esac
done
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_scene_loader fuzz_config_parser fuzz_display_config fuzz_capi)
bash scripts/install-deps.sh fuzz

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DSOUNDPAINT_FUZZ=ON -DSOUNDPAINT_BUILD_TESTS=OFF -DSOUNDPAINT_BUILD_BENCH=OFF -DSOUNDPAINT_BUILD_EXAMPLES=OFF >/dev/null
cmake --build "$build" -j"$(nproc)" --target "${targets[@]}"
root="$(pwd)"
build="$(cd "$build" && pwd)"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus/$t"
  # Regression inputs: the scene loader's are glTF files, the others' JSON.
  regressions=(tests/data/issue-*.json)
  [ "$t" != fuzz_scene_loader ] || regressions=(tests/data/issue-*.gltf tests/data/issue-*.glb)
  seed_files=""
  for f in "${regressions[@]}"; do [ ! -f "$f" ] || seed_files+="${seed_files:+,}$root/$f"; done
  echo "== $t: ${seconds} s, ${timeout_s} s an input"
  # What libFuzzer leaves behind is a finding whatever its exit status: a
  # marker dates this run's.
  marker="$build/.fuzz-$t-started"
  touch "$marker"
  # The first directory receives new inputs; the seeds are only read.
  status=0
  (cd "$build" && "./fuzz/$t" -max_total_time="$seconds" -timeout="$timeout_s" -report_slow_units="$timeout_s" \
     -rss_limit_mb=2048 -max_len=65536 -dict="$root/fuzz/$t.dict" -print_final_stats=1 \
     ${seed_files:+-seed_inputs="$seed_files"} "corpus/$t" "$root/fuzz/corpus/$t" >"$t.log" 2>&1) || status=$?
  grep -E "^(INFO: Seed|Done [0-9]+ runs|stat::number_of_executed_units|==[0-9]+==ERROR|SUMMARY)|Test unit written" \
    "$build/$t.log" || true
  findings=$(find "$build" -maxdepth 1 -type f -newer "$marker" \
    \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | sort)
  if [ "$status" -ne 0 ] || [ -n "$findings" ]; then
    tail -n 40 "$build/$t.log"
    [ -z "$findings" ] || printf '== finding: %s\n' $findings
    echo "== $t FAILED (exit $status); its log: $build/$t.log"
    exit 1
  fi
done
echo "== fuzz: ${#targets[@]} targets, ${seconds} s each, ${timeout_s} s an input, no finding"
