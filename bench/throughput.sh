#!/usr/bin/env bash
# Throughput against Cycles (issue 14's benchmark target, docs/rendering.md "Time to Cycles'
# 256-spp error"): per apartment, the error of Cycles at 256 spp, and the error and whole-process
# time of our frames at a few spp, at 640x480 on 2 threads, each renderer against its own truth
# (bench/throughput_error.py: no converged image needed).
#
#   bench/throughput.sh DIR [WIDTH=640]
#   APARTMENTS="3 7 11" SPPS="1 2 3 4 8 16" SEQ_SPPS="1 2 4 8" INET=build/apps/interiornet
#
# DIR holds the apartments of bench/apartment_compare.sh (DIR/aptN/layout/layout.json and
# DIR/aptN/camera.json, any width: scaled to WIDTH). Per apartment, into DIR/aptN/throughput/:
#   cycles64_{0,1}   Cycles at 64 spp, two seeds (their difference gives its variance at 256)
#   ref_{7,8}        ours at 256 spp, two seeds, no denoiser (our truth, noise taken out)
#   one_sN           `render --denoise` with the light cache, sun and lamp photons (what `generate`
#                    uses) at N spp: a single frame, whole process
#   seq_sN           the last frame of a 12-frame `generate` sequence (default settings: temporal
#                    reuse, the denoiser, every ground-truth pass) sliding 1 cm per frame to the
#                    same pose (bench/camera_trajectory.py); seq_sN_f12.t and seq_sN_f4.t are
#                    the whole processes of 12 and 4 frames, whose difference / 8 is the time of
#                    one frame inside a sequence
# Bounces: 8 in Cycles, 9 in ours (Cycles counts them after the first hit). About 25 minutes per
# apartment at 640x480, mostly the references (the defaults give docs/rendering.md's tables).
set -euo pipefail
DIR=${1:?apartments folder of bench/apartment_compare.sh}
W=${2:-640}
H=$((W * 3 / 4))
INET=${INET:-build/apps/interiornet}
SPPS=${SPPS:-1 2 3 4 8 16}
SEQ_SPPS=${SEQ_SPPS:-1 2 4 8}
HERE=$(cd "$(dirname "$0")" && pwd)
secs() { /usr/bin/time -f %e "$@" 2>&1 >/dev/null | tail -1; }
for s in ${APARTMENTS:-3 7 11}; do
  a="$DIR/apt$s"
  d="$a/throughput"
  mkdir -p "$d"
  layout="$a/layout/layout.json"
  python3 - "$a/camera.json" "$W" > "$d/camera.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
k = int(sys.argv[2]) / c["width"]
for key in ("width", "height", "fx", "fy", "cx", "cy"):
    c[key] = c[key] * k
json.dump(c, sys.stdout, indent=1)
PY
  "$INET" layout export "$layout" --camera "$d/camera.json" --out "$d/apt.gltf" >/dev/null 2>&1
  for seed in 0 1; do
    [ -f "$d/cycles64_$seed.exr" ] || secs blender -b --factory-startup -P "$HERE/cycles_gltf.py" \
      -- --gltf "$d/apt.gltf" --camera "$d/camera.json" --spp 64 --threads 2 --max-bounces 8 \
      --formats exr --seed "$seed" --out "$d/cycles64_$seed" > "$d/cycles64_$seed.t"
  done
  for seed in 7 8; do
    [ -f "$d/ref_$seed.exr" ] || secs "$INET" render --layout "$layout" --camera "$d/camera.json" \
      --spp 256 --threads 2 --max-bounces 9 --light-cache --sun-photons --lamp-photons --seed "$seed" \
      --out "$d/ref_$seed.exr" > "$d/ref_$seed.t"
  done
  for n in $SPPS; do
    [ -f "$d/one_s$n.exr" ] || secs "$INET" render --layout "$layout" --camera "$d/camera.json" \
      --spp "$n" --threads 2 --max-bounces 9 --light-cache --sun-photons --lamp-photons --denoise --seed 3 \
      --out "$d/one_s$n.exr" > "$d/one_s$n.t"
  done
  python3 "$HERE/camera_trajectory.py" "$d/camera.json" --frames 12 > "$d/trajectory.txt"
  read -r fx fy cx cy < <(python3 -c "import json, sys; c = json.load(open(sys.argv[1])); \
print(c['fx'], c['fy'], c['cx'], c['cy'])" "$d/camera.json")
  seqs=()
  for n in $SEQ_SPPS; do
    for frames in 12 4; do
      o="$d/seq_s${n}_f$frames"
      [ -f "$o.t" ] && continue
      rm -rf "$o"
      secs "$INET" generate --layout "$layout" --trajectory "$d/trajectory.txt" --frames "$frames" \
        --width "$W" --height "$H" --fx "$fx" --fy "$fy" --cx "$cx" --cy "$cy" --spp "$n" \
        --max-bounces 9 --hdr --seed 3 --no-progress --out "$o" > "$o.t"
    done
    cp "$(find "$d/seq_s${n}_f12/" -path '*cam0/data/*.exr' | sort | tail -1)" "$d/seq_s$n.exr"
    cp "$d/seq_s${n}_f12.t" "$d/seq_s$n.t"
    echo "apt$s seq_s$n: $(cat "$d/seq_s${n}_f12.t") s for 12 frames, $(cat "$d/seq_s${n}_f4.t") s for 4"
    seqs+=("$d/seq_s$n.exr")
  done
  # the label pass of the last frame: the flat regions
  label=$(find "$d/seq_s${SEQ_SPPS%% *}_f12/" -name '*_nyu.png' | sort | tail -1)
  ones=()
  for n in $SPPS; do ones+=("$d/one_s$n.exr"); done
  blender -b --factory-startup -P "$HERE/throughput_error.py" -- \
    --peer "$d/cycles64_0.exr" "$d/cycles64_1.exr" --refs "$d/ref_7.exr" "$d/ref_8.exr" \
    --label "$label" --json "$d/error.json" "${ones[@]}" "${seqs[@]}" 2>/dev/null |
    grep THR_JSON | sed "s/^THR_JSON/apt$s/"
done
