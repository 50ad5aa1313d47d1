#!/usr/bin/env bash
# examples/openal end to end (ctest openal_example): the example plays its
# sox and espeak-ng sounds through OpenAL Soft's null output while walking
# the bundled level, and writes three pictures. Checked: it succeeds, every
# picture is written, the looping alarm and the voice paint in each, the
# footsteps in at least one (their thuds fill a sixth of the time), and the validation layer
# (SOUNDPAINT_VALIDATION=1) said nothing.
#   openal_example.sh EXAMPLE SCENE SOUNDS_DIR OUT_DIR
set -euo pipefail
example="$1" scene="$2" sounds="$3" out="$4"
rm -rf "$out"
"$example" "$scene" "$sounds" "$out" >"$out.stdout" 2>"$out.stderr" || {
  cat "$out.stderr" >&2
  exit 1
}
cat "$out.stdout"
for frame in 060 120 180; do
  png="$out/openal-frame-$frame.png"
  [ -s "$png" ] || { echo "openal_example: $png was not written" >&2; exit 1; }
  line="$(grep "^$png:" "$out.stdout" || true)"
  [ -n "$line" ] || { echo "openal_example: no line for $png" >&2; exit 1; }
  # The alarm loops from the start and the voice speaks from frame 60:
  # both paint in every picture.
  for category in alarm voice; do
    echo "$line" | grep -qE " $category [1-9]" || { echo "openal_example: no $category cues at frame $frame" >&2; exit 1; }
  done
done
grep -qE " footsteps [1-9]" "$out.stdout" || { echo "openal_example: the footsteps never painted" >&2; exit 1; }
if grep -qiE 'validation|VUID' "$out.stderr"; then
  echo "openal_example: validation messages:" >&2
  cat "$out.stderr" >&2
  exit 1
fi
echo "openal_example: ok"
