#!/usr/bin/env python3
"""siloscope timeline: a run's discharge as a figure of its own. Each species' cumulative exits against time
(the staircase), every clog as a band from its start to its end coloured by how it ended (the rule, the drive,
by itself, still standing at the run's end), axis ticks and labels, a legend and the run named; the command
that made it in the footer. Vector in PDF and SVG, text kept as text.

    python3 timeline.py RUN OUT FROM TO VERSION COMMAND [COLORS] [LOOK]    (called by `siloscope timeline`)

COLORS: each species' colour as #rrggbb, comma-separated, as the movies draw them (default: matplotlib's).
LOOK: "background=dark;font_scale=2" (look.py), the run's look; ";width_pt=W": a journal figure W points wide,
text 7-9 pt, the legend under the axes.
"""
import os
import sys
import textwrap

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import siloscope  # noqa: E402  one reader of siloscope's files
from look import Look  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
import numpy as np  # noqa: E402
from guard import guarded  # noqa: E402  one line, never a traceback

ENDED = {"rule": ("#c0392b", "clog ended by the rule (arch removed)"),
         "vibration": ("#2e86c1", "clog broken by the drive"),
         "spontaneous": ("#95a5a6", "transient stop (resumed by itself)"),
         "run_end": ("#7d3c98", "clogged at the run's end")}


def journal_layout(fig, ax, look, handles, title, footer_text):
    """The figure at the journal's width, every part placed by its measured size: the title over the axes, the
    ticks and label under them, the legend under those (the data keeps the whole width), the footer last."""
    width, line, edge = look.width_pt / 72, 1.22 / 72, 0.05
    title = "\n".join(textwrap.wrap(title, int(look.width_pt / (look.size(9) * 0.55))))
    footer = "\n".join(textwrap.wrap(footer_text, int(look.width_pt / (look.size(6) * 0.55))))
    ncol = 2 if look.width_pt > 400 else 1
    title_h = (title.count("\n") + 1) * look.size(9) * line + 0.1
    axes_h = 0.42 * width
    xaxis_h = (look.size(7.5) + look.size(8)) * line + 0.16
    legend_h = -(-len(handles) // ncol) * look.size(7) * 1.5 / 72 + 0.06
    footer_h = (footer.count("\n") + 1) * look.size(6) * line + 0.06
    height = edge + title_h + axes_h + xaxis_h + legend_h + footer_h + edge
    left, right = 0.5 + 0.1 * (look.size(7.5) - 7), 0.12
    fig.set_size_inches(width, height)
    bottom = edge + footer_h + legend_h + xaxis_h
    ax.set_position([left / width, bottom / height, (width - left - right) / width, axes_h / height])
    ax.set_title(title, fontsize=look.size(9))
    fig.legend(handles=handles, fontsize=look.size(7), loc="upper left", ncol=ncol, frameon=False,
               bbox_to_anchor=(left / width - 0.01, (edge + footer_h + legend_h) / height), borderaxespad=0.0)
    fig.text(edge / width, edge / height, footer, fontsize=look.size(6), color=look.muted, ha="left", va="bottom")


def main(run_dir, out, t0, t1, version, command, species_colors="", look_spec=""):
    r = siloscope.read_run(run_dir)
    look = Look(look_spec)
    plt.rcParams.update({"svg.fonttype": "none", "pdf.fonttype": 42, "font.size": 9})
    look.apply(plt)
    ended = dict(ENDED)
    if r.metadata.get("run", {}).get("drain_outcome") == "jammed":  # the movie's words for the drain's last clog
        ended["run_end"] = ("#7d3c98", "jammed (the clog that ended the drain)")
    if look.journal:  # the width asked for, the legend under the axes: the data keeps the whole width
        fig, ax = plt.subplots()  # sized and placed once the legend and the title's lines are known
    else:
        fig, ax = plt.subplots(figsize=(8 + 2.2 * look.font_scale, 3.6 + 0.6 * (look.font_scale - 1)))
    seen = set()
    for _, c in r.clogs.iterrows():
        a, b = max(float(c["start_s"]), t0), min(float(c["end_s"]), t1)
        if b <= a:
            continue
        color, _ = ended.get(c["ended_by"], ("#cccccc", c["ended_by"]))
        ax.axvspan(a, b, color=color, alpha=0.25, lw=0)
        seen.add(c["ended_by"])
    given = [c for c in species_colors.split(",") if c]
    tab = plt.get_cmap("tab10")

    def colors(k):
        return given[k] if k < len(given) else tab(k)

    for k, name in enumerate(r.species_names):
        t = np.sort(r.exits.loc[r.exits["species"] == name, "t_s"].to_numpy(float))
        t = t[t <= t1]
        n = np.arange(1, len(t) + 1)
        ax.step(np.r_[t0, t, t1], np.r_[np.sum(t < t0) if len(t) else 0, n, len(t)], where="post", color=colors(k),
                label=f"{name}: {len(t)} exits")
    ax.set_xlim(t0, t1)
    ax.set_ylim(bottom=0)
    ax.set_xlabel("time since the outlet opened [s]")
    ax.set_ylabel("cumulative exits")
    ax.grid(alpha=0.3)
    handles, _labels = ax.get_legend_handles_labels()
    handles += [Patch(color=ended[e][0], alpha=0.25, label=ended[e][1]) for e in ended if e in seen]
    sc = r.scene
    title = f"{os.path.basename(os.path.abspath(run_dir))}: {len(r.clogs)} clogs, seed {sc['seed']}, " \
            f"{sc['duration']:g} s"
    if look.journal:
        journal_layout(fig, ax, look, handles, title, f"siloscope {version}: {command}")
    else:
        # Beside the axes, never on the data.
        ax.legend(handles=handles, fontsize=look.size(7), loc="upper left", bbox_to_anchor=(1.01, 1.0),
                  borderaxespad=0.0)
        ax.set_title(title, fontsize=look.size(9))
        footer = "\n".join(textwrap.wrap(f"siloscope {version}: {command}", int(8 * 72 / (look.size(6) * 0.6))))
        fig.text(0.01, 0.005, footer, fontsize=look.size(6), color=look.muted, ha="left", va="bottom")
        fig.tight_layout(rect=(0, 0.015 + 0.02 * look.font_scale * (footer.count("\n") + 1), 1, 1))
    tag = f"siloscope timeline {version}"  # lets `siloscope timeline --force` recognise its own figure
    meta = ({"CreationDate": None, "ModDate": None, "Creator": tag} if out.endswith(".pdf") else
            {"Date": None, "Creator": tag} if out.endswith(".svg") else {"Software": tag})
    fig.savefig(out, dpi=200, metadata=meta)


if __name__ == "__main__":
    if len(sys.argv) not in (7, 8, 9):
        sys.exit(__doc__)
    guarded("timeline", lambda: main(sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5],
                                     sys.argv[6], *sys.argv[7:9]))
