"""The tilted silo and the fixed-N drain (issue 38, point 5), for physics.py: the mean avalanche against the tilt
at two outlets (Thomas and Durian, PRE 87, 052201, 2013) and the jamming probability J(D/d) at two hopper angles
(To, Lai and Pak, PRL 86, 71, 2001; To, Chin. J. Phys. 40, 379, 2002)."""
import math
import os

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import siloscope

D_MEAN = 0.1  # m, the mean grain diameter of both scenes (radii uniform in 0.045-0.055 m)


def count_range(rows):
    """The realizations with an exit direction per point: "8", or "6-8" where points differ."""
    lo, hi = min(r["n_phi"] for r in rows), max(r["n_phi"] for r in rows)
    return f"{lo}" if lo == hi else f"{lo}-{hi}"


def exit_directions(results):
    """The pack's exit directions per realization (analysis/exit_directions.csv, from a rerun at the same seeds:
    docs/campaigns/exit_directions.py), or None."""
    path = os.path.join(results, "analysis", "exit_directions.csv")
    return pd.read_csv(path) if os.path.exists(path) else None


def exit_collapse(runs, exits, pooled_mean, rng, k=2000):
    """Thomas and Durian's rule as they state it: the outlet projected across the direction the exiting grains
    move, D cos(phi) with phi a point's mean exit direction over the realizations that recorded it (`exits`),
    governs the mean avalanche. The upright points give <s> against the projected width (log-linear between the
    two outlets, and beyond them); each tilted point's observed <s> is set against that prediction at its own
    projected width. Intervals: a bootstrap (k resamples) over the realizations of the tilted point and of both
    upright points, avalanches and exit directions each resampled within their point. Returns one row per
    tilted point; [] without exit directions."""
    if exits is None or not len(exits):
        return []
    phis = {key: grp["exit_direction_deg"].to_numpy(float) for key, grp in exits.groupby(["aperture", "tilt"])}
    phi_of = lambda D, t: next((v for (d, tt), v in phis.items() if np.isclose(d, D) and np.isclose(tt, t)), None)
    up = {D: runs[np.isclose(runs["aperture"], D) & np.isclose(runs["tilt"], 0.0)]
          for D in sorted(runs["aperture"].unique())}
    if len(up) != 2 or any(len(u) == 0 or phi_of(D, 0.0) is None for D, u in up.items()):
        return []
    (d1, u1), (d2, u2) = sorted(up.items())
    f1, f2 = phi_of(d1, 0.0), phi_of(d2, 0.0)

    def width(D, phi):
        return D * math.cos(math.radians(float(np.mean(phi)))) / D_MEAN

    def predict(D, phi, a, pa, b, pb):
        w1, w2 = width(d1, pa), width(d2, pb)
        s1, s2 = pooled_mean(a), pooled_mean(b)
        return math.exp(math.log(s1) + (width(D, phi) - w1) * (math.log(s2) - math.log(s1)) / (w2 - w1))

    pick = lambda x: x[rng.integers(0, len(x), len(x))]
    rows = []
    for (D, t), sel in runs.groupby(["aperture", "tilt"]):
        f = phi_of(D, t)
        if t == 0 or f is None:
            continue
        obs, pred = pooled_mean(sel), predict(D, f, u1, f1, u2, f2)
        ratios, means = [], []
        for _ in range(k):
            bs = sel.iloc[rng.integers(0, len(sel), len(sel))]
            b1 = u1.iloc[rng.integers(0, len(u1), len(u1))]
            b2 = u2.iloc[rng.integers(0, len(u2), len(u2))]
            bf = pick(f)
            means.append(float(np.mean(bf)))
            if min(bs["avalanches"].sum(), b1["avalanches"].sum(), b2["avalanches"].sum()) == 0:
                continue
            ratios.append(pooled_mean(bs) / predict(D, bf, b1, pick(f1), b2, pick(f2)))
        lo, hi = np.quantile(ratios, [0.025, 0.975])
        plo, phi_hi = np.quantile(means, [0.025, 0.975])
        rows.append(dict(D=D, tilt=t, phi=float(np.mean(f)), phi_lo=plo, phi_hi=phi_hi, n_phi=len(f),
                         w_gravity=D * math.cos(math.radians(t)) / D_MEAN, w_exit=width(D, f), observed=obs,
                         predicted=pred, ratio=obs / pred, lo=lo, hi=hi, n=len(sel)))
    return rows


def exit_collapse_lines(rows, what):
    """The table and reading of exit_collapse's rows for `what` (the container)."""
    if not rows:
        return ["", f"Projected across the exit direction ({what}): not measured (the pack's runs were made "
                "before siloscope recorded where grains leave, and no rerun at the same seeds has added "
                "analysis/exit_directions.csv)."]
    out = ["", f"**Projected across the exit direction** ({what}; Thomas and Durian's rule as stated: the outlet "
           "projected across the direction the exiting grains move, measured in each run as the direction of their "
           "mean velocity as their centres cross the outlet's line, from the outlet's normal). The prediction is "
           "the upright outlets' <s> read at the tilted point's projected width (log-linear in the width, beyond "
           "the two outlets by the same line); intervals: bootstrap over realizations of the tilted point and of "
           "both upright points (2000 resamples)."
           + (f" The exit directions come from {count_range(rows)} "
              f"of the {max(r['n'] for r in rows)} realizations per point (a rerun at the same seeds, which "
              "gives the same events and records the direction; analysis/exit_directions.csv"
              + ("; PARTIAL" if min(r["n_phi"] for r in rows) < max(r["n"] for r in rows) else "") + ")."),
           "",
           "| D | tilt [deg] | exit direction [deg] (95%; realizations) | D cos(tilt) / d | D cos(exit) / d | "
           "<s> pooled | <s> predicted | observed / predicted (95%) |", "|---|---|---|---|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: (r["D"], r["tilt"])):
        out.append(f"| {r['D'] / D_MEAN:g} d | {r['tilt']:g} | {r['phi']:.1f} ({r['phi_lo']:.1f} to {r['phi_hi']:.1f}; "
                   f"{r['n_phi']}) | "
                   f"{r['w_gravity']:.2f} | {r['w_exit']:.2f} | {r['observed']:.1f} | {r['predicted']:.1f} | "
                   f"{r['ratio']:.2f} ({r['lo']:.2f}-{r['hi']:.2f}) |")
    agree = [r for r in rows if r["lo"] <= 1 <= r["hi"]]
    above = [r for r in rows if r["lo"] > 1]
    below = [r for r in rows if r["hi"] < 1]
    fmt = lambda rs: ", ".join(f"{r['D'] / D_MEAN:g} d at {r['tilt']:g}" for r in rs) or "none"
    out += ["", f"The exit-direction projection predicts the mean avalanche within the interval at {fmt(agree)} "
            f"degrees; the observed avalanche is larger than predicted (clogging less likely than the rule says) at "
            f"{fmt(above)}, smaller at {fmt(below)}."]
    return out


def tilt(results, out, lines, helpers):
    runs_of, per_run_avalanches, pooled_mean, boot_stat, boot_ratio = helpers
    c = siloscope.read_campaign(results)
    p = c.points.sort_values(["aperture", "tilt"])
    scene = runs_of(results)[0].scene
    runs = per_run_avalanches(results, ("aperture", "tilt"))
    exits = exit_directions(results)
    collapse = exit_collapse(runs, exits, pooled_mean, np.random.default_rng(531))
    fig, (ax, bx, cx) = plt.subplots(1, 3, figsize=(13, 3.6))
    for D, grp in p.groupby("aperture"):
        ax.errorbar(grp["tilt"], grp["avalanche_mean"], yerr=grp["avalanche_mean_ci95"], fmt="o-", capsize=3,
                    label=f"D = {D / D_MEAN:g} d")
        w = D * np.cos(np.radians(grp["tilt"])) / D_MEAN
        bx.errorbar(w, grp["avalanche_mean"], yerr=grp["avalanche_mean_ci95"], fmt="o", capsize=3,
                    label=f"D = {D / D_MEAN:g} d")
        exit_deg = [exits[np.isclose(exits["aperture"], D) & np.isclose(exits["tilt"], t)]["exit_direction_deg"].mean()
                    if exits is not None else math.nan for t in grp["tilt"]]
        if np.all(np.isfinite(exit_deg)):
            cx.errorbar(D * np.cos(np.radians(exit_deg)) / D_MEAN, grp["avalanche_mean"],
                        yerr=grp["avalanche_mean_ci95"], fmt="o", capsize=3, label=f"D = {D / D_MEAN:g} d")
    cx.set_xlabel(r"outlet width projected across the exit direction, $D\cos\varphi / d$")
    cx.set_ylabel(r"$\langle s \rangle$ [grains]")
    cx.set_yscale("log")
    n_phi = exits.groupby(["aperture", "tilt"]).size() if exits is not None else None
    cx.set_title("Thomas and Durian's projection (exit direction measured"
                 + (f" in {n_phi.min()}-{n_phi.max()} of {int(p['n_runs'].max())} runs per point: PARTIAL)"
                    if n_phi is not None and n_phi.min() < int(p["n_runs"].max()) else ")"), fontsize=8)
    cx.legend(fontsize=7)
    ax.set_xlabel("tilt [deg]")
    ax.set_ylabel(r"mean avalanche $\langle s \rangle$ [grains]")
    ax.set_yscale("log")
    lo_n, hi_n = int(p["n_runs"].min()), int(p["n_runs"].max())
    ax.set_title(f"tilted flat silo, n = {lo_n}" + (f"-{hi_n}" if hi_n != lo_n else "") + " realizations per point "
                 "(t intervals)", fontsize=8)
    ax.legend(fontsize=7)
    bx.set_xlabel(r"outlet width projected across gravity, $D\cos\theta / d$")
    bx.set_ylabel(r"$\langle s \rangle$ [grains]")
    bx.set_yscale("log")
    bx.set_title("if the projected width governed, one curve", fontsize=8)
    bx.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tilt.png"))
    plt.close(fig)
    partial = int(p["n_runs"].min()) < 8
    nmin, nmax = int(p["n_runs"].min()), int(p["n_runs"].max())
    lines += ["## A tilted silo (Thomas and Durian)", "",
              f"`assets/campaigns/tilt.toml` (`tilted-silo.toml`): the flat silo of the obstacle campaign without its "
              f"obstacle (width {scene['silo_width']:g} m, 300 grains of mean diameter d = 0.1 m, no drive, clog rule "
              "after 1 s), turned by the tilt; outlets 3.5 d and 4.5 d; "
              f"{nmin}" + (f"-{nmax}" if nmax != nmin else "") + f" realizations of {scene['duration']:g} s per point"
              + (" (PARTIAL: the campaign plans 8)" if partial else "") + ". "
              "A tilted container is filled upright and turned to its tilt with the outlet closed (settle_time: "
              "half filling, a quarter turning, a quarter at rest): grains dropped into a container already standing "
              "at 60 degrees rest in a chain up its lower wall, above its top. Avalanches end at held clogs (as for "
              "the obstacle). 38.94 degrees is where the wider outlet's projected width D cos(tilt) equals the "
              "narrower one's upright. The last column is the pooled mean over the same outlet's upright one, its "
              "interval a bootstrap over the realizations of both (2000 resamples).", "",
              "| D | tilt [deg] | D cos(tilt) / d | realizations | avalanches | <s> per run (95%) | <s> pooled (95%) | "
              "Q [grains/s] | pooled <s> over upright (95%) |", "|---|---|---|---|---|---|---|---|---|"]
    ratios = {}
    for _, row in p.iterrows():
        sel = runs[np.isclose(runs["aperture"], row["aperture"]) & np.isclose(runs["tilt"], row["tilt"])]
        up = runs[np.isclose(runs["aperture"], row["aperture"]) & np.isclose(runs["tilt"], 0.0)]
        pm = pooled_mean(sel)
        lo, hi = boot_stat(sel, pooled_mean)
        if row["tilt"] == 0:
            vs = "1"
        else:
            rlo, rhi = boot_ratio(sel, up, pooled_mean)
            ratios[(row["aperture"], row["tilt"])] = (pm / pooled_mean(up), rlo, rhi)
            vs = f"{pm / pooled_mean(up):.2f} ({rlo:.2f}-{rhi:.2f})"
        lines.append(f"| {row['aperture'] / D_MEAN:g} d | {row['tilt']:g} | "
                     f"{row['aperture'] * math.cos(math.radians(row['tilt'])) / D_MEAN:.2f} | {len(sel)} | "
                     f"{int(sel['avalanches'].sum())} | {row['avalanche_mean']:.1f} +- {row['avalanche_mean_ci95']:.1f} "
                     f"| {pm:.1f} ({lo:.1f}-{hi:.1f}) | {row['q_per_s']:.2f} +- {row['q_per_s_ci95']:.2f} | {vs} |")
    verdict = []
    for D in sorted(p["aperture"].unique()):
        same = [t for (d, t), (r, lo, hi) in sorted(ratios.items()) if d == D and lo <= 1 <= hi]
        more = [t for (d, t), (r, lo, hi) in sorted(ratios.items()) if d == D and lo > 1]
        fewer = [t for (d, t), (r, lo, hi) in sorted(ratios.items()) if d == D and hi < 1]
        part = f"At D = {D / D_MEAN:g} d the mean avalanche is the upright one's within the interval at tilts " + \
            (", ".join(f"{t:g}" for t in same) or "none")
        if more:
            part += "; larger (clogging less likely) at " + ", ".join(f"{t:g}" for t in more)
        if fewer:
            part += "; smaller (clogging more likely) at " + ", ".join(f"{t:g}" for t in fewer)
        verdict.append(part + " degrees.")
    a = runs[np.isclose(runs["aperture"], 0.35) & np.isclose(runs["tilt"], 0.0)]
    b = runs[np.isclose(runs["aperture"], 0.45) & np.isclose(runs["tilt"], 38.94)]
    if len(a) and len(b):
        r = pooled_mean(b) / pooled_mean(a)
        lo, hi = boot_ratio(b, a, pooled_mean)
        verdict.append(f"At equal projected widths (3.5 d upright against 4.5 d at 38.94 degrees) the pooled mean "
                       f"avalanche of the tilted wide outlet is {r:.2f} times the upright narrow one's (95% interval "
                       f"{lo:.2f}-{hi:.2f})"
                       + (": equal within the interval, as the projected width would have it." if lo <= 1 <= hi
                          else ": the projected width does not govern clogging here."))
    few = p[p["clogs"] < 5 * p["n_runs"]]
    if len(few):
        verdict.append("Where clogs are rare (" + ", ".join(f"{r['aperture'] / D_MEAN:g} d at {r['tilt']:g} degrees: "
                                                          f"{int(r['clogs'])} clogs in {int(r['n_runs'])} runs"
                                                          for _, r in few.iterrows())
                       + f") the last avalanche of a run is cut by its end ({scene['duration']:g} s), so the mean there "
                         "is a lower bound.")
    agree = [r for r in collapse if r["lo"] <= 1 <= r["hi"]]
    lines += ["", " ".join(verdict) + " (This compares widths projected across gravity.)"]
    lines += exit_collapse_lines(collapse, "the tilted flat silo")
    lines += ["", "Reading against Thomas and Durian (PRE 87, 052201, 2013; PRL 114, 178001, 2015): in their "
              "experiment tilting makes clogging more likely and the outlet's width projected across the flow "
              "governs it. Projected across gravity, siloscope's tilted flat silo does not follow them; projected "
              "across the direction its grains actually leave in, as they state the rule, the prediction "
              + (f"holds within the interval at {len(agree)} of {len(collapse)} tilted points" if collapse
                 else "is not measured yet")
              + "".join(f"; at the equal-width pair (4.5 d at 38.94 degrees, {r['w_exit']:.2f} d across its exit "
                        f"direction against 3.50 d across gravity) the observed mean avalanche is {r['ratio']:.2f} "
                        f"({r['lo']:.2f}-{r['hi']:.2f}) times the prediction, where across gravity it was an "
                        "order of magnitude: most of the disagreement was the projection chosen"
                        for r in collapse if np.isclose(r["D"], 0.45) and np.isclose(r["tilt"], 38.94))
              + ". What is left over, and the candidate causes a referee would list, in the order a run could "
              "test them: the floor (at 50 and 60 degrees it is steeper than a packing's angle of repose, so "
              "grains slide down it and cross the outlet along its width; the angle of repose of this packing is "
              "not measured here), the flat-bottomed geometry of their hoppers against this silo's inclined "
              "floor (the tilted hopper below, whose grains reach the outlet from above, separates the two), and "
              "the model (2D frictional disks without rolling resistance against their 3D beads; their long "
              "slits are quasi-2D and follow the rule, so 3D alone does not explain a 2D disagreement).", "",
              "![Tilt](figures/tilt.png)", ""]


def tilt_hopper(results, out, lines, helpers):
    """The tilt campaign again in a hopper (assets/campaigns/tilt-hopper.toml): whether the flat silo's
    disagreement with Thomas and Durian is its geometry (then the hopper follows them) or the model (then it does
    not either)."""
    runs_of, per_run_avalanches, pooled_mean, boot_stat, boot_ratio = helpers
    c = siloscope.read_campaign(results)
    p = c.points.sort_values(["aperture", "tilt"])
    scene = runs_of(results)[0].scene
    runs = per_run_avalanches(results, ("aperture", "tilt"))
    fig, ax = plt.subplots(figsize=(5.2, 3.6))
    for D, grp in p.groupby("aperture"):
        w = D * np.cos(np.radians(grp["tilt"])) / D_MEAN
        ax.errorbar(w, grp["avalanche_mean"], yerr=grp["avalanche_mean_ci95"], fmt="o-", capsize=3,
                    label=f"D = {D / D_MEAN:g} d, tilts {', '.join(f'{t:g}' for t in grp['tilt'])} deg")
    ax.set_xlabel(r"outlet width projected across gravity, $D\cos\theta / d$")
    ax.set_ylabel(r"mean avalanche $\langle s \rangle$ [grains]")
    ax.set_yscale("log")
    nmin, nmax = int(p["n_runs"].min()), int(p["n_runs"].max())
    n_text = f"{nmin}" + (f"-{nmax}" if nmax != nmin else "")
    ax.set_title(f"tilted hopper (walls {scene['hopper_angle']:g} deg from the vertical)\nn = {n_text} "
                 "realizations per point (t intervals); one curve if D cos(tilt) governed", fontsize=8)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tilt-hopper.png"))
    plt.close(fig)
    planned = c.planned or nmax
    lines += ["## A tilted hopper: geometry or model?", "",
              f"`assets/campaigns/tilt-hopper.toml`: the tilted silo above with a hopper for a container (walls "
              f"{scene['hopper_angle']:g} degrees from the vertical, the same width, grains, rule and filling), the "
              f"same outlets, tilts 0 to 38.94 degrees; {n_text} realizations of {scene['duration']:g} s per point"
              + (f" (PARTIAL: the campaign plans {planned})" if nmin < planned else "") + ". Up to a tilt equal to "
              "the walls' angle grains reach the outlet from above on both sides, as in Thomas and Durian's hoppers; "
              "at 38.94 degrees the upper wall overhangs the outlet. Columns as above.", "",
              "| D | tilt [deg] | D cos(tilt) / d | realizations | avalanches | <s> per run (95%) | <s> pooled (95%) | "
              "Q [grains/s] | pooled <s> over upright (95%) |", "|---|---|---|---|---|---|---|---|---|"]
    ratios = {}
    for _, row in p.iterrows():
        sel = runs[np.isclose(runs["aperture"], row["aperture"]) & np.isclose(runs["tilt"], row["tilt"])]
        up = runs[np.isclose(runs["aperture"], row["aperture"]) & np.isclose(runs["tilt"], 0.0)]
        pm = pooled_mean(sel)
        lo, hi = boot_stat(sel, pooled_mean)
        vs = "1"
        if row["tilt"] != 0:
            rlo, rhi = boot_ratio(sel, up, pooled_mean)
            ratios[(row["aperture"], row["tilt"])] = (pm / pooled_mean(up), rlo, rhi)
            vs = f"{pm / pooled_mean(up):.2f} ({rlo:.2f}-{rhi:.2f})"
        lines.append(f"| {row['aperture'] / D_MEAN:g} d | {row['tilt']:g} | "
                     f"{row['aperture'] * math.cos(math.radians(row['tilt'])) / D_MEAN:.2f} | {len(sel)} | "
                     f"{int(sel['avalanches'].sum())} | {row['avalanche_mean']:.1f} +- {row['avalanche_mean_ci95']:.1f} "
                     f"| {pm:.1f} ({lo:.1f}-{hi:.1f}) | {row['q_per_s']:.2f} +- {row['q_per_s_ci95']:.2f} | {vs} |")
    fewer = [(d, t) for (d, t), (r, lo, hi) in ratios.items() if hi < 1]
    more = [(d, t) for (d, t), (r, lo, hi) in ratios.items() if lo > 1]
    same = [(d, t) for (d, t), (r, lo, hi) in ratios.items() if lo <= 1 <= hi]
    fmt = lambda pts: ", ".join(f"{d / D_MEAN:g} d at {t:g}" for d, t in sorted(pts)) or "none"
    text = [f"Against the upright hopper, the mean avalanche is smaller (clogging more likely) at {fmt(fewer)}; "
            f"larger at {fmt(more)}; the same within the interval at {fmt(same)} degrees."]
    a = runs[np.isclose(runs["aperture"], 0.35) & np.isclose(runs["tilt"], 0.0)]
    b = runs[np.isclose(runs["aperture"], 0.45) & np.isclose(runs["tilt"], 38.94)]
    equal_projection = None
    if len(a) and len(b):
        r = pooled_mean(b) / pooled_mean(a)
        lo, hi = boot_ratio(b, a, pooled_mean)
        equal_projection = bool(lo <= 1 <= hi)
        text.append(f"At equal projected widths (3.5 d upright against 4.5 d at 38.94 degrees) the ratio of pooled "
                    f"mean avalanches is {r:.2f} (95% interval {lo:.2f}-{hi:.2f})"
                    + (": equal within the interval." if equal_projection else ": the projected width does not "
                       "govern clogging in this hopper either."))
    collapse = exit_collapse(runs, exit_directions(results), pooled_mean, np.random.default_rng(532))
    agree = [r for r in collapse if r["lo"] <= 1 <= r["hi"]]
    follows_tilt = bool(fewer) and not more
    if not collapse:
        why = ("not settled: the exit directions of these runs are not measured yet (a rerun at the same seeds "
               "adds them), so Thomas and Durian's projection cannot be applied here.")
    elif len(agree) == len(collapse):
        why = ("projected across the direction the grains leave in, as Thomas and Durian state the rule, the "
               "tilted hopper's mean avalanches follow the upright curve at every tilted point; the disagreement "
               "was mostly the projection chosen (across gravity). The same model (2D frictional disks, the same "
               "grains and rule) follows the rule here, so what is left in the tilted flat silo points at its "
               "geometry (the inclined floor grains slide down), not at the model.")
    else:
        why = (f"projected across the exit direction, the tilted hopper's mean avalanche follows the upright curve "
               f"at {len(agree)} of {len(collapse)} tilted points. The candidate causes of what is left, none "
               "settled here: the hopper's own geometry at tilts beyond its walls' angle (at 38.94 degrees the "
               "upper wall overhangs the outlet), the short tails of avalanche sizes at 8 realizations, and the "
               "model (2D frictional disks without rolling resistance).")
    text.append("Tilting " + ("makes clogging more likely here, as they find." if follows_tilt
                              else "does not make clogging resolvably more likely here at this n."))
    lines += ["", " ".join(text)]
    lines += exit_collapse_lines(collapse, "the tilted hopper")
    lines += ["", "Geometry or model: " + why, "",
              "![Tilted hopper](figures/tilt-hopper.png)", ""]


def logistic_half(x, jammed, n):
    """J(x) = 1 / (1 + exp(-(a + b x))) fitted by maximum likelihood to the drains (binomial counts per outlet,
    iteratively reweighted least squares); returns x where J = 1/2 (-a/b), its 95% half-width (delta method), a
    and b, or NaNs where the fit fails (no decline, or complete separation)."""
    x, k, n = (np.asarray(v, float) for v in (x, jammed, n))
    X = np.column_stack([np.ones_like(x), x])
    beta = np.array([0.0, 0.0])
    for _ in range(100):
        p = 1 / (1 + np.exp(-(X @ beta)))
        w = np.maximum(n * p * (1 - p), 1e-12)
        z = X @ beta + (k - n * p) / w
        new = np.linalg.solve(X.T @ (w[:, None] * X), X.T @ (w * z))
        if not np.all(np.isfinite(new)) or abs(new[1]) > 1e6:
            return math.nan, math.nan, math.nan, math.nan
        done = np.max(np.abs(new - beta)) < 1e-10
        beta = new
        if done:
            break
    p = 1 / (1 + np.exp(-(X @ beta)))
    cov = np.linalg.inv(X.T @ ((n * p * (1 - p))[:, None] * X))
    a, b = beta
    if not b < 0:
        return math.nan, math.nan, math.nan, math.nan
    g = np.array([-1 / b, a / b ** 2])
    return -a / b, 1.96 * math.sqrt(float(g @ cov @ g)), a, b


def drain_at_half(results, out, lines, d300):
    """Where J = 1/2 falls, with an interval (a logistic fit to every drain), at drain.toml's 300 disks with
    drain-fine.toml's outlets between its points, and at To, Lai and Pak's 700 disks (drain-700.toml)."""
    parent = os.path.dirname(os.path.abspath(results))
    sets = []
    fine = os.path.join(parent, "drain-fine", "analysis", "drain.csv")
    d_fine = pd.read_csv(fine) if os.path.exists(fine) else None
    pooled = pd.concat([d300, d_fine]) if d_fine is not None else d300
    sets.append(("300", "drain" + (" + drain-fine" if d_fine is not None else ""), pooled))
    big = os.path.join(parent, "drain-700", "analysis", "drain.csv")
    d700 = pd.read_csv(big) if os.path.exists(big) else None
    if d700 is not None:
        sets.append(("700", "drain-700", d700))
    rows = []
    for grains, source, d in sets:
        for angle, grp in d.groupby("hopper_angle"):
            grp = grp.groupby("aperture", as_index=False)[["n_jammed", "n_runs"]].sum()
            half, h, a, b = logistic_half(grp["aperture"] / D_MEAN, grp["n_jammed"], grp["n_runs"])
            rows.append(dict(grains=grains, source=source, angle=angle, half=half, h=h, a=a, b=b, points=len(grp),
                             drains=int(grp["n_runs"].sum()), grp=grp))
    lines += ["### Where J = 1/2 falls, with its interval", "",
              "A logistic J = 1 / (1 + exp(-(a + b D/d))) fitted by maximum likelihood to every drain of a set "
              "(binomial at each outlet), J = 1/2 at D/d = -a/b with a 95% interval by the delta method; the "
              "unit of the interval is one drain. At 300 disks drain.toml's outlets, 0.5 d apart, are joined by "
              "drain-fine.toml's between them (another seed family); at 700 disks (about the number To, Lai and "
              "Pak drained) drain-700.toml, in a silo tall enough to hold them."
              + ("" if d_fine is not None else " drain-fine: not measured yet.")
              + ("" if d700 is not None else " drain-700: not measured yet."), "",
              "| disks | campaigns | hopper walls from the vertical | outlets | drains | J = 1/2 at D/d (95%) |",
              "|---|---|---|---|---|---|"]
    for r in rows:
        at = f"{r['half']:.2f} ({r['half'] - r['h']:.2f}-{r['half'] + r['h']:.2f})" if math.isfinite(r["half"]) \
            else "no fit"
        lines.append(f"| {r['grains']} | {r['source']} | {r['angle']:g} deg | {r['points']} | {r['drains']} | {at} |")
    by = {(r["grains"], r["angle"]): r for r in rows}
    text = []
    for grains in ("300", "700"):
        a30, a60 = by.get((grains, 30.0)), by.get((grains, 60.0))
        if a30 and a60 and math.isfinite(a30["half"]) and math.isfinite(a60["half"]):
            gap = a60["half"] - a30["half"]
            hh = math.hypot(a30["h"], a60["h"])
            text.append(f"At {grains} disks the flatter hopper (60 degrees) puts J = 1/2 {gap:+.2f} d "
                        f"(+- {hh:.2f}) from the steeper one: "
                        + ("resolved" if abs(gap) > hh else "not resolved") + ".")
    for angle in (30.0, 60.0):
        a, b = by.get(("300", angle)), by.get(("700", angle))
        if a and b and math.isfinite(a["half"]) and math.isfinite(b["half"]):
            shift = b["half"] - a["half"]
            hh = math.hypot(a["h"], b["h"])
            text.append(f"With walls {angle:g} degrees from the vertical, 700 disks move J = 1/2 by {shift:+.2f} d "
                        f"(+- {hh:.2f}) against 300: more grains to pass the outlet, more chances to jam.")
    if text:
        lines += ["", " ".join(text)]
    # The figure: J against D/d, 300 disks (filled: drain, open: drain-fine) and 700 (squares), the fits.
    fig, ax = plt.subplots(figsize=(5.8, 3.8))
    colors = {30.0: "tab:blue", 60.0: "tab:orange"}
    for r in rows:
        grp = r["grp"]
        x = grp["aperture"] / D_MEAN
        j = grp["n_jammed"] / grp["n_runs"]
        c = colors.get(r["angle"], "k")
        ax.plot(x, j, "o" if r["grains"] == "300" else "s", color=c, mfc=c if r["grains"] == "300" else "white",
                label=f"{r['grains']} disks, walls {r['angle']:g} deg (n = {r['drains']} drains)")
        if math.isfinite(r["half"]):
            xs = np.linspace(x.min(), x.max(), 200)
            ax.plot(xs, 1 / (1 + np.exp(-(r["a"] + r["b"] * xs))), color=c, lw=1,
                    ls="-" if r["grains"] == "300" else "--")
            ax.errorbar([r["half"]], [0.5], xerr=[[r["h"]], [r["h"]]], fmt="x", color=c, capsize=3)
    ax.axhline(0.5, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel("outlet D / mean grain diameter d")
    ax.set_ylabel("jamming probability J (fraction of drains)")
    ax.set_title("J = 1/2 located by a logistic fit (x: 95%)", fontsize=8)
    ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "drain-half.png"))
    plt.close(fig)
    lines += ["", "![Where J = 1/2 falls](figures/drain-half.png)", ""]


def drain(results, out, lines, helpers):
    runs_of = helpers[0]
    path = os.path.join(results, "analysis", "drain.csv")
    if not os.path.exists(path):
        raise siloscope.SiloscopeError(f"{path}: missing (siloscope analyze writes it for drain runs)")
    d = pd.read_csv(path)
    scene = runs_of(results)[0].scene
    fig, ax = plt.subplots(figsize=(5.2, 3.6))
    for angle, grp in d.groupby("hopper_angle"):
        grp = grp.sort_values("aperture")
        x = grp["aperture"] / D_MEAN
        j = grp["jam_probability"]
        ax.errorbar(x, j, yerr=[j - grp["jam_probability_lo95"], grp["jam_probability_hi95"] - j], fmt="o-",
                    capsize=3, label=f"walls {angle:g} deg from the vertical ({90 - angle:g} from the horizontal)")
    ax.set_xlabel("outlet D / mean grain diameter d")
    ax.set_ylabel("jamming probability J")
    ax.set_ylim(-0.03, 1.03)
    n = d["n_runs"]
    span = f"{n.min()}" + (f"-{n.max()}" if n.max() != n.min() else "")
    ax.set_title(f"{scene['species'][0]['count']} disks drained, n = {span} drains per point (Wilson 95%)", fontsize=8)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "drain.png"))
    plt.close(fig)
    partial = int(n.min()) < 40
    lines += ["## The jamming probability J(D/d) of a drained hopper (To, Lai and Pak)", "",
              f"`assets/campaigns/drain.toml` (`hopper-drain.toml`, `drain = true`): {scene['species'][0]['count']} "
              "disks (radii uniform in 0.045-0.055 m) settled in a hopper with the outlet closed, then drained "
              "without re-injection; a drain ends *emptied* (every grain out) or *jammed* (a clog that stood 1 s: "
              "without a drive it never breaks). J is the fraction of drains that jam; its interval is Wilson's, the "
              f"unit one drain; {int(n.min())}" + (f"-{int(n.max())}" if n.max() != n.min() else "") + " drains per point"
              + (" (PARTIAL: the campaign plans 40)" if partial else "") + ".", "",
              "| hopper walls from the vertical | D / d | drains | jammed | emptied | J (95%) | grains out before the "
              "jam (mean) |", "|---|---|---|---|---|---|---|"]
    for _, r in d.sort_values(["hopper_angle", "aperture"]).iterrows():
        before = "-" if not math.isfinite(r["exits_before_jam_mean"]) else f"{r['exits_before_jam_mean']:.0f}"
        lines.append(f"| {r['hopper_angle']:g} deg | {r['aperture'] / D_MEAN:g} | {int(r['n_runs'])} | "
                     f"{int(r['n_jammed'])} | {int(r['n_emptied'])} | {r['jam_probability']:.2f} "
                     f"({r['jam_probability_lo95']:.2f}-{r['jam_probability_hi95']:.2f}) | {before} |")
    # Where J crosses 1/2 at each angle (linear between the measured points), and the direction with the angle.
    half = {}
    for angle, grp in d.groupby("hopper_angle"):
        grp = grp.sort_values("aperture")
        x, j = grp["aperture"].to_numpy() / D_MEAN, grp["jam_probability"].to_numpy()
        for k in range(len(x) - 1):
            if j[k] >= 0.5 > j[k + 1]:
                half[angle] = x[k] + (j[k] - 0.5) / (j[k] - j[k + 1]) * (x[k + 1] - x[k])
                break
    spans = []
    for angle, grp in d.groupby("hopper_angle"):
        grp = grp.sort_values("aperture")
        x, j = grp["aperture"].to_numpy() / D_MEAN, grp["jam_probability"].to_numpy()
        hi = [xx for xx, jj in zip(x, j) if jj >= 0.95]
        lo = [xx for xx, jj in zip(x, j) if jj <= 0.05]
        if hi and lo:
            spans.append(f"from D/d = {max(hi):g} (J >= 0.95) to {min(lo):g} (J <= 0.05) with walls {angle:g} degrees "
                         "from the vertical")
    text = ["J falls from 1 to 0 as the outlet widens, as in To, Lai and Pak's experiment: " + "; ".join(spans) + "."]
    if len(half) == 2:
        (a1, x1), (a2, x2) = sorted(half.items())
        text.append(f"J = 1/2 is crossed at D/d = {x1:.2f} with walls {a1:g} degrees from the vertical and at "
                    f"{x2:.2f} with walls {a2:g} degrees (linear between measured points): the flatter hopper "
                    f"{'jams up to wider outlets' if x2 > x1 else 'jams less'}. To (Chin. J. Phys. 40, 379, 2002) finds J "
                    "decreasing as the walls get steeper (his angles from the horizontal), so a flatter hopper jams "
                    f"more: siloscope {'agrees' if x2 > x1 else 'disagrees'}.")
    lines += ["", " ".join(text), "", "![Drain](figures/drain.png)", ""]
    drain_at_half(results, out, lines, d)
