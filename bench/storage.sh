#!/usr/bin/env bash
# Bytes per frame of every pass, and what the lossless storage choices save (issue 16;
# docs/output.md section 9). Renders the same 640x480 frames of builtin:apartment (4 rooms
# furnished from the catalogs; a hand-held path) once per storage choice, every default pass plus
# the linear-radiance EXR, then prints bytes per frame per folder and file kind.
# Flow exists for every frame but the last (forward) or the first (backward); folders are
# divided by the frames that have them.
# Usage: bench/storage.sh [interiornet binary] [work folder] [frames]
set -euo pipefail
BIN=$(realpath "${1:-build/apps/interiornet}")
WORK=${2:-$(mktemp -d)}
FRAMES=${3:-4}
mkdir -p "$WORK"
COMMON=(generate --layout builtin:apartment --trajectory hand-held --seed 2
        --frames "$FRAMES" --spp 4 --width 640 --height 480 --format asl --no-progress)

run() {  # name, extra flags...
  local name=$1; shift
  if [ ! -f "$WORK/$name.done" ]; then
    rm -rf "${WORK:?}/$name"
    /usr/bin/time -f "%e" -o "$WORK/$name.time" "$BIN" "${COMMON[@]}" --out "$WORK/$name" "$@" \
      >/dev/null
    touch "$WORK/$name.done"
  fi
}

run default --hdr
run kitti_only --hdr --flow-files kitti
run exr_flow --hdr --flow-files exr
run smallest --hdr-half --flow-files exr --png-level 9 --exr-compression piz
run png9 --hdr --png-level 9
run piz --hdr --exr-compression piz
run zips --hdr --exr-compression zips
run half --hdr-half

python3 - "$WORK" "$FRAMES" <<'PY'
import os, sys, collections
work, frames = sys.argv[1], int(sys.argv[2])
def kinds(root):
    seq = next(os.path.join(d, s) for d, ds, _ in os.walk(root) for s in ds if s == "seq_000")
    out = collections.Counter(); count = collections.Counter()
    for folder in sorted(os.listdir(seq)):
        data = os.path.join(seq, folder, "data")
        if not os.path.isdir(data): continue
        for f in os.listdir(data):
            suffix = f[19:]  # after the 19-digit timestamp
            key = f"{folder}/{suffix}"
            out[key] += os.path.getsize(os.path.join(data, f)); count[key] += 1
    return {k: out[k] / count[k] for k in out}
names = ["default", "kitti_only", "exr_flow", "png9", "piz", "zips", "half", "smallest"]
runs = {n: kinds(os.path.join(work, n)) for n in names if os.path.isdir(os.path.join(work, n))}
keys = sorted(set().union(*runs.values()))
print(f"{'file (bytes per frame, kB)':28}" + "".join(f"{n:>11}" for n in runs))
for k in keys:
    print(f"{k:28}" + "".join(f"{runs[n].get(k, 0)/1e3:11.1f}" for n in runs))
print(f"{'total per frame (MB)':28}" + "".join(f"{sum(runs[n].values())/1e6:11.2f}" for n in runs))
base = sum(runs["default"].values())
print(f"{'vs default':28}" + "".join(f"{sum(runs[n].values())/base:11.2f}" for n in runs))
times = {n: float(open(os.path.join(work, n + ".time")).read()) for n in runs}
print(f"{'wall time (s)':28}" + "".join(f"{times[n]:11.1f}" for n in runs))
PY
