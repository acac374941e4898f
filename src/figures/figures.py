#!/usr/bin/env python3
"""Figures like the paper's (Carlevaro et al., Granular Matter 24, 2022) from the tidy CSV of `siloscope analyze`.
Over 400 lines because every figure of a campaign is drawn here from the same tables and style: the paper's
(Q~ against r and mu, chi_eff, survival, avalanches) and those of scenes of one's own.

    python3 figures.py ANALYSIS_DIR OUT_DIR

Reads points.csv, survival.csv and avalanches.csv; writes each figure as PNG, SVG and PDF. Error bars are the 95% confidence
intervals of the mean over realizations. Restyle freely: every number comes from the CSV.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import siloscope  # noqa: E402  one reader of siloscope's files, for the package and these scripts
from siloscope._tables import records  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from guard import guarded  # noqa: E402  one line, never a traceback

plt.rcParams.update({"figure.dpi": 100, "savefig.dpi": 200, "font.size": 10, "axes.grid": True,
                     "grid.alpha": 0.3, "svg.hashsalt": "siloscope", "legend.fontsize": 8})
COLORS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"]


NOTE = ""


def save(fig, out, name):
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    if NOTE and not fig.texts:
        stamp(fig, NOTE)
    for ext in ("png", "svg", "pdf"):
        meta = {"Date": None} if ext in ("svg", "pdf") else {}
        if ext == "pdf":
            meta = {"CreationDate": None, "ModDate": None}
        fig.savefig(os.path.join(out, f"{name}.{ext}"), metadata=meta)
    plt.close(fig)
    print(f"{name}.png/.svg/.pdf")


def finite(x):
    return isinstance(x, float) and math.isfinite(x)


FRACTIONS = {"chi_eff", "fraction_broken_by_vibration", "airborne_fraction"}


def bounded(ys, hs, key):
    """Error bars that stop at the physical bounds: rates, counts and ratios are >= 0, fractions also <= 1."""
    lo = [min(h, y) for y, h in zip(ys, hs)]
    hi = [min(h, 1.0 - y) if key in FRACTIONS else h for y, h in zip(ys, hs)]
    return [lo, hi]


def series(rows, x, y, key):
    """Points sorted by x, with finite y, as (xs, ys, [lower, upper] error bars bounded at 0 (and 1))."""
    rows = sorted((r for r in rows if finite(r.get(y))), key=lambda r: r[x])
    hs = [r.get(key, 0.0) if finite(r.get(key)) else 0.0 for r in rows]
    ys = [r[y] for r in rows]
    return [r[x] for r in rows], ys, bounded(ys, hs, y)


def nearest(values, target):
    return min(values, key=lambda v: abs(v - target)) if values else None


def stats_note(points, planned):
    """'n = 4-5 realizations per point (partial: 20 planned)': every figure says what stands behind it."""
    ns = [int(p["n_runs"]) for p in points]
    lo, hi = min(ns), max(ns)
    text = f"n = {lo}" + (f"-{hi}" if hi != lo else "") + " realizations per point"
    if planned and lo < planned:
        text += f" (PARTIAL: {planned} planned)"
    refused = [p for p in points if finite(p.get("n_refused")) and p["n_refused"] > 0]
    if refused:
        text += (f"\n{sum(int(p['n_refused']) for p in refused)} refused by the health monitor at "
                 f"{len(refused)} points (not in n)")
    return text


def stamp(fig, note):
    fig.text(0.99, 0.005, note, ha="right", va="bottom", fontsize=7, color="#444444")


def kick_figure(points, surv, out, note):
    """The kick study: flow, Q~/Q_p, clogs broken by vibration, long arches and survival versus the kick."""
    literal = min(p["kick_impulse_max"] for p in points)
    fig, axes = plt.subplots(2, 3, figsize=(12, 6.8))
    groups = [("pure", lambda p: p["chi"] == 0, "k"),
              ("r = 0.4", lambda p: p["chi"] > 0 and abs(p["size_ratio"] - 0.4) < 1e-9, COLORS[0]),
              ("r = 1.0", lambda p: p["chi"] > 0 and abs(p["size_ratio"] - 1.0) < 1e-9, COLORS[1])]

    def panel(ax, key, label, which, ref=None):
        for name, keep, color in groups:
            if name not in which:
                continue
            rows = sorted((p for p in points if keep(p) and finite(p.get(key))), key=lambda p: p["kick_impulse_max"])
            xs = [p["kick_impulse_max"] / literal for p in rows]
            ys = [p[key] for p in rows]
            es = bounded(ys, [p[key + "_ci95"] if finite(p.get(key + "_ci95")) else 0.0 for p in rows], key)
            ax.errorbar(xs, ys, yerr=es, marker="o", capsize=3, color=color, label=name)
        if ref is not None:
            ax.axhline(ref, color="k", lw=0.8, ls="--")
        ax.set_xscale("log")
        ax.set_xlabel("kick strength / literal kick (5e-5 N s at 1 kg/m$^2$)")
        ax.set_ylabel(label)
        ax.legend()
        # Top axis: the largest velocity change of an original disk in units of sqrt(g r_o).
        dv = [p["kick_dv_over_sqrt_g_ro"] / (p["kick_impulse_max"] / literal) for p in points][0]
        top = ax.secondary_xaxis("top", functions=(lambda x: x * dv, lambda y: y / dv))
        top.set_xlabel(r"$\Delta v_{max} / \sqrt{g r_o}$", fontsize=8)

    panel(axes[0][0], "q_p_per_s", r"$Q_p$ [1/s] (pure system)", ["pure"])
    panel(axes[0][1], "q_tilde_over_qp", r"$\tilde Q / Q_p$", ["r = 0.4", "r = 1.0"], ref=1.0)
    panel(axes[0][2], "fraction_broken_by_vibration", "clogs broken by vibration\n(of vibration + 5 s rule)",
          ["pure", "r = 0.4", "r = 1.0"])
    panel(axes[1][0], "long_arches_per_min", "long-lasting arches per minute", ["pure", "r = 0.4", "r = 1.0"])
    panel(axes[1][1], "airborne_fraction", "fraction of disks in flight\n(ballistic above 0.01)",
          ["pure", "r = 0.4", "r = 1.0"], ref=0.01)
    ax = axes[1][2]
    if surv:
        kicks = sorted({s["kick_impulse_max"] for s in surv})
        cmap = plt.get_cmap("viridis")
        for i, k in enumerate(kicks):
            rows = sorted((s for s in surv if s["kick_impulse_max"] == k and s["chi"] == 0), key=lambda s: s["tau_s"])
            taus = [s["tau_s"] for s in rows if finite(s["survival"]) and s["survival"] > 0]
            ps = [s["survival"] for s in rows if finite(s["survival"]) and s["survival"] > 0]
            ax.step(taus, ps, where="post", color=cmap(i / max(1, len(kicks) - 1)), label=f"{k / literal:g}x")
        ax.set_yscale("log")
        ax.set_xlabel(r"$\tau$ [s]")
        ax.set_ylabel(r"$\tilde P(\Delta t \geq \tau)$, pure system")
        ax.legend(title="kick", ncol=2)
    fig.suptitle("The kick study: what the kick strength does to the clogging hopper", fontsize=11)
    stamp(fig, note)
    save(fig, out, "kicks")


def main(src, out):
    try:
        campaign = siloscope.read_campaign(src)
    except siloscope.SiloscopeError as e:
        print(f"figures: {e}", file=sys.stderr)
        sys.exit(2)
    try:
        draw(campaign, src, out)
    except KeyError as e:
        # A points.csv not written by `siloscope analyze` (or by an older one): one line, never a traceback.
        print(f"figures: {campaign.path}/points.csv has no column {e.args[0]} (written by siloscope analyze?)",
              file=sys.stderr)
        sys.exit(2)


def chi_eff_figure(points, mixed, chi0, r4, out):
    """Q~ versus chi_eff (magnetic) beside Q~ versus chi (non-magnetic), at r near 0.4."""
    if not any(p["size_ratio"] == r4 and p["mu"] == 0 and 0 < p["chi"] for p in points if abs(p["chi"] - chi0) > 1e-9):
        print(f"note qtilde_vs_chi_eff: no other non-magnetic chi at r = {r4:g}, the chi curve has one point")
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


def avalanche_figure(points, mixed, ratios, sizes, chi0, out):
    """Mean avalanche size versus r, one curve per dipole strength, the pure system as a band."""
    if "avalanche_mean" not in points[0]:
        print("skipped avalanche_size_vs_r: points.csv has no avalanche_mean (analyzed by an older siloscope)")
        return
    if len(sizes) < 2:
        print(f"skipped avalanche_size_vs_r: the grid has one size ratio at chi = {chi0:g}")
        return
    fig, ax = plt.subplots(figsize=(5, 3.6))
    for i, fr in enumerate(ratios):
        xs, ys, es = series([p for p in mixed if abs(p["dipole_force_ratio"] - fr) < 1e-6], "size_ratio",
                            "avalanche_mean", "avalanche_mean_ci95")
        label = "non-magnetic" if fr == 0 else f"$F_{{dip}}/W_a$ = {fr:g}"
        ax.errorbar(xs, ys, yerr=es, marker="o", capsize=3, color=COLORS[i % len(COLORS)], label=label)
    for p in points:
        if p["chi"] == 0 and finite(p.get("avalanche_mean")):
            h = p["avalanche_mean_ci95"] if finite(p.get("avalanche_mean_ci95")) else 0.0
            ax.axhspan(p["avalanche_mean"] - h, p["avalanche_mean"] + h, color="k", alpha=0.12, lw=0)
            ax.axhline(p["avalanche_mean"], color="k", lw=0.8, ls="--", label="pure")
    ax.set_xlabel(r"size ratio $r = r_a / r_o$")
    ax.set_ylabel(r"mean avalanche size $\langle s \rangle$ [disks]")
    ax.set_title(rf"$\chi$ = {chi0:g}")
    ax.legend()
    save(fig, out, "avalanche_size_vs_r")


def draw(campaign, src, out):
    os.makedirs(out, exist_ok=True)
    points = records(campaign.points)
    note = stats_note(points, campaign.planned)
    global NOTE
    NOTE = note
    tables = {"survival": campaign.survival, "avalanches": campaign.avalanches}
    cols = list(campaign.points.columns)
    extra = cols[cols.index("kick_impulse_max") + 1: cols.index("dipole_force_ratio")]
    own_species = all(not finite(p.get("dipole_force_ratio")) for p in points)
    if extra or own_species:
        scene_figures(campaign, points, extra, out)
        return
    if len({p["kick_impulse_max"] for p in points}) > 1:
        kick_figure(points, records(tables["survival"]) if tables["survival"] is not None else [], out, note)
        return
    chi0 = 0.4 if any(abs(p["chi"] - 0.4) < 1e-9 for p in points) else max(p["chi"] for p in points)
    mixed = [p for p in points if abs(p["chi"] - chi0) < 1e-9]
    ratios = sorted({round(p["dipole_force_ratio"], 6) for p in mixed})
    sizes = sorted({p["size_ratio"] for p in mixed})
    has_qp = any(finite(p["q_tilde_over_qp"]) for p in points)
    qkey, qlabel = ("q_tilde_over_qp", r"$\tilde Q / Q_p$") if has_qp else ("q_tilde_per_s", r"$\tilde Q$ [1/s]")

    # Points no figure below draws are named, never dropped in silence: the figures show chi = chi0, the pure
    # system (as Q_p and as bands), and the non-magnetic chi curve at r near 0.4.
    r4 = nearest(sizes, 0.4)
    for p in points:
        if abs(p["chi"] - chi0) < 1e-9 or p["chi"] == 0 or (p["size_ratio"] == r4 and p["mu"] == 0):
            continue
        print(f"not drawn: the point r = {p['size_ratio']:g}, chi = {p['chi']:g}, mu = {p['mu']:g} fits no figure "
              f"(they show chi = {chi0:g}, the pure system, and chi at r = {r4:g} without dipoles); it is in "
              "points.csv")

    # Q~/Q_p versus r, one curve per dipole strength.
    if len(sizes) < 2:
        print(f"skipped qtilde_vs_r: the grid has one size ratio at chi = {chi0:g}")
    else:
        fig, ax = plt.subplots(figsize=(5, 3.6))
        for i, fr in enumerate(ratios):
            xs, ys, es = series([p for p in mixed if abs(p["dipole_force_ratio"] - fr) < 1e-6], "size_ratio", qkey,
                                qkey + "_ci95")
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
        if len(ratios) < 2:
            print(f"skipped {name}: the grid has one dipole strength")
            continue
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
        ax.set_title(rf"$\chi$ = {chi0:g}")
        ax.legend()
        save(fig, out, name)

    chi_eff_figure(points, mixed, chi0, r4, out)

    # Survival of the gaps between original exits, and of the avalanche sizes: one panel per size ratio.
    for name, x, xlabel, ylabel, logx in (
            ("survival", "tau_s", r"$\tau$ [s]", r"$\tilde P(\Delta t \geq \tau)$", False),
            ("avalanches", "size", r"avalanche size $s$ (disks between two clogs)", r"$P(S \geq s)$", True)):
        if tables[name] is None:
            print(f"skipped {name}: no {name}.csv")
            continue
        distribution_panels(records(tables[name]), chi0, x, xlabel, ylabel, logx, out, name)

    avalanche_figure(points, mixed, ratios, sizes, chi0, out)


def scene_figures(campaign, points, keys, out):
    """A campaign of one's own scenes (analyze --by KEY): the flow (all grains and each species), the mean
    avalanche size and the clogs' survival against the key the campaign varies; categorical keys (obstacle =
    none|disk) by name. Every figure names the slice it shows (the other keys' values)."""
    if not keys:
        keys = []
    def label_of(p, skip=None):
        return ", ".join(f"{k} = {p[k]:g}" if isinstance(p[k], float) else f"{k} = {p[k]}" for k in keys if k != skip)
    if not keys:
        print("a single point: flow and clog figures of one point")
    x = next((k for k in keys if all(isinstance(p[k], float) for p in points)), keys[0] if keys else None)
    groups = {}
    for p in points:
        groups.setdefault(label_of(p, x), []).append(p)
    species = records(campaign.species) if campaign.species is not None else []
    for what, key, ylabel in (("flow", "q_per_s", "Q, all grains [1/s]"),
                              ("avalanche", "avalanche_mean", r"mean avalanche size $\langle s \rangle$ [grains]")):
        fig, ax = plt.subplots(figsize=(5, 3.6))
        for i, (slice_label, ps) in enumerate(sorted(groups.items())):
            if x is None or not all(isinstance(p[x], float) for p in ps):
                names = [label_of(p) for p in ps]
                xs = list(range(len(ps)))
                ax.set_xticks(xs, names, rotation=20, fontsize=7)
            else:
                ps = sorted(ps, key=lambda p: p[x])
                xs = [p[x] for p in ps]
            ys = [p[key] for p in ps]
            hs = [p.get(key + "_ci95", 0.0) if finite(p.get(key + "_ci95")) else 0.0 for p in ps]
            ax.errorbar(xs, ys, yerr=bounded(ys, hs, key), marker="o", capsize=3, color=COLORS[i % len(COLORS)],
                        label=slice_label or None)
            if what == "flow" and len({s["species"] for s in species}) > 1:
                for j, name in enumerate(sorted({s["species"] for s in species})):
                    sp = [next((s for s in species if s["species"] == name and all(s.get(k) == p[k] for k in keys)),
                               None) for p in ps]
                    if any(v is None for v in sp):
                        continue
                    # One realization per point has no interval (NaN): drawn without a bar, as above.
                    err = [v["q_per_s_ci95"] if finite(v.get("q_per_s_ci95")) else 0.0 for v in sp]
                    ax.errorbar(xs, [v["q_per_s"] for v in sp], yerr=err, marker=".",
                                ls=":", capsize=2, color=COLORS[(i + j + 1) % len(COLORS)], label=f"{name}")
        ax.set_xlabel(x if x and all(isinstance(p[x], float) for p in points) else "point")
        ax.set_ylabel(ylabel)
        if any(groups):
            ax.legend(fontsize=7)
        name = f"{what}_vs_{x}" if x else what
        save(fig, out, name.replace(".", "_"))
    cs = campaign.clog_survival
    if cs is not None and len(cs):
        rows = records(cs)
        fig, ax = plt.subplots(figsize=(5, 3.6))
        for i, p in enumerate(points):
            curve = [r for r in rows if all(r.get(k) == p[k] for k in keys) and r["t_s"] > 0]
            if not curve:
                continue
            ax.step([r["t_s"] for r in curve], [r["survival"] for r in curve], where="post",
                    color=COLORS[i % len(COLORS)], label=label_of(p) or "all")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("clog duration t [s]")
        ax.set_ylabel("P(clog lasts > t) (Kaplan-Meier)")
        ax.legend(fontsize=7)
        save(fig, out, "clog_survival")
    if campaign.avalanches is not None and len(campaign.avalanches):
        rows = records(campaign.avalanches)
        fig, ax = plt.subplots(figsize=(5, 3.6))
        for i, p in enumerate(points):
            curve = [r for r in rows if all(r.get(k) == p[k] for k in keys) and r["survival"] > 0]
            if curve:
                ax.step([r["size"] for r in curve], [r["survival"] for r in curve], where="post",
                        color=COLORS[i % len(COLORS)], label=label_of(p) or "all")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("avalanche size s [grains]")
        ax.set_ylabel(r"$P(S \geq s)$")
        ax.legend(fontsize=7)
        save(fig, out, "avalanches")


def distribution_panels(rows, chi0, x, xlabel, ylabel, logx, out, name):
    """P(X >= x) per point at chi0, one panel per size ratio (every curve of the grid), each with the pure system."""
    groups = {}
    for s in rows:
        groups.setdefault((s["size_ratio"], s["chi"], s["mu"]), []).append(s)
    pure = [g for (r, chi, mu), g in groups.items() if chi == 0]
    rs = sorted({r for (r, chi, mu) in groups if chi > 0 and abs(chi - chi0) < 1e-9})
    if not rs:
        print(f"skipped {name}: no points at chi = {chi0:g}")
        return
    cols = min(3, len(rs))
    nrows = math.ceil(len(rs) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.2 * cols, 3.2 * nrows), squeeze=False)
    for ax, r in zip(axes.flat, rs):
        def curve(g, **kw):
            g = sorted((s for s in g if finite(s["survival"]) and s["survival"] > 0), key=lambda s: s[x])
            ax.step([s[x] for s in g], [s["survival"] for s in g], where="post", **kw)
        for g in pure:
            curve(g, color="k", lw=1.6, label="pure")
        i = 0
        for (rr, chi, mu), g in sorted(groups.items()):
            if rr == r and abs(chi - chi0) < 1e-9:
                curve(g, color=COLORS[i % len(COLORS)], lw=1.1, label=rf"$\mu$ = {mu:.3g}")
                i += 1
        ax.set_yscale("log")
        if logx:
            ax.set_xscale("log")
        ax.set_title(f"r = {r:g}")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.legend(fontsize=6)
    for ax in list(axes.flat)[len(rs):]:
        ax.axis("off")
    save(fig, out, name)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    guarded("figures", lambda: main(sys.argv[1], sys.argv[2]))
