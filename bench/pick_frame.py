"""Index (from 0) of the label image that shows the most NYU40 classes, each on at least 0.5 %
of the pixels, ties going to the earlier frame (run inside Blender's Python, which has NumPy):

    blender -b --factory-startup -P bench/pick_frame.py -- label0/data/*_nyu.png

Prints "PICK <index> <classes>". bench/apartment_compare.sh uses it to skip frames that look
at a bare wall.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_images import load_labels  # noqa: E402

best, best_n = 0, -1
for i, f in enumerate(sys.argv[sys.argv.index("--") + 1:]):
    lab = load_labels(f)
    counts = np.bincount(lab.ravel(), minlength=41)
    n = int((counts[1:] >= 0.005 * lab.size).sum())
    if n > best_n:
        best, best_n = i, n
print(f"PICK {best} {best_n}")
