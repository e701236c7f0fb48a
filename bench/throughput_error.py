"""The error of Cycles at 256 spp and of our frames, each against its own renderer's truth, for
bench/throughput.sh (issue 14: "a 640x480 apartment frame reaching the error of Cycles at 256
spp"). Run inside Blender's Python, which has NumPy:

    blender -b --factory-startup -P bench/throughput_error.py -- --peer A.exr B.exr \\
        [--peer256 C.exr] --refs R1.exr R2.exr [--label nyu.png] [--json out.json] OURS.exr...

No converged image is needed. A and B are Cycles at the same spp n with two seeds, R1 and R2
ours at high spp with two seeds; every image is unbiased, the two of a pair independent:
  Cycles' variance at n spp     (A - B)^2 / 2 per pixel and channel, at 256 spp that times n / 256
                                (independent samples: variance falls as 1 / spp)
  our error of x                (x - R)^2 - (R1 - R2)^2 / 4, R = (R1 + R2) / 2: E (x - R)^2 is
                                the error plus Var R, and E (R1 - R2)^2 = 4 Var R
  the scale                     sum m^2 - sum (A - B)^2 / 4 for Cycles (m = (A + B) / 2), the
                                same with R1, R2 for ours: sum T^2 without the images' noise
rel_rmse is sqrt(sum error / scale) over every pixel and channel (and over walls, floors and
ceilings with --label), so the two renderers are compared in relative terms: their means differ
by the material mapping (docs/rendering.md, "Mean radiance").
--peer256 checks the 1 / spp step: with C at 256 spp (another seed), (C - A)^2 - (A - B)^2 / 2
estimates C's own variance. Seconds are read from OURS.t beside each image when it exists. Every figure comes twice, as is
and despeckled (keys ending in _despeckled: every image first cleared of pixels brighter than
10x their 3x3 median), because a single firefly can dominate a sum of squares.
Prints one line "THR_JSON {...}".
"""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_images import load, load_labels  # noqa: E402


def rgb(path):
    return load(path)[:, :, :3].astype(np.float64)


def despeckled(img):
    """Each pixel brighter than 10x the median luminance of its 3x3 neighbourhood scaled down to
    it: the robust variant, which takes the fireflies out of both renderers' figures."""
    lum = img @ np.array([0.2126, 0.7152, 0.0722])
    p = np.pad(lum, 1, mode="edge")
    h, w = lum.shape
    med = np.median(np.stack([p[y:y + h, x:x + w] for y in range(3) for x in range(3)]), axis=0)
    cap = 10 * med + 1e-6
    return img * np.minimum(1.0, cap / np.maximum(lum, 1e-30))[:, :, None]


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="throughput_error.py")
    ap.add_argument("--peer", nargs=2, required=True)
    ap.add_argument("--peer-spp", type=int, default=64)
    ap.add_argument("--peer256")
    ap.add_argument("--refs", nargs=2, required=True)
    ap.add_argument("--label")
    ap.add_argument("--json")
    ap.add_argument("ours", nargs="*")
    a = ap.parse_args(argv)
    regions = {"all": None}
    if a.label:
        regions["flat"] = np.isin(load_labels(a.label), [1, 2, 22])
    paths = list(a.peer) + list(a.refs) + ([a.peer256] if a.peer256 else []) + a.ours
    images = {p: rgb(p) for p in paths}  # read once, used as is and despeckled
    out = {}
    for variant, prep in (("", lambda x: x), ("_despeckled", despeckled)):
        figures(a, regions, lambda p: prep(images[p]), variant, out)
    print("THR_JSON " + json.dumps(out))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)


def rel(err, scale, mask):
    """sqrt(sum err / sum scale) over the pixels of mask (None: all)."""
    e, s = (err, scale) if mask is None else (err[mask], scale[mask])
    return float(np.sqrt(max(e.sum(), 0.0) / max(s.sum(), 1e-30)))


def figures(a, regions, image, variant, out):
    """Adds the figures of every image (image(path): the prepared pixels) as keys + variant."""
    A, B = (image(p) for p in a.peer)
    m = (A + B) / 2
    cyc_scale = m ** 2 - (A - B) ** 2 / 4
    var256 = (A - B) ** 2 / 2 * a.peer_spp / 256
    out["cycles256" + variant] = {k: rel(var256, cyc_scale, r) for k, r in regions.items()}
    if a.peer256:
        C = image(a.peer256)
        measured = (C - A) ** 2 - (A - B) ** 2 / 2
        out["cycles256_measured" + variant] = {k: rel(measured, cyc_scale, r)
                                               for k, r in regions.items()}
    R1, R2 = (image(p) for p in a.refs)
    R = (R1 + R2) / 2
    ref_var = (R1 - R2) ** 2 / 4
    scale = R ** 2 - ref_var
    out["ours_reference_noise" + variant] = {k: rel(ref_var, scale, r) for k, r in regions.items()}
    for path in a.ours:
        x = image(path)
        if x.shape != R.shape:
            sys.exit(f"throughput_error.py: {path}: {x.shape[1]}x{x.shape[0]}, the references "
                     f"are {R.shape[1]}x{R.shape[0]}")
        err = (x - R) ** 2 - ref_var
        row = {k: rel(err, scale, r) for k, r in regions.items()}
        t = os.path.splitext(path)[0] + ".t"
        if os.path.exists(t):
            with open(t) as f:
                row["seconds"] = float(f.read().split()[-1])
        out[os.path.basename(path) + variant] = row


main()
