#!/usr/bin/env python3
"""The arch gallery sheet of `siloscope gallery`: tiles (PNG) and their index.csv -> one PDF, SVG or PNG.

    python3 gallery.py TILES_DIR OUT TITLE VERSION [COLUMNS]
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import siloscope  # noqa: E402  one reader of siloscope's files
from siloscope._tables import read_table  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

plt.rcParams.update({"svg.hashsalt": "siloscope", "font.size": 8})


def main(tiles, out, title, version, columns=0):
    try:
        rows = read_table(os.path.join(tiles, "index.csv"), ("tile", "t_s")).astype(str).to_dict("records")
    except siloscope.SiloscopeError as e:
        print(f"gallery: {e}", file=sys.stderr)
        sys.exit(2)
    n = len(rows)
    cols = columns if columns > 0 else max(1, math.ceil(math.sqrt(n)))
    nrows = math.ceil(n / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(2.2 * cols, 2.5 * nrows + 0.4), squeeze=False)
    for k, ax in enumerate(axes.flat):
        ax.axis("off")
        if k >= n:
            continue
        r = rows[k]
        ax.imshow(mpimg.imread(os.path.join(tiles, r["tile"])))
        shorthand = set(r["species"].split(";")) <= {"original", "added"}
        who = f"{r['members']} disks ({r['added']} added)" if shorthand else f"{r['members']} grains"
        ax.set_title(f"#{k + 1}  t = {float(r['t_s']):.2f} s, clog {float(r['clog_s']):.1f} s\n"
                     f"{who}, span {100 * float(r['span_m']):.0f} cm", fontsize=7)
    fig.suptitle(title, fontsize=9)
    fig.text(0.99, 0.003, f"siloscope {version}; members gold, bonds dark; the state one time step before the "
             f"clog rule removed each arch", ha="right", va="bottom", fontsize=6, color="#444444")
    fig.tight_layout(rect=(0, 0.02, 1, 0.97))
    # The creator tag lets `siloscope gallery --force` recognise its own sheet (and nothing else).
    tag = f"siloscope gallery {version}"
    if out.endswith(".pdf"):
        meta = {"CreationDate": None, "ModDate": None, "Creator": tag}
    elif out.endswith(".svg"):
        meta = {"Date": None, "Creator": tag}
    else:
        meta = {"Software": tag}
    fig.savefig(out, dpi=150, metadata=meta)


if __name__ == "__main__":
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]) if len(sys.argv) > 5 else 0)
