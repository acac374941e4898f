#!/usr/bin/env python3
"""Speed versus accuracy chart from `siloscope bench accuracy` CSV.

    python3 accuracy_chart.py accuracy.csv accuracy.png

Left: mean overlap (a measure of how well contacts are resolved) against speed. Right: the error of Q~ against
the reference, with the reference's 95% interval as a band. One point per setting; the Pareto front (faster and
more accurate than every other point) is joined by a line.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in list(r):
            try:
                r[k] = float(r[k])
            except ValueError:
                pass
    return rows


def pareto(points):
    """Points (speed, error, label) not dominated by another that is at least as fast and as accurate."""
    front = []
    for p in points:
        if not any(q[0] >= p[0] and q[1] <= p[1] and (q[0] > p[0] or q[1] < p[1]) for q in points):
            front.append(p)
    return sorted(front)


def main(src, out):
    rows = [r for r in read(src) if r["scene"] == "default" and math.isfinite(r["sim_per_wall"])]
    ref = next(r for r in rows if r["setting"] == "reference")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, key, label in ((axes[0], "overlap_mean_pct", "mean overlap [% of the smaller radius]"),
                           (axes[1], "q_tilde_rel_error", r"$|\tilde Q - \tilde Q_{ref}| / \tilde Q_{ref}$")):
        pts = [(r["sim_per_wall"], r[key], r["setting"]) for r in rows if math.isfinite(r[key])]
        for speed, err, name in pts:
            ax.scatter([speed], [err], s=40 if name != "default" else 90, zorder=3,
                       color="#D55E00" if name == "default" else ("#000000" if name == "reference" else "#0072B2"))
            ax.annotate(name, (speed, err), textcoords="offset points", xytext=(5, 4), fontsize=8)
        front = pareto([p for p in pts if p[2] != "reference"] + [p for p in pts if p[2] == "reference"])
        ax.plot([p[0] for p in front], [p[1] for p in front], color="#009E73", lw=1.2, ls="--", label="Pareto front")
        if key == "q_tilde_rel_error" and ref["q_tilde_per_s"] > 0:
            ax.axhline(ref["q_tilde_ci95"] / ref["q_tilde_per_s"], color="grey", lw=1, ls=":",
                       label="reference 95% CI half-width")
        ax.set_xscale("log")
        ax.set_xlabel("speed [simulated s per wall s, one core]")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("siloscope: speed versus accuracy, default scene (r = 0.4, chi = 0.4)")
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    print(f"chart {out}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
