#!/usr/bin/env bash
# Apartments furnished from the Sweet Home 3D catalogs next to the same seeds furnished with our
# parametric library (docs/assets.md): for each seed, both layouts, one view picked on the
# catalog version (the frame of a random path that shows the most NYU40 classes), rendered in
# both at W x H, SPP samples per pixel with the denoiser, 2 threads. Prints per apartment and
# furniture source: triangles placed, whole-process render seconds and peak memory (GNU time),
# and writes OUT/aptN/{parametric,catalog}.png and OUT/aptN/side_by_side.jpg.
#
#   bench/catalog_apartments.sh OUT [SPP] [W]        (APARTMENTS="3:0 7:0 11:10" seed:rooms)
#
# Needs sweethome3d-furniture and, for picking the view and the side-by-side image, Blender
# (bash scripts/setup.sh peers).
set -euo pipefail
OUT=${1:?output folder}
SPP=${2:-64}
W=${3:-640}
H=$((W * 3 / 4))
F=$(python3 -c "print($W * 600 / 640)")
INET=${INET:-build/apps/interiornet}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
for spec in ${APARTMENTS:-3:0 7:0 11:10}; do
  seed=${spec%%:*}; rooms=${spec##*:}
  d="$OUT/apt$seed"
  mkdir -p "$d"
  args=(--seed "$seed" --texture-size 256); [ "$rooms" != 0 ] && args+=(--rooms "$rooms")
  for src in parametric catalog; do
    [ -f "$d/$src/layout.json" ] ||
      "$INET" layout generate "${args[@]}" --furniture "$src" --out "$d/$src" >/dev/null
  done
  if [ ! -f "$d/camera.json" ]; then
    "$INET" generate --layout "$d/catalog/layout.json" --frames 60 --spp 1 \
      --passes rgb,depth,label --format asl,tum --width "$W" --height "$H" --fx "$F" --fy "$F" \
      --no-progress --out "$d/seq" >/dev/null 2>&1
    seq=$(dirname "$(find "$d/seq" -name meta.json | head -1)")
    frame=$(blender -b --factory-startup -P "$HERE/pick_frame.py" -- \
      "$seq"/label0/data/*_nyu.png 2>/dev/null | awk '/^PICK/ {print $2}')
    python3 "$HERE/frame_camera.py" "$seq" --frame "$frame" > "$d/camera.tmp"
    mv "$d/camera.tmp" "$d/camera.json"
  fi
  for src in parametric catalog; do
    tris=$("$INET" layout show --layout "$d/$src/layout.json" | awk '/^meshes/ {print $3}' | tr -d '(')
    /usr/bin/time -f "%e %M" -o "$d/$src.time" "$INET" render --layout "$d/$src/layout.json" \
      --camera "$d/camera.json" --spp "$SPP" --denoise --threads 2 --out "$d/$src.png" >/dev/null
    read -r secs kb < "$d/$src.time"
    echo "apt$seed $src triangles=$tris render_s=$secs peak_mb=$((kb / 1024))"
  done
  blender -b --factory-startup -P "$HERE/side_by_side.py" -- "$d/side_by_side.jpg" \
    "$d/parametric.png" "$d/catalog.png" >/dev/null 2>&1 || true
done
