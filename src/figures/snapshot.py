#!/usr/bin/env python3
"""A vector snapshot (.svg or .pdf) of the inspector's main view: its draw list as a table (render/draw_list.h)
drawn as circles, regular polygons and paths, with a caption; text stays text in the SVG. With a key file
(tab-separated lines from the inspector: background, info, species, arch, colorbar, scale) the picture gets what
the bitmap pictures have, as vector elements: an information box and a legend beside it, a colour bar, a scale
bar on the picture, and a dark background when the inspector's is dark.

    python3 snapshot.py TABLE.csv OUT WIDTH_M HEIGHT_M CAPTION VERSION [KEY.tsv]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import siloscope  # noqa: E402
from siloscope._tables import read_table  # noqa: E402

import gallery  # noqa: E402  the tile drawing, shared
from look import Look, read_key  # noqa: E402
import matplotlib  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from guard import guarded  # noqa: E402  one line, never a traceback


def draw_key(fig, ax, side, key, width_m, height_m):
    ink = "#eeeeee" if key["background"] == "dark" else "#111111"
    fs = key["font_scale"]
    side.axis("off")
    y = 1.0
    for text in key["info"]:
        side.text(0.0, y, text, fontsize=7 * fs, color=ink, va="top", ha="left", transform=side.transAxes)
        y -= 0.04
    handles = [Line2D([], [], marker="o", linestyle="", markersize=7, markerfacecolor=c, markeredgecolor="#555555",
                      label=name) for name, c in key["species"]]
    handles += [Line2D([], [], marker="o", linestyle="", markersize=8, markerfacecolor="none", markeredgecolor=c,
                       markeredgewidth=2, label=name) for name, c in key["arch"]]
    if handles:
        legend = side.legend(handles=handles, loc="upper left", bbox_to_anchor=(0.0, y - 0.02), frameon=False,
                             fontsize=7 * fs, labelcolor=ink)
        legend.set_in_layout(False)
        y -= 0.045 * len(handles) + 0.04
    if key["colorbar"]:
        label, lo, hi, cmap = key["colorbar"]
        pos = side.get_position()
        bar = fig.add_axes([pos.x0, pos.y0 + pos.height * max(0.05, y - 0.06), pos.width * 0.9, 0.025])
        cb = fig.colorbar(matplotlib.cm.ScalarMappable(norm=matplotlib.colors.Normalize(lo, hi), cmap=cmap),
                          cax=bar, orientation="horizontal")
        cb.set_label(label, fontsize=7 * fs, color=ink)
        cb.ax.tick_params(labelsize=6 * fs, colors=ink)
    draw_scale(ax, key, width_m, height_m)


def draw_scale(ax, key, width_m, height_m):
    if not key["scale"]:
        return
    ink = "#eeeeee" if key["background"] == "dark" else "#111111"
    d, text = key["scale"]
    x0, y0 = -0.5 * width_m + 0.04 * width_m, -0.5 * height_m + 0.05 * height_m
    ax.plot([x0, x0 + d], [y0, y0], color=ink, lw=2.5, solid_capstyle="butt")
    ax.text(x0, y0 + 0.015 * height_m, text, fontsize=7 * key["font_scale"], color=ink, va="bottom", ha="left")


def main(table, out, width_m, height_m, caption, version, key_path=None):
    try:
        rows = read_table(table, ("kind", "x", "y"))
    except siloscope.SiloscopeError as e:
        print(f"snapshot: {e}", file=sys.stderr)
        sys.exit(2)
    key = read_key(key_path, "snapshot") if key_path else None
    width_in = 7.0
    height_in = width_in * height_m / width_m + 0.5
    side_panel = bool(key) and bool(key["info"] or key["species"] or key["arch"] or key["colorbar"])
    if side_panel:
        fig, (ax, side) = plt.subplots(1, 2, figsize=(width_in + 2.4, height_in),
                                       gridspec_kw={"width_ratios": [width_in, 2.4]})
    else:
        fig, ax = plt.subplots(figsize=(width_in, height_in))
    dark = bool(key) and key["background"] == "dark"
    gallery.draw_tile(ax, rows, width_m, height_m, width_in, look=Look("background=dark" if dark else ""))
    if dark:
        fig.patch.set_facecolor("#121217")
        ax.set_facecolor("#121217")
    ax.set_title(caption, fontsize=8 * (key["font_scale"] if key else 1), color="#eeeeee" if dark else "black")
    if side_panel:
        draw_key(fig, ax, side, key, width_m, height_m)
    elif key:
        draw_scale(ax, key, width_m, height_m)
    tag = f"siloscope snapshot {version}"
    meta = {"CreationDate": None, "ModDate": None, "Creator": tag} if out.endswith(".pdf") else \
        {"Date": None, "Creator": tag}
    fig.savefig(out, metadata=meta, bbox_inches="tight", pad_inches=0.05, facecolor=fig.get_facecolor())


if __name__ == "__main__":
    if len(sys.argv) not in (7, 8):
        sys.exit(__doc__)
    guarded("snapshot", lambda: main(sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5],
                                     sys.argv[6], sys.argv[7] if len(sys.argv) == 8 else None))
