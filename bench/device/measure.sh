#!/bin/bash
# Runs on a lent GPU machine, from the repository's root, what issues 35
# and 34 need measured there (bench/device/prepare.sh made the binaries):
#   - bench_step, GPU backend, the paper's pattern on the bundled level,
#     budgets 1, 100, 500 and 2500, with per-kernel GPU times; the two
#     builds alternate over three rounds;
#   - bench_embed: the host's frame with and without the visualizer, and
#     the async compute path where the device has a compute-only family.
# Everything goes to $OUT (one file per build and tool), which comes back.
# MEASURE_QUICK=1 runs a few steps of each (to try the script anywhere).
set -uo pipefail
out=${OUT:-/tmp/device-out}
mkdir -p "$out"
# The Vulkan loader, where the machine has none (the device README's way).
if ! ldconfig -p | grep -q 'libvulkan.so.1 '; then
  for f in .gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
export LD_LIBRARY_PATH=$PWD/.device/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
if [ -e /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ] && [ -z "${VK_DRIVER_FILES:-}" ]; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
steps=2000 runs=3 frames=600 rounds=3
if [ "${MEASURE_QUICK:-0}" = 1 ]; then steps=20 runs=1 frames=20 rounds=1; fi

{ date -u; nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv 2>&1;
  cat .device/before/commit .device/after/commit; } >"$out/machine.txt"
for ((round = 1; round <= rounds; ++round)); do
  for side in before after; do
    echo "# round $round" >>"$out/step-$side.txt"
    timeout 120 ".device/$side/bench_step" --backends gpu --budgets 1,100,500,2500 --steps "$steps" \
      --runs "$runs" --kernels 300 >>"$out/step-$side.txt" 2>&1 || echo "exit $?" >>"$out/step-$side.txt"
  done
done
for side in before after; do
  timeout 120 ".device/$side/bench_embed" --frames "$frames" --big 0 >"$out/embed-$side.txt" 2>&1 ||
    echo "exit $?" >>"$out/embed-$side.txt"
done
grep -h -E "^(gpu |     kernels)" "$out"/step-*.txt | head -40
