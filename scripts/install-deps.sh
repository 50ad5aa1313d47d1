#!/usr/bin/env bash
# Installs the Debian 12 packages soundpaint builds and tests with, if any is
# missing. Needs root (or sudo). `install-deps.sh fuzz` adds the clang
# tools CI uses: clang, the libFuzzer and sanitizer runtimes scripts/fuzz.sh
# needs (libclang-rt-14-dev, only recommended by clang, so named here) and
# clang-format for scripts/format.sh. `install-deps.sh embree` adds
# libembree-dev, for -DSOUNDPAINT_EMBREE=ON (cpu_traversal "embree") and
# bench_rays' Embree comparison. `install-deps.sh openal` adds OpenAL Soft
# (libopenal-dev), for the optional OpenAL adapter soundpaint::openal and
# its trace shim; `sounds` adds sox and espeak-ng, which make the sounds of
# examples/openal; `ccache` adds ccache, which the test builds compile
# through when it is there. Extras combine: `install-deps.sh fuzz embree`.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libtinygltf-dev nlohmann-json3-dev libstb-dev libglm-dev
  libgtest-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libglfw3-dev libimgui-dev xvfb xauth
)
for extra in "$@"; do
  case "$extra" in
    fuzz) packages+=(clang libclang-rt-14-dev clang-format) ;;
    embree) packages+=(libembree-dev) ;;
    openal) packages+=(libopenal-dev) ;;
    sounds) packages+=(sox espeak-ng) ;;
    ccache) packages+=(ccache) ;;
    *)
      echo "install-deps.sh: unknown extra '$extra' (fuzz, embree, openal, sounds, ccache)" >&2
      exit 2
      ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "installing: ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
