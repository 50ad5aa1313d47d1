#!/usr/bin/env bash
# OpenArena, unmodified, records a sound-event trace of a bot match, which
# soundpaint then paints on the converted level (README "A real game:
# OpenArena"). Not part of the test suite: it runs a game for a minute.
#
#   scripts/openarena-trace.sh [OUT_DIR] [SECONDS]
#
# On a fresh Debian 12 machine, as root: installs what it needs (the build's
# packages, openarena, libopenal1, Xvfb), builds the trace shim and the CLI,
# names the game's sounds (scripts/openarena-sound-names.py), runs OpenArena
# under Xvfb with software GL and OpenAL Soft's null output
# (ALSOFT_DRIVERS=null) for SECONDS (default 30) of a free-for-all of bots on
# oa_dm1 with the shim preloaded, and writes OUT_DIR/trace.jsonl (default
# openarena-output/). With ../shared/levels/oa_dm1-draw.glb beside the
# checkout (or LEVEL=path), it then renders the trace from the player's
# position into OUT_DIR/oa_dm1-trace-*.png.
#
# Debian's ioquake3 links libopenal at build time instead of loading the
# cvar s_alDriver's library, so the shim is put in front with LD_PRELOAD;
# an ioquake3 built with USE_OPENAL_DLOPEN takes it as +set s_alDriver PATH.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-openarena-output}"
seconds="${2:-30}"
level="${LEVEL:-../shared/levels/oa_dm1-draw.glb}"

bash scripts/install-deps.sh openal
need=(openarena libopenal1 xvfb xauth libgl1-mesa-dri)
missing=()
for p in "${need[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target soundpaint_al_trace soundpaint_cli >/dev/null
shim="$PWD/build/libsoundpaint_al_trace.so"
[ -f "$shim" ] || { echo "openarena-trace.sh: the shim was not built (is libopenal-dev installed?)" >&2; exit 1; }

mkdir -p "$out"
out="$(cd "$out" && pwd)"
home="$(mktemp -d)"
trap 'rm -rf "$home"' EXIT
python3 scripts/openarena-sound-names.py "$out/sound-names.tsv" /usr/share/games/openarena/baseoa/*.pk3

# A free-for-all of four bots on oa_dm1; the player stands at a spawn point
# and listens. No frag or time limit: the run ends when `timeout` does.
mkdir -p "$home/baseoa"
cat > "$home/baseoa/soundpaint-bots.cfg" <<'CFG'
seta com_introplayed 1
seta com_maxfps 60
seta sv_pure 0
seta s_useOpenAL 1
seta s_alPrecache 1
seta r_fullscreen 0
seta r_mode 3
seta g_gametype 0
seta fraglimit 0
seta timelimit 0
seta bot_enable 1
seta bot_minplayers 5
seta g_spSkill 3
map oa_dm1
CFG

echo "openarena-trace.sh: playing ${seconds} s of oa_dm1 (plus loading) under Xvfb"
start=$(date +%s)
set +e
ALSOFT_DRIVERS=null LIBGL_ALWAYS_SOFTWARE=1 SOUNDPAINT_TRACE="$out/trace.jsonl" \
  SOUNDPAINT_SOUND_NAMES="$out/sound-names.tsv" LD_PRELOAD="$shim" \
  timeout -s TERM $((seconds + 20)) xvfb-run -a -s "-screen 0 1024x768x24" \
  /usr/games/openarena +set fs_homepath "$home" +exec soundpaint-bots.cfg >"$out/openarena.log" 2>&1
set -e
echo "openarena-trace.sh: the game ran $(($(date +%s) - start)) s; $(wc -l <"$out/trace.jsonl") trace lines"
grep -c '"type":"buffer"' "$out/trace.jsonl" | xargs echo "  buffers:"
grep '"type":"buffer"' "$out/trace.jsonl" | grep -vc '"name":null' | xargs echo "  named:"
grep -c '"type":"play"' "$out/trace.jsonl" | xargs echo "  plays:"
tail -n 1 "$out/trace.jsonl"

if [ -f "$level" ]; then
  # Pictures from the player's position, at the two busiest 2 s windows of
  # footsteps and gunfire, facing where those sounds were (mean position,
  # in the scene's metres: (x, y, z) -> (x/32, z/32, -y/32)).
  python3 - "$out/trace.jsonl" >"$out/windows.txt" <<'PY'
import json, sys
names, events = {}, []
for line in open(sys.argv[1]):
    e = json.loads(line)
    if e["type"] == "buffer":
        names[e["buffer"]] = e["name"] or ""
    elif e["type"] == "play" and not e["relative"] and e["position"] != [0, 0, 0]:
        n = names.get(e["buffer"], "")
        if "/footsteps/" in n or "/weapons/machinegun/machgf" in n or "/weapons/shotgun/" in n:
            events.append((e["t"], e["position"]))
best = []
for t0 in sorted({int(t) for t, _ in events}):
    inside = [p for t, p in events if t0 <= t < t0 + 2]
    best.append((len(inside), t0, inside))
best.sort(reverse=True)
chosen = []
for count, t0, inside in best:
    if all(abs(t0 - c) >= 3 for c, _ in chosen):
        chosen.append((t0, inside))
    if len(chosen) == 2:
        break
for t0, inside in chosen:
    x = sum(p[0] for p in inside) / len(inside) / 32
    y = sum(p[2] for p in inside) / len(inside) / 32
    z = -sum(p[1] for p in inside) / len(inside) / 32
    print(t0, f"{x:.2f},{y:.2f},{z:.2f}")
PY
  while read -r start look; do
    build/soundpaint render "$level" --events "$out/trace.jsonl" --event-axes quake \
      --event-rules data/openarena-categories.json --event-start "$start" --steps 120 --look-at "$look" \
      --out "$out/oa_dm1-trace-$((start + 2))s.png"
  done <"$out/windows.txt"
  echo "openarena-trace.sh: pictures in $out (trace time in the name)"
else
  echo "openarena-trace.sh: no $level: no pictures (LEVEL=path/to/oa_dm1-draw.glb)"
fi
