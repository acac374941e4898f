#!/usr/bin/env python3
"""The breaking-kick campaign's analysis (docs/arches.md): every arch tested, pooled; the kick that breaks it
against its largest bead angle, in bins, with 95% intervals from a bootstrap over runs (the unit: one run gives
one or two arches, and its arches share a packing); a figure.

    python3 docs/arches/analyse.py RESULTS OUT_DIR

RESULTS holds sSEED/breaking/breaking.csv (docs/arches/campaign.sh); OUT_DIR receives breaking.csv (every arch,
with its seed), by_angle.csv and breaking.png. An arch that held at the strongest kick tried is censored there:
a bin's median is given only while fewer than half of its arches held."""
import glob
import os
import sys

import numpy as np
import pandas as pd

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "src", "python"))
from siloscope import stats  # noqa: E402

BINS = [(0, 140), (140, 160), (160, 180), (180, 270)]


def pooled(results):
    frames = []
    for path in sorted(glob.glob(os.path.join(results, "s*", "breaking", "breaking.csv"))):
        seed = int(os.path.basename(os.path.dirname(os.path.dirname(path)))[1:])
        t = pd.read_csv(path)
        t.insert(0, "seed", seed)
        frames.append(t)
    if not frames:
        sys.exit(f"analyse.py: no s*/breaking/breaking.csv under {results}")
    t = pd.concat(frames, ignore_index=True)
    return t[t.outcome.isin(["broken", "held"])].copy()


def median_break(t):
    """The median breaking kick, m/s: held arches count as stronger than any kick tried; NaN when half held."""
    if len(t) == 0 or (t.outcome == "held").sum() * 2 >= len(t):
        return np.nan
    v = np.where(t.outcome == "held", np.inf, (t.dv_held_m_s + t.dv_broke_m_s) / 2)
    return float(np.median(v))


def spearman(t):
    v = np.where(t.outcome == "held", np.inf, (t.dv_held_m_s + t.dv_broke_m_s) / 2)
    a = pd.Series(t.theta_max_deg.values).rank().values
    b = pd.Series(v).rank().values
    return float(np.corrcoef(a, b)[0, 1])


def main(results, out):
    t = pooled(results)
    os.makedirs(out, exist_ok=True)
    t.to_csv(os.path.join(out, "breaking.csv"), index=False)
    rng = np.random.default_rng(1)
    rows = []
    for lo, hi in BINS:
        b = t[(t.theta_max_deg >= lo) & (t.theta_max_deg < hi)]
        if len(b) == 0:
            continue
        m = median_break(b)
        ci = stats.bootstrap_groups(median_break, b, "seed", rng) if len(b) >= 5 else (np.nan, np.nan)
        rows.append(dict(theta_lo_deg=lo, theta_hi_deg=hi, theta_median_deg=float(b.theta_max_deg.median()),
                         n_arches=len(b), n_runs=b.seed.nunique(),
                         n_held=int((b.outcome == "held").sum()), median_dv_break_m_s=m,
                         ci95_lo=ci[0], ci95_hi=ci[1]))
    bins = pd.DataFrame(rows)
    rho = spearman(t)
    rho_ci = stats.bootstrap_groups(spearman, t, "seed", rng)
    bins.to_csv(os.path.join(out, "by_angle.csv"), index=False, float_format="%.4g")
    summary = (f"{len(t)} arches from {t.seed.nunique()} runs ({(t.outcome == 'held').sum()} held at the "
               f"strongest kick); Spearman rho(theta_max, dv_break) = {rho:.3f} "
               f"[{rho_ci[0]:.3f}, {rho_ci[1]:.3f}] (95%, bootstrap over runs)")
    with open(os.path.join(out, "summary.txt"), "w") as f:
        f.write(summary + "\n" + bins.to_string(index=False, float_format=lambda v: f"{v:.3g}") + "\n")
    print(summary)
    print(bins.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    figure(t, bins, rho, rho_ci, os.path.join(out, "breaking.png"))


def figure(t, bins, rho, rho_ci, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.6), dpi=150)
    broken = t[t.outcome == "broken"]
    held = t[t.outcome == "held"]
    ax.scatter(broken.theta_max_deg, (broken.dv_held_m_s + broken.dv_broke_m_s) / 2, s=12, alpha=0.5, color="#4477aa",
               label=f"one arch ({len(broken)} broken)")
    if len(held):
        ax.scatter(held.theta_max_deg, held.dv_held_m_s, marker="^", s=18, color="#cc6677",
                   label=f"held at the strongest kick ({len(held)})")
    for _, b in bins.iterrows():
        if np.isnan(b.median_dv_break_m_s):
            continue
        x = b.theta_median_deg
        if np.isnan(b.ci95_lo) or np.isnan(b.ci95_hi):  # too few arches for an interval: the median alone
            ax.plot(x, b.median_dv_break_m_s, "s", mfc="white", color="black")
        else:
            err = [[b.median_dv_break_m_s - b.ci95_lo], [b.ci95_hi - b.median_dv_break_m_s]]
            ax.errorbar(x, b.median_dv_break_m_s, yerr=err, fmt="s", color="black", capsize=3)
        ax.annotate(f"n={int(b.n_arches)}", (x, b.ci95_hi if not np.isnan(b.ci95_hi) else b.median_dv_break_m_s),
                    textcoords="offset points", xytext=(0, 4), ha="center", fontsize=7)
    ax.axvline(180, color="grey", lw=0.8, ls=":")
    ax.set_xlabel("largest bead angle of the arch, deg (above 180: a defect)")
    ax.set_ylabel("kick that breaks the clog, m/s")
    ax.set_title(f"{len(t)} arches, {t.seed.nunique()} runs; medians per bin, 95% bootstrap over runs\n"
                 f"Spearman rho = {rho:.2f} [{rho_ci[0]:.2f}, {rho_ci[1]:.2f}]", fontsize=9)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2, frameon=False)
    fig.tight_layout()
    fig.savefig(path)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
