#!/usr/bin/env bash
# The test sequence of docs/rendering.md "Clean sequences" and its high-spp references, scored by
# bench/sequence_quality.py (flat-region error, blotches, flicker):
#
#   bench/sequence_references.sh OUT [REF_SPP=512]
#   APARTMENT=3 FRAMES=24 PICK="0 11 23" WIDTH=320 SPP=16 INET=build/apps/interiornet
#   EXTRA="--temporal 8"   more flags for the scored sequence (its default settings otherwise)
#   NAME=default           the scored sequence's folder, OUT/seq_NAME
#   TWIN=1                 also render OUT/seq_NAME_twin, the same poses and flags with render
#                          seed 4, and split the error into our noise and our bias (--twin)
#
# OUT/layout         procedural apartment APARTMENT (`layout generate --seed APARTMENT`)
# OUT/seq_NAME       FRAMES frames of the (1, 1) two-body path (--v-mult 1 --w-mult 1 --seed 3)
#                    at SPP, `generate`'s defaults and EXTRA, with --hdr and the passes the
#                    measure reads (rgb, depth, label, flow, albedo)
# OUT/ref_a, ref_b   frames PICK of that path at REF_SPP, seeds 101 and 102, no reuse and no
#                    denoiser: two independent unbiased references (their own noise is taken out
#                    by sequence_quality.py). Made once: the path depends only on the layout and
#                    the trajectory's seed, so every NAME is scored against the same references.
# Prints sequence_quality.py's "SEQ_JSON {...}" line and writes it to OUT/seq_NAME.json.
set -euo pipefail
OUT=${1:?output folder}
REF_SPP=${2:-512}
APARTMENT=${APARTMENT:-3}
FRAMES=${FRAMES:-24}
PICK=${PICK:-0 11 23}
W=${WIDTH:-320}
H=$((W * 3 / 4))
F=$(python3 -c "print($W * 300 / 320)")
SPP=${SPP:-16}
NAME=${NAME:-default}
INET=${INET:-build/apps/interiornet}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
[ -f "$OUT/layout/layout.json" ] || "$INET" layout generate --seed "$APARTMENT" --out "$OUT/layout" >/dev/null
camera=(--width "$W" --height "$H" --fx "$F" --fy "$F" --no-progress --format asl --hdr)
seq="$OUT/seq_$NAME"
if [ ! -f "$seq.done" ]; then
  # shellcheck disable=SC2086  # EXTRA is a list of flags
  "$INET" generate --layout "$OUT/layout/layout.json" --trajectory two-body --v-mult 1 --w-mult 1 \
    --seed 3 --frames "$FRAMES" --spp "$SPP" --passes rgb,depth,label,flow,albedo "${camera[@]}" \
    ${EXTRA:-} --out "$seq" >/dev/null
  touch "$seq.done"
fi
dir=$(dirname "$(find "$seq" -name meta.json | head -1)")
if [ ! -f "$OUT/rows.csv" ]; then
  gt="$dir/state_groundtruth_estimate0/data.csv"
  { head -1 "$gt"; for k in $PICK; do sed -n "$((k + 2))p" "$gt"; done; } > "$OUT/rows.tmp"
  mv "$OUT/rows.tmp" "$OUT/rows.csv"
fi
for r in a:101 b:102; do
  name=${r%%:*}; seed=${r##*:}
  [ -f "$OUT/ref_$name.done" ] && continue
  "$INET" generate --layout "$OUT/layout/layout.json" --trajectory "$OUT/rows.csv" \
    --spp "$REF_SPP" --seed "$seed" --no-denoise --temporal 1 --passes rgb,label "${camera[@]}" \
    --out "$OUT/ref_$name" >/dev/null
  touch "$OUT/ref_$name.done"
done
twin_args=()
if [ "${TWIN:-0}" = 1 ]; then
  twin="${seq}_twin"
  if [ ! -f "$twin.done" ]; then
    # shellcheck disable=SC2086  # EXTRA is a list of flags
    "$INET" generate --layout "$OUT/layout/layout.json" \
      --trajectory "$dir/state_groundtruth_estimate0/data.csv" --seed 4 --spp "$SPP" \
      --passes rgb,depth,label,flow,albedo "${camera[@]}" ${EXTRA:-} --out "$twin" >/dev/null
    touch "$twin.done"
  fi
  twin_args=(--twin "$(dirname "$(find "$twin" -name meta.json | head -1)")")
fi
ref_a=$(dirname "$(find "$OUT/ref_a" -name meta.json | head -1)")
ref_b=$(dirname "$(find "$OUT/ref_b" -name meta.json | head -1)")
blender -b --factory-startup -P "$HERE/sequence_quality.py" -- --seq "$dir" --ref "$ref_a" \
  --ref2 "$ref_b" "${twin_args[@]}" --json "$seq.json" 2>/dev/null | grep SEQ_JSON
