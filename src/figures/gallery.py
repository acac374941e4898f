#!/usr/bin/env python3
"""The arch gallery sheet of `siloscope gallery` (and the row of `siloscope filmstrip`): tiles (each a draw list as a table, render/draw_list.h) and
their index.csv -> one PDF, SVG or PNG. Grains are drawn as circles and regular polygons, walls, bonds and
halos as paths: the PDF and SVG are vector throughout (no bitmap), text stays text in the SVG.

    python3 gallery.py TILES_DIR OUT TITLE VERSION [COLUMNS] [TILE_PX] [FOOTER] [LOOK]

LOOK: "background=dark;font_scale=2" (look.py), the run's look; with ";width_pt=W" a journal figure W points
wide (text 7-9 pt, tiles at least 40 mm). TILES_DIR/key.tsv, when there, gives the species legend (and the
arch's ring) above the tiles and a scale bar in the first tile (look.read_key).
"""
import math
import os
import sys
import textwrap

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import siloscope  # noqa: E402  one reader of siloscope's files
from siloscope._tables import read_table  # noqa: E402
from look import Look, read_key  # noqa: E402

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
            lw = max(0.8, 0.012 * pt_per_m)
            if not (look and look.dark):  # a dark edge under the ring: gold alone has 1.6:1 against white
                edge = mpatches.Circle((x, y), rad + 0.006, facecolor="none", edgecolor=(0.12, 0.12, 0.12, 0.9),
                                       lw=lw + max(0.8, 0.7 * lw))
                edge.set_clip_path(clip)
                ax.add_patch(edge)
            ring = mpatches.Circle((x, y), rad + 0.006, facecolor="none", edgecolor=halo, lw=lw)
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


def round_length(most):
    """The largest of 1, 2, 5 x 10^k metres not above `most`."""
    step = 10 ** math.floor(math.log10(most))
    return max(m * step for m in (1, 2, 5) if m * step <= most)


def length_text(m):
    return f"{m * 1000:g} mm" if m < 0.01 else f"{m * 100:g} cm" if m < 1 else f"{m:g} m"


def draw_scale_bar(ax, window, look, size):
    """A bar of a round length in the tile's lower-left corner, named above it (the tile is `window` m wide)."""
    bar = round_length(0.3 * window)
    x0, y0 = -0.45 * window, -0.44 * window
    ink = look.fg
    ax.plot([x0, x0 + bar], [y0, y0], color=ink, lw=2.0, solid_capstyle="butt")
    ax.text(x0, y0 + 0.025 * window, length_text(bar), fontsize=size, color=ink, va="bottom", ha="left",
            bbox={"facecolor": look.bg, "edgecolor": "none", "alpha": 0.75, "pad": 0.6})


def legend_handles(key, look):
    """Each species' swatch and the arch's ring, as the pictures' legend has them (the ring with its dark edge
    on a light background)."""
    from matplotlib.lines import Line2D
    from matplotlib import patheffects
    edge = [] if look.dark else [patheffects.Stroke(linewidth=3.2, foreground=(0.12, 0.12, 0.12, 0.9)),
                                 patheffects.Normal()]
    handles = [Line2D([], [], marker="o", linestyle="", markersize=6, markerfacecolor=c, markeredgecolor="#555555",
                      label=name) for name, c in key["species"]]
    handles += [Line2D([], [], marker="o", linestyle="", markersize=7, markerfacecolor="none", markeredgecolor=c,
                       markeredgewidth=1.8, label=name, path_effects=edge) for name, c in key["arch"]]
    return handles


def sheet_layout(look, n, columns):
    """Columns and the tile's width in inches: the default sheet's 2.2 in tiles, or a journal width filled
    with tiles at least 40 mm wide (a filmstrip of four at 85 mm: two rows of two)."""
    cols = columns if columns > 0 else max(1, math.ceil(math.sqrt(n)))
    if not look.journal:
        return cols, TILE_IN
    width = look.width_pt / 72
    cols = max(1, min(cols, n, int(width * 25.4 // 40)))
    return cols, (width - 0.12 * cols) / cols


def main(tiles, out, title, version, columns=0, tile_px=480, footer=None, look_spec=""):
    look = Look(look_spec)
    look.apply(plt)
    try:
        rows = read_table(os.path.join(tiles, "index.csv"), ("tile", "t_s")).to_dict("records")
        tables = [read_table(os.path.join(tiles, r["tile"]), ("kind", "x", "y")) for r in rows]
    except siloscope.SiloscopeError as e:
        print(f"gallery: {e}", file=sys.stderr)
        sys.exit(2)
    key_path = os.path.join(tiles, "key.tsv")
    key = read_key(key_path, "gallery") if os.path.exists(key_path) else None
    handles = legend_handles(key, look) if key else []
    n = len(rows)
    cols, tile_in = sheet_layout(look, n, columns)
    nrows = math.ceil(n / cols)
    width = look.width_pt / 72 if look.journal else tile_in * cols
    # Wrapped to the sheet's width, so that a narrow sheet never cuts its title or footer; the sheet is as tall
    # as its tiles plus the lines of both, so neither runs into a tile.
    chars = max(30, int(width * 72 / (look.size(9) * 0.55)))
    title_lines = textwrap.wrap(title, chars)
    footer = f"siloscope {version}; {footer}" if footer else (
        f"siloscope {version}; members ringed, bonds dark; the state one time step before the clog rule "
        f"removed each arch; h/(s/2): rise over half the span; \u03b8max: the largest bead angle; "
        f"defects: bead angles above 180\u00b0 (README, arch descriptors)")
    footer_lines = textwrap.wrap(footer, int(width * 72 / (look.size(6) * 0.55)))
    # Each caption wrapped to its tile's width at the look's text size: neighbours never run together.
    caption_chars = max(12, int(tile_in * 72 / (look.size(6.5) * 0.55)))
    captions = ["\n".join(w for line in label(k, rows[k]).split("\n") for w in textwrap.wrap(line, caption_chars)
                          or [""]) for k in range(n)]
    line = 1.22 / 72  # inches per point of text, a line's height
    caption_in = max(c.count("\n") + 1 for c in captions) * look.size(6.5) * line + 0.1
    title_in = len(title_lines) * look.size(9) * line + 0.08
    legend_in = (look.size(7) * 1.7 / 72) * math.ceil(len(handles) / 4) + 0.04 if handles else 0
    footer_in = len(footer_lines) * look.size(6) * line + 0.08
    gap, edge = 0.1, 0.05  # between tiles, and round the sheet (inches)
    top_in = edge + title_in + legend_in
    height = top_in + (caption_in + tile_in) * nrows + gap * (nrows - 1) + 0.06 + footer_in + edge
    fig = plt.figure(figsize=(width, height))
    # Every part placed by its own measured size: captions above their tiles, the legend under the title, the
    # footer under the last row; none can run into another (tight_layout could, with square tiles).
    left0 = 0.5 * (width - cols * tile_in - gap * (cols - 1))
    for k in range(n):
        r, c = divmod(k, cols)
        x = left0 + c * (tile_in + gap)
        y_top = top_in + r * (caption_in + tile_in + gap) + caption_in
        ax = fig.add_axes([x / width, 1 - (y_top + tile_in) / height, tile_in / width, tile_in / height])
        window = float(rows[k]["window_m"])
        draw_tile(ax, tables[k], window, width_in=tile_in, look=look)
        ax.set_title(captions[k], fontsize=look.size(6.5), pad=4)
        if k == 0 and key and key["scale"]:
            draw_scale_bar(ax, window, look, look.size(6.5))
    fig.text(0.5, 1 - edge / height, "\n".join(title_lines), ha="center", va="top", fontsize=look.size(9))
    if handles:
        fig.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, 1 - (edge + title_in) / height),
                   ncol=min(4, len(handles)), frameon=False, fontsize=look.size(7), borderaxespad=0.0,
                   handletextpad=0.3, columnspacing=1.2, labelcolor=look.fg)
    fig.text(edge / width, edge / height, "\n".join(footer_lines), ha="left", va="bottom", fontsize=look.size(6),
             color=look.muted)
    # The creator tag lets `siloscope gallery --force` recognise its own sheet (and nothing else).
    tag = f"siloscope gallery {version}"
    if out.endswith(".pdf"):
        meta = {"CreationDate": None, "ModDate": None, "Creator": tag}
    elif out.endswith(".svg"):
        meta = {"Date": None, "Creator": tag}
    else:
        meta = {"Software": tag}
    dpi = max(72, int(tile_px / tile_in))
    if look.journal:
        # The page is the width asked for: everything was laid out inside it (a tight box would change it).
        fig.savefig(out, dpi=max(dpi, 300), metadata=meta)
    else:
        # bbox_inches="tight" grows the page to hold every label: nothing is cut at any width.
        fig.savefig(out, dpi=dpi, metadata=meta, bbox_inches="tight", pad_inches=0.08)


if __name__ == "__main__":
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    guarded("gallery", lambda: main(
        sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]) if len(sys.argv) > 5 else 0,
        int(sys.argv[6]) if len(sys.argv) > 6 else 480, sys.argv[7] if len(sys.argv) > 7 and sys.argv[7] else None,
        sys.argv[8] if len(sys.argv) > 8 else ""))
