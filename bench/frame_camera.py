"""The camera of one frame of a sequence we wrote, as a camera.json (render --camera's format,
bench/cycles_gltf.py --camera), so another renderer can render the same view.

    python3 bench/frame_camera.py SEQUENCE_DIR [--frame N] > camera.json

Reads SEQUENCE_DIR/meta.json (the renderer-convention intrinsics) and groundtruth.txt (TUM:
t tx ty tz qx qy qz qw, the pose T_world_camera in OpenCV axes); --frame counts from 0.
"""
import argparse
import json
import os
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("sequence")
    ap.add_argument("--frame", type=int, default=0)
    a = ap.parse_args()
    with open(os.path.join(a.sequence, "meta.json")) as f:
        meta = json.load(f)
    cam = meta["camera"]
    k = cam["renderer"]  # pixel centres at +0.5, as render --camera reads them
    poses = []
    with open(os.path.join(a.sequence, "groundtruth.txt")) as f:
        for line in f:
            p = line.split()
            if p and not p[0].startswith("#"):
                poses.append([float(x) for x in p[1:8]])
    if not 0 <= a.frame < len(poses):
        sys.exit(f"{a.sequence}: --frame {a.frame}: the sequence has {len(poses)} frames")
    tx, ty, tz, qx, qy, qz, qw = poses[a.frame]
    r = [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
         [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
         [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]
    m = [r[0] + [tx], r[1] + [ty], r[2] + [tz], [0, 0, 0, 1]]
    json.dump({"width": cam["width"], "height": cam["height"], "fx": k["fx"], "fy": k["fy"],
               "cx": k["cx"], "cy": k["cy"], "cam_to_world": m}, sys.stdout, indent=1)
    print()


main()
