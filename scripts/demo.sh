#!/usr/bin/env bash
# `make demo`: install what is missing, build the one program the demo runs (not the test
# suite), generate a short sequence through the built-in apartment (furnished from Sweet Home
# 3D's catalogs; the built-in room without them) and end with the folder and a contact sheet.
# One line per step with its time; each step's full output goes to out/demo_logs/STEP.log, and
# the last lines of that log are shown if the step fails.
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD="${BUILD:-build}"
JOBS="${JOBS:-$(nproc)}"
OUT="${OUT:-out/demo}"
LOGS="out/demo_logs"
mkdir -p "$LOGS"

total_start=$(date +%s)
steps=4
n=0

# step NAME DESCRIPTION COMMAND...: runs COMMAND with its output in $LOGS/NAME.log
step() {
  local name="$1" what="$2"
  shift 2
  n=$((n + 1))
  local start
  start=$(date +%s)
  printf '[%d/%d] %-44s' "$n" "$steps" "$what"
  if ! "$@" >"$LOGS/$name.log" 2>&1; then
    printf 'FAILED after %ss\n' "$(($(date +%s) - start))"
    echo "--- last lines of $LOGS/$name.log:" >&2
    tail -n 25 "$LOGS/$name.log" >&2
    exit 1
  fi
  local secs=$(($(date +%s) - start))
  printf '%3dm%02ds  (log: %s)\n' "$((secs / 60))" "$((secs % 60))" "$LOGS/$name.log"
}

step setup "packages (apt, when missing)" bash scripts/setup.sh
step configure "configure (CMake, Release)" \
  cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release
step build "build interiornet ($JOBS jobs)" \
  cmake --build "$BUILD" -j "$JOBS" --target interiornet
# 6 frames half a second apart along a look-forward path (a walk that looks where it goes),
# 16 samples per pixel and the denoiser: about 1.5 minutes on two cores
step generate "generate 6 frames (640x480, 16 spp)" \
  "$BUILD/apps/interiornet" generate --out "$OUT" --trajectory look-forward --frames 6 --fps 2 \
  --spp 16 --denoise --no-progress --contact-sheet "$OUT/contact_sheet.jpg"

seq_dir=$(sed -n 's/^wrote [0-9]* frames to //p' "$LOGS/generate.log" | head -1)
secs=$(($(date +%s) - total_start))
printf 'done in %dm%02ds\n' "$((secs / 60))" "$((secs % 60))"
echo "sequence:      ${seq_dir:-$OUT}  (cam0/ colour, depth0/, label0/ NYU40, imu0/, ... : docs/output.md)"
echo "contact sheet: $OUT/contact_sheet.jpg"
