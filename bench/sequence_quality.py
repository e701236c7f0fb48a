"""Noise, blotches and flicker of a rendered sequence against high-spp reference frames of the
same poses (issue 14's acceptance figures; run inside Blender's Python, which has NumPy):

    blender -b --factory-startup -P bench/sequence_quality.py -- --seq OURS_SEQ --ref REF_SEQ \\
        [--ref2 REF2_SEQ] [--twin TWIN_SEQ] [--json out.json]

OURS_SEQ is a folder written by `interiornet generate --hdr --passes rgb,depth,label,flow
--format asl`; REF_SEQ one written for some of its poses (the same timestamps) at high spp and
another seed (`--trajectory OURS_SEQ/state_groundtruth_estimate0/data.csv` rows). REF2_SEQ, a
second reference of the same poses with a third seed, takes the references' own noise out: with
A and B independent and unbiased, E|x - A|^2 = E|x - T|^2 + Var A and E|A - B|^2 = 2 Var A, so
|x - T|^2 is estimated by |x - A|^2 - |A - B|^2 / 2 (summed over the region; rel_rmse_flat_true).

Per frame that has a reference, over the flat diffuse regions of the label pass (walls 1, floors
2, ceilings 22, NYU40), on linear RGB:
  rel_rmse  sqrt(sum (x - r)^2 / sum r^2), every channel of every flat pixel
  blotch    the largest 4-connected group of flat pixels whose 3x3-box-filtered luminance is
            more than 10 % off the reference's (3x3 box too), in pixels
With REF2_SEQ also: rel_rmse_flat_true split into _edges (flat pixels with another class in
their 3x3 label neighbourhood, whose footprint holds two surfaces) and _interior, with the edges'
share of the squared error (flat_edge_error_share); largest_blotch_interior_px leaves the edges
out; ref_largest_blotch_px is the second reference's blotch against the first (the measure's
own floor) and largest_blotch_vs_mean_px ours against the mean of both references.
With TWIN_SEQ, the same sequence rendered with another seed (the same poses), the true error is
split into our noise (rel_rmse_flat_noise: |x - y|^2 / 2, x and y independent) and the bias both
runs share (rel_rmse_flat_bias: what the true error holds beyond the noise), over all flat pixels
and the interior (_interior); per class on the interior, the bias (rel_bias_walls, ...), the
part of it wider than 5 px (rel_bias_walls_5px: the differences box-filtered first) and the noise
(rel_noise_walls).
Over consecutive frames k, k+1 of OURS_SEQ (the flicker of the issue): the flat pixels of k whose
forward flow lands on a pixel of k+1 with the same label and a flat 3x3 label neighbourhood on
both sides; flicker = mean |L_k+1(x + flow) - L_k(x)| / mean L_k(x), luminance L (Rec. 709),
also per class (flicker_walls, _floors, _ceilings) and, where the sequence has the albedo pass
(`--passes ...,albedo`), on the light alone (flicker_light: colour / albedo, so the texture's
gradient under a sub-pixel reprojection does not count as flicker), and the measure's own floor
on the albedo pass, which is exact (flicker_albedo, per class too: what a perfect render gives).
The flicker_*bilinear* figures read frame k+1 bilinearly at x + flow instead of at the nearest
pixel, which takes most of the texture's gradient out of the measure's floor.
Specular light moves with the view, so a perfect render does not give 0 on a varnished floor.
Prints one line "SEQ_JSON {...}".
"""
import argparse
import glob
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_images import load, load_labels  # noqa: E402

FLAT = [1, 2, 22]
REC709 = np.array([0.2126, 0.7152, 0.0722])


def frames(seq):
    return sorted(os.path.basename(p)[:-4] for p in glob.glob(os.path.join(seq, "cam0/data/*.exr")))


def read_flo(path):
    with open(path, "rb") as f:
        tag = np.frombuffer(f.read(4), np.float32)[0]
        assert abs(tag - 202021.25) < 1e-3, path
        w, h = np.frombuffer(f.read(8), np.int32)
        uv = np.frombuffer(f.read(), np.float32).reshape(h, w, 2).astype(np.float64)
    valid = np.all(np.isfinite(uv) & (np.abs(uv) <= 1e9), axis=2)
    return np.where(valid[:, :, None], uv, 0.0), valid


def box3(a):
    p = np.pad(a, 1, mode="edge")
    h, w = a.shape
    return sum(p[dy:dy + h, dx:dx + w] for dy in range(3) for dx in range(3)) / 9.0


def box5(a):
    p = np.pad(a, 2, mode="constant")
    h, w = a.shape
    return sum(p[dy:dy + h, dx:dx + w] for dy in range(5) for dx in range(5)) / 25.0


def uniform3(label):
    p = np.pad(label, 1, mode="edge")
    h, w = label.shape
    return np.all(np.stack([p[dy:dy + h, dx:dx + w] == label for dy in range(3)
                            for dx in range(3)]), axis=0)


def largest_component(mask):
    """Size of the largest 4-connected True region (iterative flood fill)."""
    seen = np.zeros_like(mask, dtype=bool)
    h, w = mask.shape
    best = 0
    for y0, x0 in zip(*np.nonzero(mask)):
        if seen[y0, x0]:
            continue
        stack, n = [(y0, x0)], 0
        seen[y0, x0] = True
        while stack:
            y, x = stack.pop()
            n += 1
            for yy, xx in ((y - 1, x), (y + 1, x), (y, x - 1), (y, x + 1)):
                if 0 <= yy < h and 0 <= xx < w and mask[yy, xx] and not seen[yy, xx]:
                    seen[yy, xx] = True
                    stack.append((yy, xx))
        best = max(best, n)
    return best


BILINEAR_KEYS = tuple(f"flicker_{w}bilinear{c}" for w in ("", "light_", "albedo_")
                      for c in ("", "_walls", "_floors", "_ceilings"))


def flicker_bilinear(seq, names, img, lab, albedo, out):
    """The flicker measure with frame k+1 read bilinearly at x + flow instead of at the nearest
    pixel: nearest-pixel reading differs by up to half a pixel of the texture's gradient even in
    a perfect render (flicker_albedo), bilinear reading by its curvature only. A pixel counts
    where its 3x3 label neighbourhood is flat and uniform in frame k and the four pixels read in
    frame k+1 have its label and uniform 3x3 neighbourhoods."""
    for key in BILINEAR_KEYS:
        out[key] = {}
    for k in range(len(names) - 1):
        n0, n1 = names[k], names[k + 1]
        flo = os.path.join(seq, "flow0/data", n0 + ".flo")
        if not os.path.exists(flo):
            continue
        uv, valid = read_flo(flo)
        h, w = valid.shape
        ys, xs = np.mgrid[0:h, 0:w]
        px, py = xs + uv[:, :, 0], ys + uv[:, :, 1]  # pixel-centre coordinates in frame k+1
        x0, y0 = np.floor(px).astype(int), np.floor(py).astype(int)
        fx, fy = px - x0, py - y0
        inside = valid & (x0 >= 0) & (x0 + 1 < w) & (y0 >= 0) & (y0 + 1 < h)
        x0c, y0c = np.clip(x0, 0, w - 2), np.clip(y0, 0, h - 2)
        l0, l1 = lab[n0], lab[n1]
        u1 = uniform3(l1)
        ok = inside & np.isin(l0, FLAT) & uniform3(l0)
        for dy in (0, 1):
            for dx in (0, 1):
                ok &= (l1[y0c + dy, x0c + dx] == l0) & u1[y0c + dy, x0c + dx]

        def read(a1):
            return ((1 - fy) * ((1 - fx) * a1[y0c, x0c] + fx * a1[y0c, x0c + 1])
                    + fy * ((1 - fx) * a1[y0c + 1, x0c] + fx * a1[y0c + 1, x0c + 1]))

        fields = [("", img[n0] @ REC709, img[n1] @ REC709)]
        a0, a1 = albedo.get(n0), albedo.get(n1)
        if a0 is not None and a1 is not None:
            fields.append(("light_", (img[n0] / np.maximum(a0, 0.01)) @ REC709,
                           (img[n1] / np.maximum(a1, 0.01)) @ REC709))
            fields.append(("albedo_", a0 @ REC709, a1 @ REC709))
        for tag, f0, f1 in fields:
            d = np.abs(read(f1) - f0)
            if ok.any():
                out[f"flicker_{tag}bilinear"][n0] = float(d[ok].mean() / max(f0[ok].mean(), 1e-12))
            for cls, name in zip(FLAT, ("walls", "floors", "ceilings")):
                m = ok & (l0 == cls)
                if m.sum() > 100:
                    out[f"flicker_{tag}bilinear_{name}"][n0] = float(d[m].mean() / max(f0[m].mean(), 1e-12))


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="sequence_quality.py")
    ap.add_argument("--seq", required=True)
    ap.add_argument("--ref")
    ap.add_argument("--ref2")
    ap.add_argument("--twin")
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    names = frames(a.seq)
    if not names:
        sys.exit(f"sequence_quality.py: no cam0/data/*.exr in {a.seq} (generate --hdr)")
    out = {"frames": {}, "flicker": {}, "flicker_walls": {}, "flicker_floors": {},
           "flicker_ceilings": {}, "flicker_light": {}, "flicker_albedo": {},
           "flicker_albedo_walls": {}, "flicker_albedo_floors": {}, "flicker_albedo_ceilings": {}}
    img = {n: load(os.path.join(a.seq, "cam0/data", n + ".exr"))[:, :, :3] for n in names}
    lab = {n: load_labels(os.path.join(a.seq, "label0/data", n + "_nyu.png")) for n in names}
    albedo = {}  # the albedo pass where it was written (generate --passes ...,albedo)
    for n in names:
        p = os.path.join(a.seq, "albedo0/data", n + ".png")
        if os.path.exists(p):
            albedo[n] = load(p)[:, :, :3]
    for n in frames(a.ref) if a.ref else []:
        if n not in img:
            continue
        x, r = img[n], load(os.path.join(a.ref, "cam0/data", n + ".exr"))[:, :, :3]
        flat = np.isin(lab[n], FLAT)
        d = (x - r)[flat]
        lx, lr = box3(x @ REC709), box3(r @ REC709)
        bad = flat & (np.abs(lx - lr) > 0.1 * np.maximum(lr, 1e-6))
        out["frames"][n] = {
            "rel_rmse_flat": float(np.sqrt(np.sum(d ** 2) / np.sum(r[flat] ** 2))),
            "rel_rmse_all": float(np.sqrt(np.sum((x - r) ** 2) / np.sum(r ** 2))),
            "largest_blotch_px": int(largest_component(bad)),
            "flat_pixels": int(flat.sum())}
        r2_path = os.path.join(a.ref2, "cam0/data", n + ".exr") if a.ref2 else ""
        if r2_path and os.path.exists(r2_path):
            r2 = load(r2_path)[:, :, :3]
            # the blotch measure's own floor: the second reference against the first, and ours
            # against the mean of both (half the references' noise variance)
            l2 = box3(r2 @ REC709)
            out["frames"][n]["ref_largest_blotch_px"] = int(largest_component(
                flat & (np.abs(l2 - lr) > 0.1 * np.maximum(lr, 1e-6))))
            lm = (lr + l2) / 2
            out["frames"][n]["largest_blotch_vs_mean_px"] = int(largest_component(
                flat & (np.abs(lx - lm) > 0.1 * np.maximum(lm, 1e-6))))
            ref_noise = np.sum((r - r2)[flat] ** 2) / 2
            out["frames"][n]["ref_rel_rmse_flat"] = float(np.sqrt(ref_noise / np.sum(r[flat] ** 2)))
            true = max(np.sum(d ** 2) - ref_noise, 0.0)
            out["frames"][n]["rel_rmse_flat_true"] = float(np.sqrt(true / np.sum(r[flat] ** 2)))
            # the same split at class edges: flat pixels with another class in their 3x3 label
            # neighbourhood (a pixel's footprint there holds two surfaces) and the rest
            e2 = np.sum((x - r) ** 2, axis=2) - np.sum((r - r2) ** 2, axis=2) / 2
            edge = flat & ~uniform3(lab[n])
            for part, m in (("edges", edge), ("interior", flat & ~edge)):
                out["frames"][n][f"rel_rmse_flat_true_{part}"] = float(
                    np.sqrt(max(e2[m].sum(), 0.0) / max(np.sum(r[m] ** 2), 1e-30)))
            out["frames"][n]["flat_edge_pixels"] = int(edge.sum())
            y_path = os.path.join(a.twin, "cam0/data", n + ".exr") if a.twin else ""
            if y_path and os.path.exists(y_path):
                # the twin is the same sequence rendered with another seed: |x - y|^2 / 2 is our
                # noise variance, and what the true error holds beyond it is bias, which both
                # runs share (the denoiser's blur, the reuse's lag)
                y = load(y_path)[:, :, :3]
                v2 = np.sum((x - y) ** 2, axis=2) / 2
                for part, m in (("", flat), ("_interior", flat & ~edge)):
                    norm = max(np.sum(r[m] ** 2), 1e-30)
                    out["frames"][n][f"rel_rmse_flat_noise{part}"] = float(np.sqrt(v2[m].sum() / norm))
                    out["frames"][n][f"rel_rmse_flat_bias{part}"] = float(
                        np.sqrt(max(e2[m].sum() - v2[m].sum(), 0.0) / norm))
                # the interior's bias per class and at two scales: (x - A)(y - B) has the mean
                # b^2 (x, y share the bias b, A, B are unbiased, all four independent), and
                # the same product of the differences box-filtered over 5x5 pixels of the class
                # (b's 5-px mean squared): what is left at 5 px is the shading's, what goes is
                # pixel-scale (texture detail, a seam)
                inner = flat & ~edge
                for cls, name in zip(FLAT, ("walls", "floors", "ceilings")):
                    m = inner & (lab[n] == cls)
                    if m.sum() < 100:
                        continue
                    norm = np.sum(r[m] ** 2)
                    out["frames"][n][f"rel_bias_{name}"] = float(np.sqrt(max(
                        np.sum((x - r) * (y - r2), axis=2)[m].sum(), 0.0) / norm))
                    mf = m.astype(np.float64)
                    cnt = np.maximum(box5(mf), 1e-9)
                    dx = np.stack([box5((x - r)[:, :, c] * mf) for c in range(3)], axis=2) / cnt[:, :, None]
                    dy = np.stack([box5((y - r2)[:, :, c] * mf) for c in range(3)], axis=2) / cnt[:, :, None]
                    out["frames"][n][f"rel_bias_{name}_5px"] = float(np.sqrt(max(
                        np.sum(dx * dy, axis=2)[m].sum(), 0.0) / norm))
                    out["frames"][n][f"rel_noise_{name}"] = float(np.sqrt(v2[m].sum() / norm))
            out["frames"][n]["flat_edge_error_share"] = float(max(e2[edge].sum(), 0.0) / max(true, 1e-30))
            out["frames"][n]["largest_blotch_interior_px"] = int(largest_component(bad & ~edge))
    for k in range(len(names) - 1):
        n0, n1 = names[k], names[k + 1]
        flo = os.path.join(a.seq, "flow0/data", n0 + ".flo")
        if not os.path.exists(flo):
            continue
        uv, valid = read_flo(flo)
        h, w = valid.shape
        ys, xs = np.mgrid[0:h, 0:w]
        tx = np.floor(xs + 0.5 + uv[:, :, 0]).astype(int)
        ty = np.floor(ys + 0.5 + uv[:, :, 1]).astype(int)
        inside = valid & (tx >= 0) & (tx < w) & (ty >= 0) & (ty < h)
        txc, tyc = np.clip(tx, 0, w - 1), np.clip(ty, 0, h - 1)
        l0, l1 = lab[n0], lab[n1]
        ok = (inside & np.isin(l0, FLAT) & uniform3(l0) & (l1[tyc, txc] == l0)
              & uniform3(l1)[tyc, txc])
        L0, L1 = img[n0] @ REC709, img[n1] @ REC709
        diff = np.abs(L1[tyc, txc] - L0)[ok]
        out["flicker"][n0] = float(diff.mean() / max(L0[ok].mean(), 1e-12)) if ok.any() else None
        for cls, name in zip(FLAT, ("walls", "floors", "ceilings")):
            m = ok & (l0 == cls)
            if m.sum() > 100:
                d = np.abs(L1[tyc, txc] - L0)[m]
                out["flicker_" + name].setdefault(n0, float(d.mean() / max(L0[m].mean(), 1e-12)))
        # the same on the light alone (colour / albedo, texture divided out): nearest-pixel
        # reprojection of a textured surface differs by its texture's gradient even when exact
        a0, a1 = albedo.get(n0), albedo.get(n1)
        if a0 is not None and a1 is not None:
            S0 = (img[n0] / np.maximum(a0, 0.01)) @ REC709
            S1 = (img[n1] / np.maximum(a1, 0.01)) @ REC709
            d = np.abs(S1[tyc, txc] - S0)[ok]
            out["flicker_light"][n0] = float(d.mean() / max(S0[ok].mean(), 1e-12)) if ok.any() else None
            # the measure's own floor: the albedo is exact, so what it gives is the texture's
            # gradient under the nearest-pixel reprojection, flicker no renderer can remove
            A0, A1 = a0 @ REC709, a1 @ REC709
            d = np.abs(A1[tyc, txc] - A0)
            out["flicker_albedo"][n0] = float(d[ok].mean() / max(A0[ok].mean(), 1e-12)) if ok.any() else None
            for cls, name in zip(FLAT, ("walls", "floors", "ceilings")):
                m = ok & (l0 == cls)
                if m.sum() > 100:
                    out["flicker_albedo_" + name][n0] = float(d[m].mean() / max(A0[m].mean(), 1e-12))
    flicker_bilinear(a.seq, names, img, lab, albedo, out)
    for key in ("flicker", "flicker_walls", "flicker_floors", "flicker_ceilings", "flicker_light",
                "flicker_albedo", "flicker_albedo_walls", "flicker_albedo_floors",
                "flicker_albedo_ceilings") + BILINEAR_KEYS:
        fl = [v for v in out[key].values() if v is not None]
        out["mean_" + key] = float(np.mean(fl)) if fl else None
    for key in ("rel_rmse_flat", "rel_rmse_flat_true", "rel_rmse_flat_true_edges",
                "rel_rmse_flat_true_interior", "rel_rmse_flat_noise", "rel_rmse_flat_bias",
                "rel_rmse_flat_noise_interior", "rel_rmse_flat_bias_interior") + tuple(
                    f"rel_{kind}_{name}{scale}" for name in ("walls", "floors", "ceilings")
                    for kind, scale in (("bias", ""), ("bias", "_5px"), ("noise", ""))):
        rr = [f[key] for f in out["frames"].values() if key in f]
        out["mean_" + key] = float(np.mean(rr)) if rr else None
    print("SEQ_JSON " + json.dumps(out))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)


main()
