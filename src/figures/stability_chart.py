#!/usr/bin/env python3
"""Stability map from `siloscope bench stability` CSV: time step against dipole strength, one panel per size
ratio; marker colour says whether the safe-time-step check refused the cell and whether it broke in fact.

    python3 stability_chart.py stability.csv stability.png
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import siloscope  # noqa: E402  one reader of siloscope's files
from siloscope._tables import read_table  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from guard import guarded  # noqa: E402  one line, never a traceback

STYLE = {"accepted-clean": ("#009E73", "o"), "refused-breaks": ("#D55E00", "X"),
         "refused-runs-clean": ("#E69F00", "s"), "ACCEPTED-BREAKS": ("#000000", "*")}


def main(src, out):
    try:
        rows = read_table(src, ("size_ratio", "dt_s", "dipole_force_ratio")).astype(str).to_dict("records")
    except siloscope.SiloscopeError as e:
        print(f"stability_chart: {e}", file=sys.stderr)
        sys.exit(2)
    sizes = sorted({float(r["size_ratio"]) for r in rows})
    fig, axes = plt.subplots(1, len(sizes), figsize=(5 * len(sizes), 4), sharey=True)
    for ax, r in zip(axes if len(sizes) > 1 else [axes], sizes):
        seen = set()
        for row in rows:
            if float(row["size_ratio"]) != r:
                continue
            color, marker = STYLE[row["outcome"]]
            y = max(float(row["dipole_force_ratio"]), 0.1)  # F/W = 0 drawn at 0.1 on the log axis
            ax.scatter([float(row["dt_s"]) * 1e3], [y], c=color, marker=marker, s=90,
                       label=row["outcome"] if row["outcome"] not in seen else None)
            seen.add(row["outcome"])
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("time step [ms]")
        ax.set_title(f"r = {r:g}")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower left", framealpha=0.9)
    (axes[0] if len(sizes) > 1 else axes).set_ylabel("dipole contact force / weight (0 drawn at 0.1)")
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    print(f"chart {out}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    guarded("stability_chart", lambda: main(sys.argv[1], sys.argv[2]))
