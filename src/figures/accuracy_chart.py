#!/usr/bin/env python3
"""Speed versus accuracy chart from `siloscope bench accuracy` CSV.

    python3 accuracy_chart.py accuracy.csv accuracy.png

One row per scene case, one column per accuracy measure, one point per numerical setting, speed on the x axis:
- the mean overlap of touching disks (how well contacts are resolved);
- the KS distance of the avalanche sizes (disks per avalanche between clogs) from the reference's, over the
  distance two samples of one distribution exceed 5% of the time: below 1 (the dotted line) the setting cannot
  be told apart from the reference with this many avalanches;
- the same for the gaps between consecutive exits of original disks (hundreds per run).
The Pareto front (no other point both faster and more accurate) is dashed.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import siloscope  # noqa: E402  one reader of siloscope's files
from siloscope._tables import read_table, records  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from guard import guarded  # noqa: E402  one line, never a traceback


def read(path):
    try:
        return records(read_table(path, ("setting", "scene")))
    except siloscope.SiloscopeError as e:
        print(f"accuracy_chart: {e}", file=sys.stderr)
        sys.exit(2)


def pareto(points):
    """Points (speed, error, label) not dominated by another that is at least as fast and as accurate."""
    front = []
    for p in points:
        if not any(q[0] >= p[0] and q[1] <= p[1] and (q[0] > p[0] or q[1] < p[1]) for q in points):
            front.append(p)
    return sorted(front)


def ratio(r, ks, crit):
    if r["setting"] == "reference":
        return 0.0
    if not (math.isfinite(r.get(ks, math.nan)) and math.isfinite(r.get(crit, math.nan)) and r[crit] > 0):
        return math.nan
    return r[ks] / r[crit]


def main(src, out):
    rows = [r for r in read(src) if isinstance(r["sim_per_cpu"], float) and math.isfinite(r["sim_per_cpu"])]
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    measures = [("overlap", "mean overlap [% of the smaller radius]"),
                ("aval", "KS(avalanche sizes) / 95% critical"),
                ("gap", "KS(original exit gaps) / 95% critical")]
    fig, axes = plt.subplots(len(scenes), 3, figsize=(14, 3.4 * len(scenes)), squeeze=False)
    for i, scene in enumerate(scenes):
        srows = [r for r in rows if r["scene"] == scene]
        n = int(srows[0]["realizations"])
        for j, (key, label) in enumerate(measures):
            ax = axes[i][j]
            pts = []
            for r in srows:
                if key == "overlap":
                    v = r["overlap_mean_pct"]
                elif key == "aval":
                    v = ratio(r, "avalanche_ks_distance", "avalanche_ks_critical")
                else:
                    v = ratio(r, "gap_ks_distance", "gap_ks_critical")
                if math.isfinite(v):
                    pts.append((r["sim_per_cpu"], v, r["setting"]))
            for speed, err, name in pts:
                ax.scatter([speed], [err], s=90 if name == "default" else 40, zorder=3,
                           color="#D55E00" if name == "default" else ("#000000" if name == "reference" else "#0072B2"))
                ax.annotate(name, (speed, err), textcoords="offset points", xytext=(5, 3), fontsize=7)
            front = pareto(pts)
            ax.plot([p[0] for p in front], [p[1] for p in front], color="#009E73", lw=1.0, ls="--")
            if key != "overlap":
                ax.axhline(1.0, color="grey", lw=1, ls=":")
                ax.set_ylim(bottom=0)
            ax.set_xscale("log")
            ax.set_xlabel("speed [simulated s per CPU s of one core]")
            ax.set_ylabel(label, fontsize=8)
            ax.grid(alpha=0.3)
            if j == 0:
                ref = next((r for r in srows if r["setting"] == "reference"), None)
                extra = f", {int(ref['avalanches'])} reference avalanches" if ref and "avalanches" in ref else ""
                ax.set_title(f"scene '{scene}': n = {n} realizations per setting{extra}", fontsize=9, loc="left")
    fig.suptitle("siloscope bench accuracy: speed versus accuracy of the numerical settings")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"chart {out}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    guarded("accuracy_chart", lambda: main(sys.argv[1], sys.argv[2]))
