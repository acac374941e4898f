#!/usr/bin/env python3
"""Notebook-style example: do the avalanche sizes of the paper's campaign have an exponential tail at every size
ratio? A figure `siloscope figures` does not make: P(S >= s) of every non-magnetic size ratio (and the pure
system) on one plot, against s / <s>, with exp(-s/<s>) for comparison. An exponential distribution collapses onto
that line whatever its mean (Janda et al., EPL 84, 44002, 2008, for 2D silos).

    PYTHONPATH=src/python python3 docs/examples/avalanche_collapse.py [CAMPAIGN [OUT.png]]

CAMPAIGN defaults to docs/campaigns/paper (the literal-kick campaign, 50 realizations per point); OUT to
docs/examples/avalanche_collapse.png beside this script.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import siloscope  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
campaign = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "campaigns", "paper")
out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(here, "avalanche_collapse.png")

# 1. Load the campaign: its points (means with 95% intervals) and the pooled avalanche-size distributions.
c = siloscope.read_campaign(campaign)
points, av = c.points, c.avalanches
print(c)

# 2. The non-magnetic points at chi = 0.4, and the pure system.
keep = points[((points["mu"] == 0) & (np.isclose(points["chi"], 0.4))) | (points["chi"] == 0)]
keep = keep.sort_values(["chi", "size_ratio"])

# 3. One curve per point: P(S >= s) against s / <s>, <s> the mean avalanche size over the realizations.
fig, ax = plt.subplots(figsize=(5.2, 3.8))
cmap = plt.get_cmap("viridis")
ratios = sorted(keep[keep["chi"] > 0]["size_ratio"])
for _, p in keep.iterrows():
    rows = av[(av["size_ratio"] == p["size_ratio"]) & (av["chi"] == p["chi"]) & (av["mu"] == p["mu"])]
    rows = rows[rows["survival"] > 0]
    mean = p["avalanche_mean"]
    pure = p["chi"] == 0
    label = (f"pure, <s> = {mean:.1f}" if pure else f"r = {p['size_ratio']:g}, <s> = {mean:.1f}")
    color = "k" if pure else cmap(ratios.index(p["size_ratio"]) / max(1, len(ratios) - 1))
    ax.step(rows["size"] / mean, rows["survival"], where="post", color=color, lw=1.8 if pure else 1.0, label=label)
    print(f"{label:28s} {int(rows['avalanches'].iloc[0]):5d} avalanches pooled")
x = np.linspace(0, 8, 100)
ax.plot(x, np.exp(-x), "r--", lw=1.2, label=r"$e^{-s/\langle s\rangle}$")
ax.set_yscale("log")
ax.set_xlim(0, 8)
ax.set_ylim(1e-3, 1.1)
ax.set_xlabel(r"$s / \langle s \rangle$")
ax.set_ylabel(r"$P(S \geq s)$")
n = f"{int(keep['n_runs'].min())}-{int(keep['n_runs'].max())}" if keep["n_runs"].nunique() > 1 else \
    str(int(keep["n_runs"].iloc[0]))
ax.set_title(f"Avalanche sizes, non-magnetic, $\\chi$ = 0.4 (n = {n} per point)", fontsize=9)
ax.legend(fontsize=6, ncol=2)
fig.tight_layout()
fig.savefig(out, dpi=150, metadata={"Software": None})
print(f"written {out}")
