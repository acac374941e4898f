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


def tilt(results, out, lines, helpers):
    runs_of, per_run_avalanches, pooled_mean, boot_stat, boot_ratio = helpers
    c = siloscope.read_campaign(results)
    p = c.points.sort_values(["aperture", "tilt"])
    scene = runs_of(results)[0].scene
    runs = per_run_avalanches(results, ("aperture", "tilt"))
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(9, 3.6))
    for D, grp in p.groupby("aperture"):
        ax.errorbar(grp["tilt"], grp["avalanche_mean"], yerr=grp["avalanche_mean_ci95"], fmt="o-", capsize=3,
                    label=f"D = {D / D_MEAN:g} d")
        w = D * np.cos(np.radians(grp["tilt"])) / D_MEAN
        bx.errorbar(w, grp["avalanche_mean"], yerr=grp["avalanche_mean_ci95"], fmt="o", capsize=3,
                    label=f"D = {D / D_MEAN:g} d")
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
    lines += ["", " ".join(verdict), "",
              "Reading against Thomas and Durian (PRE 87, 052201, 2013): in their experiment tilting makes clogging "
              "more likely and the outlet's width projected across the flow governs it. siloscope's tilted flat silo "
              "does not follow them: its flow rate falls with the tilt, but clogging does not become more likely, and "
              "equal projected widths give avalanches an order of magnitude apart. Why is not settled here. The "
              "candidates, in the order we would test them: the geometry (a 2D flat silo whose floor, with the outlet "
              "in it, is inclined at the tilt: beyond the packing's angle of repose (not measured here) grains "
              "slide down the floor and cross the outlet along its width rather than arch "
              "over it from above), the grains' path to the outlet (the same at a hopper's converging walls would "
              "tell), and the model (2D frictional disks without rolling resistance, against their 3D beads). A "
              "tilted hopper (container = \"hopper\") at the same tilts separates the first from the last: the next "
              "section.", "",
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
    follows_tilt = bool(fewer) and not more
    if follows_tilt and equal_projection:
        why = ("The tilted hopper follows Thomas and Durian where the tilted flat silo does not: the flat silo's "
               "disagreement is its geometry (an inclined floor with the outlet in it), not the model.")
    elif not fewer and equal_projection is False:
        leaning = all(r < 1 for r, _, _ in ratios.values())
        why = ("The tilted hopper does not follow Thomas and Durian either. Tilting changes its mean avalanche by "
               "less than the intervals resolve" + (" (every point estimate below the upright one, the direction "
                                                    "they find, but within the interval at this n)" if leaning else "")
               + ", and equal projected widths still give avalanches an order of magnitude apart. So the flat "
               "silo's inclined floor is not why the projected width fails to govern clogging here: the hopper, "
               "where grains reach the outlet from above as in their experiment, fails the same way. What remains "
               "is the model: 2D disks, where an arch spans the outlet's whole width, against their 3D beads in a "
               "tilted hopper, where the projected area of the hole, not a width, is what the grains see.")
    else:
        why = ("The tilted hopper follows Thomas and Durian in part (above): the geometry accounts for part of the "
               "flat silo's disagreement, and the part it does not account for is left to the model.")
    lines += ["", " ".join(text), "", "Why the tilted flat silo disagrees: " + why, "",
              "![Tilted hopper](figures/tilt-hopper.png)", ""]


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
