#!/usr/bin/env bash
# The example's sounds, made with Debian's tools at build time (none is
# committed): footsteps and an alarm from sox, a voice from espeak-ng.
#   make_sounds.sh OUT_DIR
set -euo pipefail
out="${1:?usage: make_sounds.sh OUT_DIR}"
mkdir -p "$out"
# Footsteps: a 60 ms thud of brown noise every half second, 2 s, loud (-3 dB
# peaks) and short: a burst.
sox -n -r 22050 -b 16 -c 1 "$out/footsteps.wav" synth 0.06 brownnoise fade q 0.005 0.06 0.05 gain -3 pad 0 0.44 repeat 3
# An alarm: an 880 Hz then a 660 Hz square tone, 0.25 s each (sox's ":"
# chains the second after the first), steady at -9 dB, looped by the program.
sox -n -r 22050 -b 16 -c 1 "$out/alarm.wav" synth 0.25 square 880 gain -9 : synth 0.25 square 660 gain -9
# A voice: espeak-ng's own 22050 Hz mono 16-bit WAV.
espeak-ng -w "$out/voice.wav" "Intruder in the west wing. Security to the lower floor."
