#!/bin/bash
# Renders the training data of the learned denoiser (docs/denoise.md "Learned denoiser") and
# trains it. Usage: bench/denoiser_training_data.sh OUT_DIR [interiornet binary]
# About 60-90 minutes on 2 cores for the data, 15 for training.
#
# Per apartment (procedural seeds 1, 2, 4, 5, 6, 8-12 train; 7 is held out; 3 is the evaluation
# apartment of docs/rendering.md and is never used) and for the built-in room:
#   inputs:  a 22-frame sequence at 320x240 (fx 300) as `generate` renders it by default
#            (16 spp, temporal reuse over 16 frames with planned samples), dumping what the
#            denoiser reads
#            (--save-denoiser-inputs); for the first five apartments and the room a second
#            time with another render seed along the same path (a second noise realisation)
#   targets: frames 9, 13, 17, 21 (seeds 8-12: 13 and 21) at 128 spp, no reuse, render seed
#            1000: frames with 10 to 16 frames of history, so the network sees windows that
#            are still filling as well as full ones
set -e
OUT=${1:?usage: $0 OUT_DIR [interiornet]}
B=${2:-$(dirname "$0")/../build/apps/interiornet}
B=$(realpath "$B")
mkdir -p "$OUT" && cd "$OUT"
COMMON="--width 320 --height 240 --fx 300 --fy 300 --exposure fixed --passes rgb --format asl \
--imu 0 --save-denoiser-inputs --no-progress"
seqof() { dirname "$(find "$1" -name denoise_in -type d | head -1)"; }
one() {  # name, rows of the target frames (sed script), layout args...
  local name=$1 rows=$2; shift 2
  [ -f in_$name/done ] || { $B generate "$@" --frames 22 --spp 16 --out in_$name $COMMON; touch in_$name/done; }
  local gt; gt=$(find in_$name -path '*state_groundtruth_estimate0/data.csv' | head -1)
  (head -1 "$gt"; sed -n "$rows" "$gt") > sub_$name.csv
  [ -f ref_$name/done ] || { $B generate "$@" --trajectory sub_$name.csv --spp 128 --temporal 1 \
      --no-denoise --seed 1000 --out ref_$name $COMMON; touch ref_$name/done; }
}
second() {  # name, layout args...: the same path, render seed 500
  local name=$1; shift
  local gt; gt=$(find in_$name -path '*state_groundtruth_estimate0/data.csv' | head -1)
  [ -f in2_$name/done ] || { $B generate "$@" --trajectory "$gt" --seed 500 --frames 22 --spp 16 \
      --out in2_$name $COMMON; touch in2_$name/done; }
}
for s in 1 2 4 5 6 7 8 9 10 11 12; do
  [ -f lay_$s/layout.json ] || $B layout generate --seed $s --out lay_$s
  rows='11p;15p;19p;23p'
  [ $s -ge 8 ] && rows='15p;23p'
  one a$s "$rows" --layout lay_$s/layout.json --seed $s
  case $s in 1|2|4|5|6) second a$s --layout lay_$s/layout.json ;; esac
done
one room '11p;15p;19p;23p' --seed 11
second room
pairs=""  # in the order the shipped weights were trained with (it orders the random crops)
for set in in in2; do
  for n in a1 a2 a4 a5 a6 room; do
    s=$(seqof in_$n); s=${s#in_$n/}
    pairs="$pairs,${set}_$n/$s/denoise_in:ref_$n/$s/denoise_in"
  done
done
for n in a8 a9 a10 a11 a12; do
  s=$(seqof in_$n); s=${s#in_$n/}
  pairs="$pairs,in_$n/$s/denoise_in:ref_$n/$s/denoise_in"
done
s=$(seqof in_a7); s=${s#in_a7/}
$B denoiser train --pairs "${pairs#,}" --holdout "in_a7/$s/denoise_in:ref_a7/$s/denoise_in" \
  --steps 2500 --threads 2 --loss-floor 1 --out unet.bin
