"""A short TUM trajectory that ends at a camera.json's pose, so that the last frame of a
sequence (`interiornet generate --trajectory`, with temporal reuse over the frames before it)
shows the same view as `render --camera` and `bench/cycles_gltf.py --camera`:

    python3 bench/camera_trajectory.py camera.json [--frames 12] [--step 0.01] > traj.txt

The camera keeps its orientation and slides along its own x axis (image right) by --step metres
per frame at 25 Hz, like a slow sideways pan; the pose of the last frame is camera.json's
cam_to_world (T_world_camera, OpenCV axes), the inverse of bench/frame_camera.py.
"""
import argparse
import json
import math


def quaternion(r):
    """x, y, z, w of a rotation matrix (Shepperd's method: the largest diagonal term first)."""
    trace = r[0][0] + r[1][1] + r[2][2]
    if trace > 0:
        s = math.sqrt(trace + 1) * 2
        return ((r[2][1] - r[1][2]) / s, (r[0][2] - r[2][0]) / s, (r[1][0] - r[0][1]) / s, s / 4)
    i = max(range(3), key=lambda k: r[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = math.sqrt(1 + r[i][i] - r[j][j] - r[k][k]) * 2
    q = [0.0, 0.0, 0.0]
    q[i], q[j], q[k] = s / 4, (r[j][i] + r[i][j]) / s, (r[k][i] + r[i][k]) / s
    return q[0], q[1], q[2], (r[k][j] - r[j][k]) / s


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("camera")
    ap.add_argument("--frames", type=int, default=12)
    ap.add_argument("--step", type=float, default=0.01, help="metres per frame along image right")
    a = ap.parse_args()
    with open(a.camera) as f:
        m = json.load(f)["cam_to_world"]
    r = [row[:3] for row in m[:3]]
    p = [row[3] for row in m[:3]]
    qx, qy, qz, qw = quaternion(r)
    right = [r[0][0], r[1][0], r[2][0]]
    print("# timestamp tx ty tz qx qy qz qw (T_world_camera), ending at " + a.camera)
    for k in range(a.frames):
        off = (k - (a.frames - 1)) * a.step
        x, y, z = (p[i] + off * right[i] for i in range(3))
        print(f"{1 + k * 0.04:.6f} {x:.6f} {y:.6f} {z:.6f} {qx:.9f} {qy:.9f} {qz:.9f} {qw:.9f}")


main()
