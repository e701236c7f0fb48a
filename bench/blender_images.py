"""Images as NumPy arrays inside Blender's Python, for the bench scripts run with `blender -P`
(compare_renders.py, side_by_side.py, pick_frame.py)."""
import bpy
import numpy as np


def load(path, non_color=False):
    """H x W x C float64 pixels of an image file, row 0 at the top. EXR stays linear; with
    non_color a PNG's values are read as stored (labels), not sRGB-decoded."""
    img = bpy.data.images.load(path, check_existing=False)
    if non_color:
        img.colorspace_settings.name = "Non-Color"
    w, h = img.size
    return np.array(img.pixels[:], dtype=np.float64).reshape(h, w, img.channels)[::-1]


def load_labels(path):
    """Our 8-bit label PNG (NYU40 class per pixel) as integers, row 0 at the top."""
    return np.rint(load(path, non_color=True)[:, :, 0] * 255).astype(int)
