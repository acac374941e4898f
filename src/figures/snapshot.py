#!/usr/bin/env python3
"""A vector snapshot (.svg or .pdf) of the inspector's main view: its draw list as a table (render/draw_list.h)
drawn as circles, regular polygons and paths, with a caption; text stays text in the SVG. With a key file
(tab-separated lines from the inspector: background, info, species, arch, colorbar, scale) the picture gets what
the bitmap pictures have, as vector elements: an information box and a legend beside it, a colour bar, a scale
bar on the picture, and a dark background when the inspector's is dark. A key with width_pt (frame --width)
makes a journal figure: the page exactly that wide, its text 7 to 9 pt.

    python3 snapshot.py TABLE.csv OUT WIDTH_M HEIGHT_M CAPTION VERSION [KEY.tsv]
"""
import os
import sys
import textwrap

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


def draw_scale(ax, key, width_m, height_m, size=None):
    if not key["scale"]:
        return
    ink = "#eeeeee" if key["background"] == "dark" else "#111111"
    d, text = key["scale"]
    x0, y0 = -0.5 * width_m + 0.04 * width_m, -0.5 * height_m + 0.05 * height_m
    ax.plot([x0, x0 + d], [y0, y0], color=ink, lw=2.5, solid_capstyle="butt")
    ax.text(x0, y0 + 0.015 * height_m, text, fontsize=size or 7 * key["font_scale"], color=ink, va="bottom",
            ha="left")


def wrapped(text, width_in, points):
    """`text` wrapped between words to lines about width_in wide at `points` (an average glyph: 0.52 em)."""
    chars = max(12, int(width_in * 72 / (0.52 * points)))
    return "\n".join(textwrap.fill(line, chars) if line else line for line in text.split("\n"))


def journal_figure(rows, width_m, height_m, caption, key):
    """A page exactly key["width_pt"] wide (frame --width): the caption as a title, the picture the full width
    (at most 2.4 widths tall), and under it the information box's lines and the legend side by side, then the
    colour bar; every text 7 to 9 pt (look.py), each block placed by its measured number of lines."""
    look = Look(f"background={key['background']};width_pt={key['width_pt']}")
    page = key["width_pt"] / 72
    margin, gap = 0.06, 0.08
    title_pt, text_pt, tick_pt = look.size(8), look.size(7), look.size(6)

    def height(text, pt):
        return (text.count("\n") + 1) * pt * 1.25 / 72

    pic_w = page - 2 * margin
    pic_h = pic_w * height_m / width_m
    if pic_h > 2.4 * page:
        pic_h = 2.4 * page
        pic_w = pic_h * width_m / height_m
    title = wrapped(caption, page - 2 * margin, title_pt)
    info_w = (page - 2 * margin) * (0.58 if key["species"] or key["arch"] else 1.0)
    info = wrapped("\n".join(key["info"]), info_w - 0.05, text_pt) if key["info"] else ""
    handles = gallery.legend_handles(key, look)
    legend_h = len(handles) * text_pt * 1.6 / 72
    band = max(height(info, text_pt) if info else 0.0, legend_h)
    bar_h = 0.09 + (text_pt + tick_pt) * 1.4 / 72 if key["colorbar"] else 0.0
    total = margin + height(title, title_pt) + gap + pic_h + gap + band + (gap + bar_h if bar_h else 0) + margin
    fig = plt.figure(figsize=(page, total), facecolor=look.bg)
    y = total - margin  # inches from the bottom, going down
    fig.text(0.5, y / total, title, fontsize=title_pt, color=look.fg, ha="center", va="top")
    y -= height(title, title_pt) + gap
    ax = fig.add_axes([(page - pic_w) / 2 / page, (y - pic_h) / total, pic_w / page, pic_h / total])
    ax.set_facecolor(look.bg)
    gallery.draw_tile(ax, rows, width_m, height_m, pic_w / 0.92, look=look)
    draw_scale(ax, key, width_m, height_m, size=text_pt)
    y -= pic_h + gap
    if info:
        fig.text(margin / page, y / total, info, fontsize=text_pt, color=look.fg, ha="left", va="top",
                 linespacing=1.25)
    if handles:
        fig.legend(handles=handles, loc="upper left", bbox_to_anchor=((margin + info_w) / page, y / total),
                   frameon=False, fontsize=text_pt, labelcolor=look.fg, borderaxespad=0, borderpad=0,
                   handletextpad=0.3)
    y -= band
    if bar_h:
        label, lo, hi, cmap = key["colorbar"]
        y -= gap
        inset = 0.15  # room for the first tick's label
        bar = fig.add_axes([(margin + inset) / page, (y - 0.09) / total, 0.6 * (page - 2 * margin) / page,
                            0.09 / total])
        cb = fig.colorbar(matplotlib.cm.ScalarMappable(norm=matplotlib.colors.Normalize(lo, hi), cmap=cmap),
                          cax=bar, orientation="horizontal")
        cb.set_label(label, fontsize=text_pt, color=look.fg)
        cb.ax.tick_params(labelsize=tick_pt, colors=look.fg)
    return fig


def main(table, out, width_m, height_m, caption, version, key_path=None):
    try:
        rows = read_table(table, ("kind", "x", "y"))
    except siloscope.SiloscopeError as e:
        print(f"snapshot: {e}", file=sys.stderr)
        sys.exit(2)
    key = read_key(key_path, "snapshot") if key_path else None
    tag = f"siloscope snapshot {version}"
    meta = {"CreationDate": None, "ModDate": None, "Creator": tag} if out.endswith(".pdf") else \
        {"Date": None, "Creator": tag}
    if key and key["width_pt"] > 0:  # the page is exactly that wide: no tight bounding box
        journal_figure(rows, width_m, height_m, caption, key).savefig(out, metadata=meta)
        return
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
    fig.savefig(out, metadata=meta, bbox_inches="tight", pad_inches=0.05, facecolor=fig.get_facecolor())


if __name__ == "__main__":
    if len(sys.argv) not in (7, 8):
        sys.exit(__doc__)
    guarded("snapshot", lambda: main(sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5],
                                     sys.argv[6], sys.argv[7] if len(sys.argv) == 8 else None))
