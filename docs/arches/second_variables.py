#!/usr/bin/env python3
"""Beyond the largest bead angle (docs/arches.md): does an arch's load, its number of grains or its span tell
more about the kick that breaks it? For each descriptor, Spearman's rank correlation with the breaking kick, and
the partial rank correlation once the largest bead angle is accounted for (and the angle's once the descriptor
is), with 95% intervals from a bootstrap over runs (the unit: a run's arches share a packing). Held arches count
as stronger than any kick tried (rank ties at the top).

    python3 docs/arches/second_variables.py docs/arches/paper-uniform/breaking.csv OUT.csv

Reads the pooled table analyse.py writes; writes one row per descriptor and prints it."""
import os
import sys

import numpy as np
import pandas as pd

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "src", "python"))
from siloscope import stats  # noqa: E402

DESCRIPTORS = {"load_N": "load from the grains above, N", "grains": "members",
               "span_m": "span between its two ends, m"}


def kick(t):
    return np.where(t.outcome == "held", np.inf, (t.dv_held_m_s + t.dv_broke_m_s) / 2)


def rank(x):
    return pd.Series(np.asarray(x)).rank().values


def spearman(a, b):
    return float(np.corrcoef(rank(a), rank(b))[0, 1])


def partial(t, x, z):
    """Spearman's rho of x with the breaking kick, with z's share taken out of both."""
    v = kick(t)
    rxy, rxz, ryz = spearman(t[x], v), spearman(t[x], t[z]), spearman(v, t[z])
    return (rxy - rxz * ryz) / np.sqrt((1 - rxz ** 2) * (1 - ryz ** 2))


def main(table, out):
    t = pd.read_csv(table)
    t = t[t.outcome.isin(["broken", "held"])]
    rng = np.random.default_rng(1)
    rows = []
    for x, what in DESCRIPTORS.items():
        rho = spearman(t[x], kick(t))
        rho_ci = stats.bootstrap_groups(lambda s: spearman(s[x], kick(s)), t, "seed", rng)
        p = partial(t, x, "theta_max_deg")
        p_ci = stats.bootstrap_groups(lambda s: partial(s, x, "theta_max_deg"), t, "seed", rng)
        q = partial(t, "theta_max_deg", x)
        q_ci = stats.bootstrap_groups(lambda s: partial(s, "theta_max_deg", x), t, "seed", rng)
        rows.append(dict(descriptor=x, meaning=what, n_arches=len(t), n_runs=t.seed.nunique(),
                         rho_with_theta_max=spearman(t[x], t.theta_max_deg),
                         rho=rho, rho_ci95_lo=rho_ci[0], rho_ci95_hi=rho_ci[1],
                         partial_given_theta_max=p, partial_ci95_lo=p_ci[0], partial_ci95_hi=p_ci[1],
                         theta_max_partial_given_it=q, theta_partial_ci95_lo=q_ci[0],
                         theta_partial_ci95_hi=q_ci[1]))
    r = pd.DataFrame(rows)
    r.to_csv(out, index=False, float_format="%.4g")
    print(r.drop(columns="meaning").to_string(index=False, float_format=lambda v: f"{v:.3g}"))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
