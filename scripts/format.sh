#!/usr/bin/env bash
# Formats the C and C++ sources with .clang-format (clang-format 14, Debian
# 12's), or with --check lists the files that differ and fails. GLSL files
# (.comp, .vert, .frag, .glsl) are left out: clang-format 14 has no GLSL mode
# and would break their interface blocks; shaders/shared/*.h are C++ too and
# are formatted.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "format.sh: clang-format is not installed (apt-get install clang-format)" >&2; exit 2; }
mapfile -t files < <(git ls-files '*.h' '*.hpp' '*.cpp' '*.c')
if [ "${1:-}" = "--check" ]; then
  differ=()
  for f in "${files[@]}"; do
    clang-format --style=file "$f" | cmp -s - "$f" || differ+=("$f")
  done
  if [ ${#differ[@]} -gt 0 ]; then
    printf 'format.sh: not formatted (run scripts/format.sh):\n' >&2
    printf '  %s\n' "${differ[@]}" >&2
    exit 1
  fi
  echo "format.sh: ${#files[@]} files formatted as .clang-format says"
else
  clang-format -i --style=file "${files[@]}"
fi
