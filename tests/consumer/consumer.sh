#!/usr/bin/env bash
# Driver of the consumer tests (tests/consumer/CMakeLists.txt says what each
# checks):  consumer.sh MODE [CONFIG]
#   MODE: install | find_package | pkg_config | installed_headers | add_subdirectory | shared
# ctest gives the rest in the environment: SP_SOURCE_DIR, SP_BUILD_DIR,
# SP_WORK_DIR (this test's scratch folder), SP_CMAKE, SP_CTEST, SP_GENERATOR,
# SP_CC, SP_CXX, SP_JOBS, SP_LINK_FLAGS.
set -euo pipefail
mode="${1:?usage: consumer.sh MODE [CONFIG]}"
config="${2:-}"
[ -n "$config" ] || config=Release
: "${SP_SOURCE_DIR:?}" "${SP_BUILD_DIR:?}" "${SP_WORK_DIR:?}"
cmake="${SP_CMAKE:-cmake}"
ctest="${SP_CTEST:-ctest}"
cc="${SP_CC:-cc}"
cxx="${SP_CXX:-c++}"
jobs="${SP_JOBS:-2}"
link_flags="${SP_LINK_FLAGS:-}"
here="$SP_SOURCE_DIR/tests/consumer"
prefix="$SP_WORK_DIR/prefix"
generator=()
[ -z "${SP_GENERATOR:-}" ] || generator=(-G "$SP_GENERATOR")
# Nothing from the caller's environment may add an include path or a package.
unset CPATH C_INCLUDE_PATH CPLUS_INCLUDE_PATH CMAKE_PREFIX_PATH PKG_CONFIG_PATH

fail() {
  echo "consumer.sh $mode: $*" >&2
  exit 1
}
step() { echo "== $*"; }

# Runs a consumer program and checks its one line of success.
run_consumer() {
  local program="$1"
  step "run $program"
  "$program" || fail "$program failed"
}

# A shared libsoundpaint exports sp_* and sp::* only (export.h,
# cmake/exports.map): the C API and the public C++ API, nothing inside.
check_exports() {
  local lib="$1"
  step "dynamic symbols of $lib"
  nm -D --defined-only "$lib" | awk '{ $1 = ""; $2 = ""; sub(/^  /, ""); print }' | c++filt >"$SP_WORK_DIR/exports.txt"
  grep -qx 'sp_get_version' "$SP_WORK_DIR/exports.txt" || fail "$lib does not export sp_get_version"
  grep -q '^sp::parse_config(' "$SP_WORK_DIR/exports.txt" || fail "$lib does not export sp::parse_config"
  grep -qx 'typeinfo for sp::Exception' "$SP_WORK_DIR/exports.txt" || fail "$lib does not export sp::Exception's typeinfo"
  # The version nodes the linker adds (none with a plain version script) aside.
  stray="$(grep -vE '^(sp_[A-Za-z0-9_]+|sp::.*|(typeinfo|typeinfo name|vtable|VTT|(non-)?virtual thunk to) (for )?sp::.*)$' \
    "$SP_WORK_DIR/exports.txt" || true)"
  [ -z "$stray" ] || fail "$lib exports symbols outside sp_* and sp::*: $(echo "$stray" | head -20)"
  echo "$(wc -l <"$SP_WORK_DIR/exports.txt") symbols, all sp_* or sp::*"
}

# Configures tests/consumer/project/ into $1 with the remaining arguments, builds it.
build_project() {
  local dir="$1"
  shift
  rm -rf "$dir"
  step "configure $dir: $*"
  "$cmake" -S "$here/project" -B "$dir" "${generator[@]}" -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" \
    -DCMAKE_EXE_LINKER_FLAGS="$link_flags" "$@"
}

case "$mode" in
  install)
    rm -rf "$prefix"
    step "bring the library and the CLI up to date"
    "$cmake" --build "$SP_BUILD_DIR" --config "$config" --target soundpaint soundpaint_cli
    step "cmake --install into $prefix"
    "$cmake" --install "$SP_BUILD_DIR" --config "$config" --prefix "$prefix"
    for f in bin/soundpaint include/soundpaint/soundpaint.h include/soundpaint/soundpaint_vulkan.h \
             include/soundpaint/simulation.h include/soundpaint/visualizer.h; do
      [ -f "$prefix/$f" ] || fail "$f was not installed"
    done
    # The library is libsoundpaint.a, or libsoundpaint.so with BUILD_SHARED_LIBS.
    for f in 'libsoundpaint.[as]*' soundpaintConfig.cmake soundpaintConfigVersion.cmake soundpaintTargets.cmake \
             soundpaint.pc; do
      [ -n "$(find "$prefix" -name "$f" -print -quit)" ] || fail "no $f under $prefix"
    done
    # The package must not point back into this machine's trees.
    if grep -rlF -e "$SP_SOURCE_DIR" -e "$SP_BUILD_DIR" -e "$prefix" "$prefix" --include='*.cmake' --include='*.pc'; then
      fail "an installed package file names the source, build or install folder (above)"
    fi
    # The library is what an engine links: no tool module (the offline
    # renderer, its PNG writer and stb, the CLI's output files) inside it.
    lib="$(find "$prefix" -name 'libsoundpaint.[as]*' -type f -print -quit)"
    if nm -C "$lib" 2>/dev/null | grep -E ' (T|U) .*(stbi_|encode_png|write_png|AtomicFile|RenderTarget)'; then
      fail "$lib holds or needs a tool's symbols (above)"
    fi
    if readelf -d "$lib" 2>/dev/null | grep -E 'NEEDED.*libstb'; then
      fail "$lib links stb"
    fi
    case "$lib" in *.so*) check_exports "$lib" ;; esac
    "$prefix/bin/soundpaint" --help >/dev/null || fail "the installed soundpaint --help failed"
    find "$prefix" -type f | sed "s|^$prefix/||" | sort
    ;;

  find_package)
    [ -d "$prefix" ] || fail "no $prefix: consumer_install runs first"
    build_project "$SP_WORK_DIR/find_package" -DCMAKE_BUILD_TYPE="$config" -DSP_CONSUMER_MODE=package \
      -DCMAKE_PREFIX_PATH="$prefix"
    "$cmake" --build "$SP_WORK_DIR/find_package" -j"$jobs"
    run_consumer "$SP_WORK_DIR/find_package/consumer_cpp"
    run_consumer "$SP_WORK_DIR/find_package/consumer_c"
    # The OpenAL adapter, where this soundpaint was built with it.
    if [ -n "$(find "$prefix" -name soundpaintOpenALTargets.cmake -print -quit)" ]; then
      build_project "$SP_WORK_DIR/find_package_openal" -DCMAKE_BUILD_TYPE="$config" -DSP_CONSUMER_MODE=package \
        -DSP_CONSUMER_OPENAL=ON -DCMAKE_PREFIX_PATH="$prefix"
      "$cmake" --build "$SP_WORK_DIR/find_package_openal" -j"$jobs" --target consumer_openal
      ALSOFT_DRIVERS=null run_consumer "$SP_WORK_DIR/find_package_openal/consumer_openal"
    else
      step "soundpaint was built without OpenAL: no soundpaint::openal to find"
    fi
    # A C engine enables no C++: soundpaint::capi still links.
    build_project "$SP_WORK_DIR/find_package_c_only" -DCMAKE_BUILD_TYPE="$config" -DSP_CONSUMER_MODE=package \
      -DSP_CONSUMER_LANGUAGES=C -DCMAKE_PREFIX_PATH="$prefix"
    "$cmake" --build "$SP_WORK_DIR/find_package_c_only" -j"$jobs"
    run_consumer "$SP_WORK_DIR/find_package_c_only/consumer_c"
    ;;

  pkg_config)
    [ -d "$prefix" ] || fail "no $prefix: consumer_install runs first"
    pc="$(find "$prefix" -name soundpaint.pc -print -quit)"
    [ -n "$pc" ] || fail "no soundpaint.pc under $prefix"
    PKG_CONFIG_PATH="$(dirname "$pc")"
    export PKG_CONFIG_PATH
    pkg-config --exists --print-errors soundpaint
    echo "soundpaint $(pkg-config --modversion soundpaint): $(pkg-config --cflags --libs soundpaint)"
    # A shared libsoundpaint is found at run time through the library path.
    LD_LIBRARY_PATH="$(pkg-config --variable=libdir soundpaint)${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    export LD_LIBRARY_PATH
    out="$SP_WORK_DIR/pkg_config"
    rm -rf "$out"
    mkdir -p "$out"
    step "C99 consumer"
    # pkg-config's output and the link flags are lists of words.
    # shellcheck disable=SC2046,SC2086
    "$cc" -std=c99 -Wall -Wextra -pedantic -Werror $(pkg-config --cflags soundpaint) "$here/consumer.c" \
      -o "$out/consumer_c" $link_flags $(pkg-config --libs soundpaint)
    run_consumer "$out/consumer_c"
    step "C++ consumer"
    # shellcheck disable=SC2046,SC2086
    "$cxx" -std=c++20 -Wall -Wextra -Werror $(pkg-config --cflags soundpaint) "$here/consumer.cpp" \
      -o "$out/consumer_cpp" $link_flags $(pkg-config --libs soundpaint)
    run_consumer "$out/consumer_cpp"
    ;;

  installed_headers)
    [ -d "$prefix/include/soundpaint" ] || fail "no $prefix/include/soundpaint: consumer_install runs first"
    out="$SP_WORK_DIR/installed_headers"
    rm -rf "$out"
    mkdir -p "$out"
    headers=()
    for h in "$prefix"/include/soundpaint/*.h; do headers+=("soundpaint/$(basename "$h")"); done
    [ ${#headers[@]} -gt 0 ] || fail "no header installed"
    # Every dependency outside the system headers must come from the prefix.
    check_deps() {
      local deps="$1"
      local stray
      stray="$(tr ' ' '\n' <"$deps" | grep -E '\.(h|hpp)$' | grep -vF "$prefix/include/" || true)"
      [ -z "$stray" ] || fail "$2 included headers from outside the prefix: $stray"
    }
    cxxflags=(-std=c++20 -fsyntax-only -Wall -Wextra -Wconversion -Wshadow -Werror -I"$prefix/include")
    step "one C++ TU including all ${#headers[@]} installed headers"
    for h in "${headers[@]}"; do echo "#include <$h>"; done >"$out/all.cpp"
    "$cxx" "${cxxflags[@]}" -MMD -MF "$out/all.d" "$out/all.cpp" || fail "the headers do not compile together"
    check_deps "$out/all.d" all.cpp
    step "each header alone (self-contained), with nothing of ours but itself and its siblings"
    for h in "${headers[@]}"; do
      name="$(basename "$h" .h)"
      echo "#include <$h>" >"$out/$name.cpp"
      # -MD lists the system headers too: glm must be none of them, and only
      # the Vulkan interop headers may reach Vulkan's.
      "$cxx" "${cxxflags[@]}" -MD -MF "$out/$name.d" "$out/$name.cpp" || fail "$h does not compile on its own"
      ! grep -q '/glm/' "$out/$name.d" || fail "$h includes glm"
      ! grep -qE '/sp_[a-z_]+\.h' "$out/$name.d" || fail "$h includes the shaders' headers"
      case "$name" in
        visualizer | soundpaint_vulkan) ;;
        *) ! grep -q '/vulkan/' "$out/$name.d" || fail "$h includes Vulkan but is not an interop header" ;;
      esac
    done
    step "the C API's headers as C99"
    printf '#include <soundpaint/soundpaint.h>\n#include <soundpaint/soundpaint_vulkan.h>\n#include <soundpaint/soundpaint_signal.h>\n' >"$out/capi.c"
    "$cc" -std=c99 -pedantic -Wall -Wextra -Werror -fsyntax-only -I"$prefix/include" -MMD -MF "$out/capi.d" \
      "$out/capi.c" || fail "soundpaint.h, soundpaint_vulkan.h and soundpaint_signal.h do not compile as C99"
    check_deps "$out/capi.d" capi.c
    ;;

  add_subdirectory)
    # A parent with no build type must keep none (configuring is enough).
    build_project "$SP_WORK_DIR/add_subdirectory_no_build_type" -DCMAKE_BUILD_TYPE= -DSP_CONSUMER_MODE=subdirectory \
      -DSP_SOURCE_DIR="$SP_SOURCE_DIR"
    grep -qx 'CMAKE_BUILD_TYPE:STRING=' "$SP_WORK_DIR/add_subdirectory_no_build_type/CMakeCache.txt" ||
      fail "soundpaint gave a parent without a build type one of its own"
    dir="$SP_WORK_DIR/add_subdirectory"
    # With the OpenAL adapter off: the core must not need OpenAL.
    build_project "$dir" -DCMAKE_BUILD_TYPE=Debug -DSP_CONSUMER_MODE=subdirectory -DSP_SOURCE_DIR="$SP_SOURCE_DIR" \
      -DSOUNDPAINT_OPENAL=OFF -DSP_CONSUMER_NO_OPENAL=ON
    grep -qx 'CMAKE_BUILD_TYPE:STRING=Debug' "$dir/CMakeCache.txt" || fail "the parent's build type is no longer Debug"
    step "build the consumers only (the library with them), -j$jobs"
    "$cmake" --build "$dir" -j"$jobs" --target consumer_c consumer_cpp
    run_consumer "$dir/consumer_cpp"
    run_consumer "$dir/consumer_c"
    [ ! -e "$dir/shaders" ] || fail "generated files went to the parent's build folder ($dir/shaders)"
    ls "$dir"/soundpaint/shaders/*.spv.h >/dev/null 2>&1 || fail "no generated SPIR-V header in $dir/soundpaint/shaders"
    tests="$("$ctest" --test-dir "$dir" -N | sed -n 's/^Total Tests: //p')"
    [ "${tests:-0}" = 0 ] || fail "the parent's ctest lists $tests tests of soundpaint's"
    ;;

  shared)
    # A shared libsoundpaint, built and installed apart from this build
    # (which may be static), exports sp_* and sp::* only (export.h), and the
    # consumers, the OpenAL adapter's included, link and run against it.
    dir="$SP_WORK_DIR/shared_build"
    shared_prefix="$SP_WORK_DIR/shared_prefix"
    rm -rf "$shared_prefix"
    step "configure a shared build of $SP_SOURCE_DIR in $dir"
    "$cmake" -S "$SP_SOURCE_DIR" -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE="$config" -DBUILD_SHARED_LIBS=ON \
      -DSOUNDPAINT_BUILD_TESTS=OFF -DSOUNDPAINT_BUILD_BENCH=OFF -DSOUNDPAINT_BUILD_EXAMPLES=OFF \
      -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_SHARED_LINKER_FLAGS="$link_flags"
    step "build everything it installs, -j$jobs"
    "$cmake" --build "$dir" --config "$config" -j"$jobs"
    "$cmake" --install "$dir" --config "$config" --prefix "$shared_prefix"
    lib="$(find "$shared_prefix" -name 'libsoundpaint.so.*' -type f -print -quit)"
    [ -n "$lib" ] || fail "no libsoundpaint.so.* under $shared_prefix"
    check_exports "$lib"
    build_project "$SP_WORK_DIR/shared_consumers" -DCMAKE_BUILD_TYPE="$config" -DSP_CONSUMER_MODE=package \
      -DCMAKE_PREFIX_PATH="$shared_prefix"
    "$cmake" --build "$SP_WORK_DIR/shared_consumers" -j"$jobs"
    run_consumer "$SP_WORK_DIR/shared_consumers/consumer_cpp"
    run_consumer "$SP_WORK_DIR/shared_consumers/consumer_c"
    if [ -n "$(find "$shared_prefix" -name soundpaintOpenALTargets.cmake -print -quit)" ]; then
      build_project "$SP_WORK_DIR/shared_openal" -DCMAKE_BUILD_TYPE="$config" -DSP_CONSUMER_MODE=package \
        -DSP_CONSUMER_OPENAL=ON -DCMAKE_PREFIX_PATH="$shared_prefix"
      "$cmake" --build "$SP_WORK_DIR/shared_openal" -j"$jobs" --target consumer_openal
      ALSOFT_DRIVERS=null run_consumer "$SP_WORK_DIR/shared_openal/consumer_openal"
    fi
    ;;

  *)
    fail "unknown mode (install, find_package, pkg_config, installed_headers, add_subdirectory, shared)"
    ;;
esac
echo "consumer.sh $mode: ok"
