"""Side-by-side PNG of linear EXR renders (run inside Blender's Python, which has NumPy):

    blender -b --factory-startup -P bench/side_by_side.py -- OUT.png [--scale 2] \\
        [--exposure-ev -1] [--crop x0,y0,w,h] [--columns N] a.exr b.exr ...

Every image gets the same exposure (stops), is clipped to [0, 1] and sRGB-encoded, is scaled by
nearest neighbour (each pixel stays visible), and is optionally cropped (pixels, from the top
left), then the images are put side by side, left to right in the order given (rows of N with
--columns N, all of one size). PNG inputs are sRGB-decoded on loading and encoded again, so they
come out as they are. OUT ending in .jpg is written as JPEG, else PNG.
"""
import argparse
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_images import load  # noqa: E402


def srgb(x):
    x = np.clip(x, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def main():
    ap = argparse.ArgumentParser(prog="side_by_side.py")
    ap.add_argument("out")
    ap.add_argument("images", nargs="+")
    ap.add_argument("--scale", type=int, default=1)
    ap.add_argument("--exposure-ev", type=float, default=0.0)
    ap.add_argument("--crop")
    ap.add_argument("--columns", type=int, default=0)
    a = ap.parse_args(sys.argv[sys.argv.index("--") + 1:])
    tiles = []
    for f in a.images:
        px = load(f)[:, :, :3]
        if a.crop:
            x0, y0, cw, ch = (int(v) for v in a.crop.split(","))
            px = px[y0:y0 + ch, x0:x0 + cw]
        px = srgb(px * 2.0 ** a.exposure_ev)
        tiles.append(np.repeat(np.repeat(px, a.scale, 0), a.scale, 1))
    cols = a.columns if a.columns > 0 else len(tiles)
    while len(tiles) % cols:
        tiles.append(np.ones_like(tiles[0]))
    rows = []
    for r in range(0, len(tiles), cols):
        gap = np.ones((tiles[0].shape[0], 4, 3))
        rows.append(np.concatenate(sum(([t, gap] for t in tiles[r:r + cols]), [])[:-1], axis=1))
    vgap = np.ones((4, rows[0].shape[1], 3))
    row = np.concatenate(sum(([x, vgap] for x in rows), [])[:-1], axis=0)[::-1]
    h, w = row.shape[:2]
    out = bpy.data.images.new("side_by_side", w, h)
    out.colorspace_settings.name = "Non-Color"  # already encoded
    out.pixels = np.concatenate([row, np.ones((h, w, 1))], axis=2).ravel()
    out.filepath_raw = a.out
    out.file_format = "JPEG" if a.out.lower().endswith((".jpg", ".jpeg")) else "PNG"
    out.save()


main()
