# Sourced by the build scripts: options every build of theirs shares.
# sp_launcher: compile through ccache when it is installed (install-deps.sh
# ccache), so that a machine that keeps ~/.cache/ccache between runs
# recompiles only what changed; nothing when it is not.
sp_launcher=()
if command -v ccache >/dev/null 2>&1; then
  sp_launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
