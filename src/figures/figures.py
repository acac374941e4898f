#!/usr/bin/env python3
"""Figures like the paper's (Carlevaro et al., Granular Matter 24, 2022) from the tidy CSV of `siloscope analyze`.

    python3 figures.py ANALYSIS_DIR OUT_DIR

Reads points.csv and survival.csv; writes each figure as PNG, SVG and PDF. Error bars are the 95% confidence
intervals of the mean over realizations. Restyle freely: every number comes from the CSV.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

plt.rcParams.update({"figure.dpi": 100, "savefig.dpi": 200, "font.size": 10, "axes.grid": True,
                     "grid.alpha": 0.3, "svg.hashsalt": "siloscope", "legend.fontsize": 8})
COLORS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"]


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k, v in list(r.items()):
            try:
                r[k] = float(v)
            except (TypeError, ValueError):
                pass
    return rows


def save(fig, out, name):
    fig.tight_layout()
    for ext in ("png", "svg", "pdf"):
        meta = {"Date": None} if ext in ("svg", "pdf") else {}
        if ext == "pdf":
            meta = {"CreationDate": None, "ModDate": None}
        fig.savefig(os.path.join(out, f"{name}.{ext}"), metadata=meta)
    plt.close(fig)
    print(f"{name}.png/.svg/.pdf")


def finite(x):
    return isinstance(x, float) and math.isfinite(x)


def series(rows, x, y, key):
    """Points sorted by x, with finite y, as (xs, ys, errs)."""
    rows = sorted((r for r in rows if finite(r.get(y))), key=lambda r: r[x])
    return [r[x] for r in rows], [r[y] for r in rows], [r.get(key, 0.0) if finite(r.get(key)) else 0.0 for r in rows]


def nearest(values, target):
    return min(values, key=lambda v: abs(v - target)) if values else None


def main(src, out):
    os.makedirs(out, exist_ok=True)
    points = read(os.path.join(src, "points.csv"))
    if not points:
        sys.exit(f"figures: {src}/points.csv has no points")
    chi0 = 0.4 if any(abs(p["chi"] - 0.4) < 1e-9 for p in points) else max(p["chi"] for p in points)
    mixed = [p for p in points if abs(p["chi"] - chi0) < 1e-9]
    ratios = sorted({round(p["dipole_force_ratio"], 6) for p in mixed})
    sizes = sorted({p["size_ratio"] for p in mixed})
    has_qp = any(finite(p["q_tilde_over_qp"]) for p in points)
    qkey, qlabel = ("q_tilde_over_qp", r"$\tilde Q / Q_p$") if has_qp else ("q_tilde_per_s", r"$\tilde Q$ [1/s]")

    # Q~/Q_p versus r, one curve per dipole strength.
    fig, ax = plt.subplots(figsize=(5, 3.6))
    for i, fr in enumerate(ratios):
        xs, ys, es = series([p for p in mixed if abs(p["dipole_force_ratio"] - fr) < 1e-6], "size_ratio", qkey, qkey + "_ci95")
        label = "non-magnetic" if fr == 0 else f"$F_{{dip}}/W_a$ = {fr:g}"
        ax.errorbar(xs, ys, yerr=es, marker="o", capsize=3, color=COLORS[i % len(COLORS)], label=label)
    if has_qp:
        ax.axhline(1.0, color="k", lw=0.8, ls="--")
    ax.set_xlabel(r"size ratio $r = r_a / r_o$")
    ax.set_ylabel(qlabel)
    ax.set_title(rf"$\chi$ = {chi0:g}")
    ax.legend()
    save(fig, out, "qtilde_vs_r")

    # Q~/Q_p, chi_eff, long arches and added disks per arch versus mu, for r near 0.4, 0.65 and 1.0.
    picks = []
    for target in (0.4, 0.65, 1.0):
        r = nearest(sizes, target)
        if r is not None and r not in picks:
            picks.append(r)
    panels = [(qkey, qlabel, "qtilde_vs_mu"), ("chi_eff", r"$\chi_{eff}$", "chi_eff_vs_mu"),
              ("long_arches_per_min", "long-lasting arches per minute", "long_arches_vs_mu"),
              ("added_per_long_arch", "added disks per long-lasting arch", "added_per_arch_vs_mu")]
    for key, label, name in panels:
        fig, ax = plt.subplots(figsize=(5, 3.6))
        for i, r in enumerate(picks):
            xs, ys, es = series([p for p in mixed if p["size_ratio"] == r], "mu", key, key + "_ci95")
            ax.errorbar(xs, ys, yerr=es, marker="o", capsize=3, color=COLORS[i % len(COLORS)], label=f"r = {r:g}")
        if key == qkey and has_qp:
            ax.axhline(1.0, color="k", lw=0.8, ls="--")
        if key == "chi_eff":
            ax.axhline(chi0, color="k", lw=0.8, ls=":", label=rf"$\chi$ = {chi0:g}")
        ax.set_xlabel(r"dipole moment $\mu$ [A m$^2$]")
        ax.set_ylabel(label)
        ax.legend()
        save(fig, out, name)

    # Q~ versus chi_eff (magnetic) beside Q~ versus chi (non-magnetic), at r near 0.4.
    r4 = nearest(sizes, 0.4)
    fig, ax = plt.subplots(figsize=(5, 3.6))
    nonmag = [p for p in points if p["size_ratio"] == r4 and p["mu"] == 0 and p["chi"] > 0]
    xs, ys, es = series(nonmag, "chi", "q_tilde_per_s", "q_tilde_per_s_ci95")
    ax.errorbar(xs, ys, yerr=es, marker="s", capsize=3, color=COLORS[0], label=r"non-magnetic, versus $\chi$")
    mag = [p for p in mixed if p["size_ratio"] == r4 and p["mu"] > 0]
    xs, ys, es = series(mag, "chi_eff", "q_tilde_per_s", "q_tilde_per_s_ci95")
    ax.errorbar(xs, ys, yerr=es, marker="o", ls="none", capsize=3, color=COLORS[1], label=r"magnetic, versus $\chi_{eff}$")
    ax.set_xlabel(r"$\chi$ or $\chi_{eff}$")
    ax.set_ylabel(r"$\tilde Q$ [1/s]")
    ax.set_title(f"r = {r4:g}")
    ax.legend()
    save(fig, out, "qtilde_vs_chi_eff")

    # Survival functions: the pure system, and r near 0.4 for each mu.
    surv_path = os.path.join(src, "survival.csv")
    if os.path.exists(surv_path):
        surv = read(surv_path)
        fig, ax = plt.subplots(figsize=(5, 3.6))
        groups = {}
        for s in surv:
            groups.setdefault((s["size_ratio"], s["chi"], s["mu"]), []).append(s)
        i = 0
        for (r, chi, mu), rows in sorted(groups.items()):
            pure = chi == 0
            if not pure and not (r == r4 and abs(chi - chi0) < 1e-9):
                continue
            rows.sort(key=lambda s: s["tau_s"])
            taus = [s["tau_s"] for s in rows if finite(s["survival"]) and s["survival"] > 0]
            ps = [s["survival"] for s in rows if finite(s["survival"]) and s["survival"] > 0]
            label = "pure" if pure else rf"r = {r:g}, $\mu$ = {mu:.3g}"
            ax.step(taus, ps, where="post", color="k" if pure else COLORS[i % len(COLORS)], lw=1.6 if pure else 1.1, label=label)
            i += 0 if pure else 1
        ax.set_yscale("log")
        ax.set_xlabel(r"$\tau$ [s]")
        ax.set_ylabel(r"$\tilde P(\Delta t \geq \tau)$")
        ax.legend()
        save(fig, out, "survival")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
