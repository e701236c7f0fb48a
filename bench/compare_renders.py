"""Error and radiance of renders of one view, region by region (run inside Blender's Python,
which has NumPy):

    blender -b --factory-startup -P bench/compare_renders.py -- --label label_nyu.png \\
        --pair ours:ours_16.exr:ours_ref.exr:SECONDS --pair cycles:cyc_16.exr:cyc_ref.exr:SECONDS \\
        --refs ours_ref.exr cyc_ref.exr [--json out.json]

--pair NAME:IMAGE:REFERENCE:SECONDS  an equal-spp render, its own high-spp reference and the
    time it took; reports relMSE = mean over pixels and channels of (x - r)^2 / (r^2 + 0.01)
    (robust to the sun patches that dominate a plain MSE), plain MSE, and the efficiency
    1 / (relMSE x seconds).
--refs A B  the two renderers' references: mean luminance (Rec. 709) per region and A / B - 1,
    also after despeckling both (a pixel more than 10x its 3x3 median takes that median).
--label  our NYU40 label pass of the same view (8-bit PNG, class per pixel): regions walls (1),
    floor (2), ceiling (22), windows (9), everything else, and all pixels.
Prints one line "CMP_JSON {...}".
"""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_images import load, load_labels  # noqa: E402

REGIONS = {"wall": [1], "floor": [2], "ceiling": [22], "window": [9]}


def despeckle(lum):
    """Pixels more than 10x the median of their 3x3 neighbourhood (+0.01) replaced by that
    median: the rare fireflies a finite reference keeps, which would bias a region's mean."""
    p = np.pad(lum, 1, mode="edge")
    h, w = lum.shape
    med = np.median(np.stack([p[dy:dy + h, dx:dx + w] for dy in range(3) for dx in range(3)]),
                    axis=0)
    return np.where(lum > 10 * med + 0.01, med, lum)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="compare_renders.py")
    ap.add_argument("--label", required=True)
    ap.add_argument("--pair", action="append", default=[])
    ap.add_argument("--refs", nargs=2)
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    label = load_labels(a.label)
    masks = {k: np.isin(label, v) for k, v in REGIONS.items()}
    masks["other"] = ~np.any(np.stack(list(masks.values())), axis=0)
    masks["all"] = np.ones_like(label, dtype=bool)
    masks["flat"] = np.isin(label, [1, 2, 22])
    out = {"pairs": {}, "regions": {k: int(m.sum()) for k, m in masks.items()}}
    for spec in a.pair:
        name, img, ref, secs = spec.split(":")
        x, r = load(img)[:, :, :3], load(ref)[:, :, :3]
        rel = (x - r) ** 2 / (r ** 2 + 0.01)
        res = {"seconds": float(secs)}
        for k in ("all", "flat"):
            m = masks[k]
            res[f"relmse_{k}"] = float(rel[m].mean()) if m.any() else None
            res[f"mse_{k}"] = float(((x - r) ** 2)[m].mean()) if m.any() else None
            # relative RMSE of the region's mean-normalised error, as the "2 %" reads
            res[f"rel_rmse_{k}"] = float(np.sqrt(((x - r) ** 2)[m].mean()) / r[m].mean()) \
                if m.any() and r[m].mean() > 0 else None
        res["efficiency"] = 1.0 / (res["relmse_all"] * float(secs))
        out["pairs"][name] = res
    if a.refs:
        lum = np.array([0.2126, 0.7152, 0.0722])
        ra, rb = load(a.refs[0])[:, :, :3] @ lum, load(a.refs[1])[:, :, :3] @ lum
        da, db = despeckle(ra), despeckle(rb)
        out["refs"] = {}
        for k, m in masks.items():
            if not m.any():
                continue
            ma, mb = float(ra[m].mean()), float(rb[m].mean())
            sa, sb = float(da[m].mean()), float(db[m].mean())
            out["refs"][k] = {"a": ma, "b": mb, "a_over_b_minus_1": ma / mb - 1 if mb > 0 else None,
                              "despeckled_a_over_b_minus_1": sa / sb - 1 if sb > 0 else None,
                              "despeckled_pixels_a": int((da != ra)[m].sum()),
                              "despeckled_pixels_b": int((db != rb)[m].sum())}
    line = json.dumps(out)
    print("CMP_JSON " + line)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)


main()
