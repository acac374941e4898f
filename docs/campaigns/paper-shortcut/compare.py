#!/usr/bin/env python3
"""The shortcut's rerun against the committed literal campaign, point by point (issue 30, point 3).

    PYTHONPATH=src/python python3 docs/campaigns/paper-shortcut/compare.py \
        docs/campaigns/paper/analysis docs/campaigns/paper-shortcut/analysis > docs/campaigns/paper-shortcut/compare.md

For each of the rerun's points and each measure claims.md reads there: both means with their 95% intervals (from
points.csv; for the survival of lapses at 1 s and 2 s, bootstrapped over realizations), their difference with
its 95% interval, and whether the difference is resolved (the interval excludes 0). Realizations are paired
by seed (the rerun uses the campaign's seeds), so the table also gives how many realizations ended with the
same events count as their counterpart.
"""
import math
import sys

import numpy as np

import siloscope

KEYS = ("size_ratio", "chi", "mu", "kick_impulse_max")
MEASURES = [
    ("q_tilde_per_s", "Q~ [1/s]"),
    ("q_tilde_over_qp", "Q~/Q_p"),
    ("q_per_s", "Q [1/s]"),
    ("chi_eff", "chi_eff"),
    ("long_arches_per_min", "long arches per minute"),
    ("avalanche_mean", "mean avalanche size"),
    ("fraction_broken_by_vibration", "clogs broken by vibration"),
]


def lapse_survival(rows, column, rng):
    """P(lapse >= t) pooled over realizations, with a bootstrap 95% half-width over realizations."""
    n = rows["lapses"].to_numpy(dtype=float)
    k = rows[column].to_numpy(dtype=float)
    est = k.sum() / n.sum() if n.sum() > 0 else math.nan
    boots = []
    for _ in range(2000):
        i = rng.integers(0, len(n), len(n))
        if n[i].sum() > 0:
            boots.append(k[i].sum() / n[i].sum())
    lo, hi = np.percentile(boots, [2.5, 97.5])
    return est, 0.5 * (hi - lo)


def main(before_dir, after_dir):
    before = siloscope.read_campaign(before_dir)
    after = siloscope.read_campaign(after_dir)
    rng = np.random.default_rng(2022)
    print("| point | measure | literal campaign | with the shortcut | difference | resolved? |")
    print("|---|---|---|---|---|---|")
    unresolved = resolved = 0
    for _, p in after.points.iterrows():
        match = before.points
        for k in KEYS:
            match = match[np.isclose(match[k], p[k])]
        if len(match) != 1:
            print(f"no counterpart for r = {p['size_ratio']:g}, chi = {p['chi']:g}", file=sys.stderr)
            continue
        q = match.iloc[0]
        label = "pure" if p["chi"] == 0 else f"r = {p['size_ratio']:g}, chi = {p['chi']:g}"
        label += f" (n = {int(q['n_runs'])} | {int(p['n_runs'])})"
        rows = []
        for col, name in MEASURES:
            a, ha = q.get(col), q.get(col + "_ci95")
            b, hb = p.get(col), p.get(col + "_ci95")
            if a is None or b is None or not (math.isfinite(a) and math.isfinite(b)):
                continue
            rows.append((name, a, ha, b, hb))
        for column, name in (("lapses_ge_1s", "P(lapse >= 1 s)"), ("lapses_ge_2s", "P(lapse >= 2 s)")):
            sel = []
            for table in (before.realizations, after.realizations):
                t = table
                for k in KEYS:
                    t = t[np.isclose(t[k], p[k])]
                sel.append(t)
            if all(len(t) and "lapses" in t for t in sel):
                (a, ha), (b, hb) = (lapse_survival(t, column, rng) for t in sel)
                rows.append((name, a, ha, b, hb))
        for name, a, ha, b, hb in rows:
            ha = ha if math.isfinite(ha) else 0.0
            hb = hb if math.isfinite(hb) else 0.0
            d, hd = b - a, math.hypot(ha, hb)
            res = abs(d) > hd
            resolved += res
            unresolved += not res
            fmt = "{:.4g}".format
            print(f"| {label} | {name} | {fmt(a)} +- {fmt(ha)} | {fmt(b)} +- {fmt(hb)} | {d:+.3g} +- {hd:.3g} | "
                  f"{'**yes**' if res else 'no'} |")
    print()
    print(f"{unresolved + resolved} comparisons: {resolved} differences resolved at 95% (about "
          f"{0.05 * (unresolved + resolved):.1f} expected by chance alone if nothing changed).")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
