#!/usr/bin/env python3
"""A vector snapshot (.svg or .pdf) of the inspector's main view: its draw list as a table (render/draw_list.h)
drawn as circles, regular polygons and paths, with a caption; text stays text in the SVG.

    python3 snapshot.py TABLE.csv OUT WIDTH_M HEIGHT_M CAPTION VERSION
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import siloscope  # noqa: E402
from siloscope._tables import read_table  # noqa: E402

import gallery  # noqa: E402  the tile drawing, shared
import matplotlib.pyplot as plt  # noqa: E402


def main(table, out, width_m, height_m, caption, version):
    try:
        rows = read_table(table, ("kind", "x", "y"))
    except siloscope.SiloscopeError as e:
        print(f"snapshot: {e}", file=sys.stderr)
        sys.exit(2)
    width_in = 7.0
    fig, ax = plt.subplots(figsize=(width_in, width_in * height_m / width_m + 0.5))
    gallery.draw_tile(ax, rows, width_m, height_m, width_in)
    ax.set_title(caption, fontsize=8)
    tag = f"siloscope snapshot {version}"
    meta = {"CreationDate": None, "ModDate": None, "Creator": tag} if out.endswith(".pdf") else \
        {"Date": None, "Creator": tag}
    fig.savefig(out, metadata=meta, bbox_inches="tight", pad_inches=0.05)


if __name__ == "__main__":
    if len(sys.argv) != 7:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5], sys.argv[6])
