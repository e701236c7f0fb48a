#!/usr/bin/env bash
# Benchmarks of the dataset builder (issue 16), whole commands on this machine:
#  1. plan time and memory for 100,000 procedural layouts (1 sequence of 1,000 frames each, in
#     100-frame units: a million units);
#  2. the share of wall time outside the frame loop for 100-frame units (ground truth only, and
#     RGB at 4 spp), from the build's own accounting;
#  3. ranks scaling on this machine: the ground-truth plan with 1 thread locally, and under
#     mpirun with 1 and 2 workers of 1 thread each (the coordinator mostly sleeps);
#  4. resident memory after each of 100 units of one process (it must stay flat).
# Usage: bench/dataset.sh [interiornet binary] [work folder]
set -euo pipefail
BIN=${1:-build/apps/interiornet}
BIN=$(realpath "$BIN")
WORK=${2:-$(mktemp -d)}
mkdir -p "$WORK"
cd "$WORK"
MPIRUN="mpirun --allow-run-as-root --oversubscribe --mca btl self,vader"
TIME=/usr/bin/time

spec() {  # name count frames unit passes width spp
  cat > "$1.yaml" <<SPEC
version: 1
name: $1
seed: 1
layouts:
  procedural: {count: $2, rooms: [2, 4], furniture: catalog}
sequences: {per_layout: 1, frames: $3, unit_frames: $4}
sparse: {per_layout: 0}
camera: {width: $6, height: $(( $6 * 3 / 4 )), fx: $(( $6 * 15 / 16 )), fy: $(( $6 * 15 / 16 ))}
render: {spp: $7}
passes: [$5]
imu: 0
formats: [asl]
SPEC
}

echo "== 1. plan of 100,000 layouts (1,000,000 units)"
spec plan100k 100000 1000 100 default 640 16
$TIME -f "wall %e s, peak RSS %M kB" "$BIN" dataset plan plan100k.yaml --out plan100k | tail -1
ls -l plan100k/plan.json | awk '{print "plan.json", $5, "bytes"}'

echo "== 2+3. 100-frame ground-truth units (4 layouts x 200 frames, 320x240)"
spec gt 4 200 100 "depth, label, instance, normal" 320 1
for run in "local1:--threads 1" "local2:--threads 2" "mpi2:-np 2" "mpi3:-np 3"; do
  name=${run%%:*}; args=${run#*:}
  rm -rf "gt_$name"; "$BIN" dataset plan gt.yaml --out "gt_$name" > /dev/null
  start=$(date +%s.%N)
  if [[ $name == mpi* ]]; then
    $MPIRUN $args "$BIN" dataset build "gt_$name" --threads 1 --no-progress 2>/dev/null | grep -v "^wrote"
  else
    "$BIN" dataset build "gt_$name" $args --no-progress 2>/dev/null | grep -v "^wrote"
  fi
  end=$(date +%s.%N)
  echo "$name: $(python3 -c "print(round($end - $start, 1))") s wall for 800 frames"
done
diff -r gt_local1/data gt_mpi3/data > /dev/null && echo "gt: 1 thread and 3 ranks give the same bytes"

echo "== 2b. 100-frame RGB units (2 layouts x 100 frames, 160x120, 4 spp, every default pass)"
spec rgb 2 100 100 default 160 4
rm -rf rgb_b; "$BIN" dataset plan rgb.yaml --out rgb_b > /dev/null
"$BIN" dataset build rgb_b --no-progress 2>/dev/null | grep -v "^wrote"

echo "== 4. resident memory over 100 units (10 layouts x 200 frames in 20-frame units, 64x48)"
spec mem 10 200 20 "depth, label" 64 1
rm -rf mem_b; "$BIN" dataset plan mem.yaml --out mem_b > /dev/null
$TIME -f "wall %e s, peak RSS %M kB" "$BIN" dataset build mem_b --no-progress 2>&1 | grep -v "^wrote\|resuming"
echo "work folder: $WORK"
