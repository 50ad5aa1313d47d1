#!/bin/bash
# Prepares what bench/device/measure.sh needs on a lent GPU machine, which
# builds nothing: the bench binaries of BEFORE (a commit) and of this
# working tree (its Release build in build/), the shared libraries they
# need beyond the C and C++ runtimes, and the Vulkan loader as Debian
# packages (the machine may have none). All of it goes under .device/ and
# .gl/, which .git/info/exclude keeps out of git; name both in the
# device run's `carry`.
#
#   bash bench/device/prepare.sh a63ab0e    # then, on the device:
#   bash bench/device/measure.sh            # carry: [".gl", ".device"]
set -euo pipefail
before=${1:?usage: prepare.sh BEFORE_COMMIT}
root=$(git rev-parse --show-toplevel)
cd "$root"
exclude=$(git rev-parse --git-path info/exclude)
mkdir -p "$(dirname "$exclude")"
touch "$exclude"
for ignored in /.gl/ /.device/; do
  grep -qxF "$ignored" "$exclude" || echo "$ignored" >>"$exclude"
done

build_benches() {  # source dir, build dir
  cmake -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$2" -j "$(nproc)" --target bench_step bench_embed >/dev/null
}

# BEFORE_WORKTREE: an existing worktree to build BEFORE in (its build/ is reused).
worktree=${BEFORE_WORKTREE:-/tmp/soundpaint-device-before}
if [ ! -d "$worktree" ]; then git worktree add --detach "$worktree" "$before" >/dev/null; fi
git -C "$worktree" checkout -q --detach "$before"
build_benches "$worktree" "$worktree/build"
build_benches "$root" "$root/build"

rm -rf .device
for side in before after; do
  dir=$([ "$side" = before ] && echo "$worktree/build" || echo "$root/build")
  mkdir -p ".device/$side"
  cp "$dir/bench/bench_step" "$dir/bench/bench_embed" ".device/$side/"
done
git -C "$worktree" rev-parse --short HEAD >.device/before/commit
{ git rev-parse --short HEAD; git diff --quiet HEAD || echo "(with uncommitted changes)"; } >.device/after/commit
# Libraries the binaries link that a bare machine may lack (ldd names them).
mkdir -p .device/lib
ldd .device/after/bench_step .device/before/bench_step | awk '/=> \// {print $3}' | sort -u |
  grep -E 'libtinygltf|libstb' | xargs -r cp -t .device/lib

mkdir -p .gl /tmp/amd64/partial
apt_opts=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64)
if ! ls .gl/libvulkan1_*.deb >/dev/null 2>&1; then
  apt-get "${apt_opts[@]}" update >/dev/null
  (cd .gl && apt-get "${apt_opts[@]}" download libvulkan1 >/dev/null)
fi
du -sh .device .gl
