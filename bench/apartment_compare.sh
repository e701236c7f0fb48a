#!/usr/bin/env bash
# Same-apartment comparison with Blender Cycles (issue 14, docs/rendering.md): for each
# procedural apartment, one frame of a random camera path rendered by us and by Cycles at equal
# spp and bounces on 2 threads, each against its own high-spp reference, plus the two references'
# mean radiance region by region (bench/compare_renders.py).
#
#   bench/apartment_compare.sh OUT [SPP=16] [REF_SPP=512] [WIDTH=320]
#   APARTMENTS="3:0 7:0 11:10" (seed:rooms, 0 = drawn) FRAMES=50 BOUNCES=8
#   INET=build/apps/interiornet
# Bounces: Cycles' max_bounces counts the bounces after the first hit (0 = direct light only),
# ours counts scattering events (1 = direct light only): Cycles' N is our N + 1.
# The frame is the one of the path's first FRAMES that shows the most classes
# (bench/pick_frame.py).
set -euo pipefail
OUT=${1:?output folder}
SPP=${2:-16}
REF=${3:-512}
W=${4:-320}
H=$((W * 3 / 4))
F=$(python3 -c "print($W * 600 / 640)")
INET=${INET:-build/apps/interiornet}
HERE=$(cd "$(dirname "$0")" && pwd)
FRAMES=${FRAMES:-50}
BOUNCES=${BOUNCES:-8}
mkdir -p "$OUT"
secs() { /usr/bin/time -f %e "$@" 2>&1 >/dev/null | tail -1; }
for spec in ${APARTMENTS:-3:0 7:0 11:10}; do
  seed=${spec%%:*}; rooms=${spec##*:}
  d="$OUT/apt$seed"
  mkdir -p "$d"
  args=(--seed "$seed"); [ "$rooms" != 0 ] && args+=(--rooms "$rooms")
  [ -f "$d/layout/layout.json" ] || "$INET" layout generate "${args[@]}" --out "$d/layout" >/dev/null
  if [ ! -f "$d/camera.json" ]; then
    "$INET" generate --layout "$d/layout/layout.json" --frames "$FRAMES" --spp 1 \
      --passes rgb,depth,label --format asl,tum --width "$W" --height "$H" --fx "$F" --fy "$F" --no-progress \
      --out "$d/seq" >/dev/null 2>&1
    seq=$(dirname "$(find "$d/seq" -name meta.json | head -1)")
    # the frame of the path's first FRAMES that shows the most classes (not a bare wall)
    frame=$(blender -b --factory-startup -P "$HERE/pick_frame.py" -- \
      "$seq"/label0/data/*_nyu.png 2>/dev/null | awk '/^PICK/ {print $2}')
    python3 "$HERE/frame_camera.py" "$seq" --frame "$frame" > "$d/camera.tmp"
    mv "$d/camera.tmp" "$d/camera.json"
    cp "$(ls "$seq"/label0/data/*_nyu.png | sed -n "$((frame + 1))p")" "$d/label_nyu.png"
    echo "$frame" > "$d/frame"
  fi
  "$INET" layout export "$d/layout/layout.json" --camera "$d/camera.json" \
    --out "$d/apt.gltf" >/dev/null
  # references use another seed than the equal-spp images: the same seed would share their
  # first samples (and fireflies), and each would be measured against part of itself
  render_ours() {  # spp out seed -> prints whole-process seconds
    secs "$INET" render --layout "$d/layout/layout.json" --camera "$d/camera.json" \
      --spp "$1" --threads 2 --max-bounces $((BOUNCES + 1)) --seed "$3" --out "$2"
  }
  render_cycles() {  # spp out-stem seed -> prints whole-process seconds
    secs blender -b --factory-startup -P "$HERE/cycles_gltf.py" -- --gltf "$d/apt.gltf" \
      --camera "$d/camera.json" --spp "$1" --threads 2 --max-bounces "$BOUNCES" --formats exr,png \
      --seed "$3" --out "$2"
  }
  t_ours=$(render_ours "$SPP" "$d/ours_$SPP.exr" 0)
  render_ours "$SPP" "$d/ours_$SPP.png" 0 >/dev/null
  t_cyc=$(render_cycles "$SPP" "$d/cycles_$SPP" 0)
  [ -f "$d/ours_ref.exr" ] || render_ours "$REF" "$d/ours_ref.exr" 7 > "$d/ours_ref.seconds"
  [ -f "$d/cycles_ref.exr" ] || render_cycles "$REF" "$d/cycles_ref" 7 > "$d/cycles_ref.seconds"
  blender -b --factory-startup -P "$HERE/compare_renders.py" -- --label "$d/label_nyu.png" \
    --pair "ours:$d/ours_$SPP.exr:$d/ours_ref.exr:$t_ours" \
    --pair "cycles:$d/cycles_$SPP.exr:$d/cycles_ref.exr:$t_cyc" \
    --refs "$d/ours_ref.exr" "$d/cycles_ref.exr" --json "$d/compare.json" 2>/dev/null |
    grep CMP_JSON | sed "s/^CMP_JSON/apt$seed/"
done
