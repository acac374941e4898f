#!/usr/bin/env python3
"""The arch gallery sheet of `siloscope gallery` (and the row of `siloscope filmstrip`): tiles (each a draw list as a table, render/draw_list.h) and
their index.csv -> one PDF, SVG or PNG. Grains are drawn as circles and regular polygons, walls, bonds and
halos as paths: the PDF and SVG are vector throughout (no bitmap), text stays text in the SVG.

    python3 gallery.py TILES_DIR OUT TITLE VERSION [COLUMNS] [TILE_PX] [FOOTER] [LOOK]

LOOK: "background=dark;font_scale=2" (look.py), the run's look.
"""
import math
import os
import sys
import textwrap

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import siloscope  # noqa: E402  one reader of siloscope's files
from siloscope._tables import read_table  # noqa: E402
from look import Look  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.patches as mpatches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
from guard import guarded  # noqa: E402  one line, never a traceback

plt.rcParams.update({"svg.hashsalt": "siloscope", "svg.fonttype": "none", "font.size": 8})

TILE_IN = 2.2  # inches per tile


def colour(text):
    """#rrggbbaa -> an RGBA tuple; '' or nan -> None."""
    if not isinstance(text, str) or not text.startswith("#"):
        return None
    v = [int(text[k:k + 2], 16) / 255 for k in (1, 3, 5, 7)]
    return tuple(v)


def draw_tile(ax, table, window, height=None, width_in=TILE_IN, look=None):
    """A draw list in its own frame: the window [-w/2, w/2] x [-h/2, h/2] in metres (h = w: a square tile),
    on axes about width_in inches wide."""
    half, half_h = 0.5 * window, 0.5 * (height if height else window)
    ax.set_xlim(-half, half)
    ax.set_ylim(-half_h, half_h)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    for side in ax.spines.values():
        side.set_linewidth(0.4)
        side.set_color(look.frame if look else "#999999")
    # Metres to points: the axes are TILE_IN wide (less a little) for `window` metres.
    pt_per_m = 0.92 * width_in * 72 / window
    clip = ax.patch
    rows = table.to_dict("records")
    for r in rows:  # walls first: under the grains
        if r["kind"] == "wall":
            ax.plot([r["x"], r["x2"]], [r["y"], r["y2"]], color=colour(r["fill"]), lw=r["width_m"] * pt_per_m,
                    solid_capstyle="round", clip_path=clip)
    for r in rows:
        if r["kind"] not in ("grain", "obstacle"):
            continue
        fill, halo = colour(r["fill"]), colour(r["halo"])
        sides, x, y, rad = int(r["sides"]), r["x"], r["y"], r["r"]
        if sides == 100:  # a box (the bar obstacle)
            shape = mpatches.Rectangle((x - r["half_w"], y - r["half_h"]), 2 * r["half_w"], 2 * r["half_h"],
                                       angle=0.0, facecolor=fill, edgecolor="none")
        elif 3 <= sides <= 8:
            # matplotlib's first vertex is at +y (90 degrees) before `orientation`; siloscope's at `angle`.
            shape = mpatches.RegularPolygon((x, y), sides, radius=rad, orientation=r["angle"] - math.pi / 2,
                                            facecolor=fill, edgecolor=(0, 0, 0, 0.45), lw=0.3)
        else:
            shape = mpatches.Circle((x, y), rad, facecolor=fill, edgecolor=(0, 0, 0, 0.45), lw=0.3)
        shape.set_clip_path(clip)
        ax.add_patch(shape)
        if halo is not None:
            ring = mpatches.Circle((x, y), rad + 0.006, facecolor="none", edgecolor=halo,
                                   lw=max(0.8, 0.012 * pt_per_m))
            ring.set_clip_path(clip)
            ax.add_patch(ring)
    for kind in ("chain", "bond"):
        for r in rows:
            if r["kind"] == kind:
                ax.plot([r["x"], r["x2"]], [r["y"], r["y2"]], color=colour(r["fill"]),
                        lw=max(0.6, r["width_m"] * pt_per_m), solid_capstyle="round", clip_path=clip)


def label(k, r):
    if isinstance(r.get("label"), str) and r["label"]:  # a filmstrip's own caption (siloscope filmstrip)
        return r["label"].replace("\\n", "\n")
    shorthand = set(str(r["species"]).split(";")) <= {"original", "added"}
    who = f"{r['members']} disks ({r['added']} added)" if shorthand else f"{r['members']} grains"
    aspect = float(r["aspect"])
    aspect_text = f"h/(s/2) {aspect:.2f}" if math.isfinite(aspect) else "flat"
    return (f"#{k + 1}  t = {float(r['t_s']):.2f} s, clog {float(r['clog_s']):.1f} s\n"
            f"{who}, span {100 * float(r['span_m']):.0f} cm, rise {100 * float(r['rise_m']):.0f} cm\n"
            f"{aspect_text}, \u03b8max {float(r['theta_max_deg']):.0f}\u00b0, "
            f"{int(float(r['defects']))} defect{'s' if int(float(r['defects'])) != 1 else ''}")


def main(tiles, out, title, version, columns=0, tile_px=480, footer=None, look_spec=""):
    look = Look(look_spec)
    look.apply(plt)
    try:
        rows = read_table(os.path.join(tiles, "index.csv"), ("tile", "t_s")).to_dict("records")
        tables = [read_table(os.path.join(tiles, r["tile"]), ("kind", "x", "y")) for r in rows]
    except siloscope.SiloscopeError as e:
        print(f"gallery: {e}", file=sys.stderr)
        sys.exit(2)
    n = len(rows)
    cols = columns if columns > 0 else max(1, math.ceil(math.sqrt(n)))
    nrows = math.ceil(n / cols)
    width = TILE_IN * cols
    # Wrapped to the sheet's width, so that a narrow sheet never cuts its title or footer; the sheet is as tall
    # as its tiles plus the lines of both, so neither runs into a tile.
    chars = max(30, int(width * 72 / (look.size(9) * 0.55)))
    title_lines = textwrap.wrap(title, chars)
    footer = f"siloscope {version}; {footer}" if footer else (
        f"siloscope {version}; members ringed, bonds dark; the state one time step before the clog rule "
        f"removed each arch; h/(s/2): rise over half the span; \u03b8max: the largest bead angle; "
        f"defects: bead angles above 180\u00b0 (README, arch descriptors)")
    footer_lines = textwrap.wrap(footer, int(width * 72 / (look.size(6) * 0.55)))
    title_in = len(title_lines) * look.size(9) * 1.3 / 72 + 0.1
    footer_in = len(footer_lines) * look.size(6) * 1.3 / 72 + 0.1
    height = (TILE_IN + 0.55 * look.font_scale) * nrows + title_in + footer_in
    fig, axes = plt.subplots(nrows, cols, figsize=(width, height), squeeze=False)
    for k, ax in enumerate(axes.flat):
        if k >= n:
            ax.axis("off")
            continue
        draw_tile(ax, tables[k], float(rows[k]["window_m"]), look=look)
        # Each caption wrapped to its tile's width at the look's text size: neighbours never run together.
        chars = max(12, int(TILE_IN * 72 / (look.size(6.5) * 0.55)))
        text = "\n".join(w for line in label(k, rows[k]).split("\n") for w in textwrap.wrap(line, chars) or [""])
        ax.set_title(text, fontsize=look.size(6.5))
    fig.suptitle("\n".join(title_lines), fontsize=look.size(9))
    fig.text(0.01, 0.003, "\n".join(footer_lines), ha="left", va="bottom", fontsize=look.size(6), color=look.muted)
    fig.tight_layout(rect=(0, footer_in / height, 1, 1 - title_in / height))
    # The creator tag lets `siloscope gallery --force` recognise its own sheet (and nothing else).
    tag = f"siloscope gallery {version}"
    if out.endswith(".pdf"):
        meta = {"CreationDate": None, "ModDate": None, "Creator": tag}
    elif out.endswith(".svg"):
        meta = {"Date": None, "Creator": tag}
    else:
        meta = {"Software": tag}
    # bbox_inches="tight" grows the page to hold every label: nothing is cut at any width.
    fig.savefig(out, dpi=max(72, int(tile_px / TILE_IN)), metadata=meta, bbox_inches="tight", pad_inches=0.08)


if __name__ == "__main__":
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    guarded("gallery", lambda: main(
        sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]) if len(sys.argv) > 5 else 0,
        int(sys.argv[6]) if len(sys.argv) > 6 else 480, sys.argv[7] if len(sys.argv) > 7 and sys.argv[7] else None,
        sys.argv[8] if len(sys.argv) > 8 else ""))
