"""The statistics of results, in one place for Python (the binary's are in src/analysis/stats.h, and these follow
them): the mean of independent realizations with its Student-t 95% interval, a proportion's Wilson interval, a
percentile bootstrap over realizations (or over groups of rows), the Kaplan-Meier survival of censored durations, and the maximum-likelihood
fit of a power-law tail against an exponential one. Numpy only.

    >>> from siloscope.stats import mean_ci95, wilson
    >>> mean_ci95([1.0, 2.0, 3.0])          # (mean, half-width, n): (2.0, 2.48..., 3)
    >>> wilson(3, 40)                       # (lo, hi) of 3/40
"""
import math
from statistics import NormalDist

import numpy as np


def _betacf(a, b, x):
    """The continued fraction of the incomplete beta function (modified Lentz)."""
    tiny, qab, qap, qam = 1e-300, a + b, a + 1.0, a - 1.0
    c, d = 1.0, 1.0 - qab * x / qap
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 300):
        m2 = 2 * m
        for aa in (m * (b - m) * x / ((qam + m2) * (a + m2)), -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2))):
            d = 1.0 + aa * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + aa / c
            c = c if abs(c) > tiny else tiny
            h *= d * c
        if abs(d * c - 1.0) < 3e-16:
            break
    return h


def incomplete_beta(a, b, x):
    """The regularized incomplete beta function I_x(a, b)."""
    if x <= 0:
        return 0.0
    if x >= 1:
        return 1.0
    front = math.exp(math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log1p(-x))
    if x < (a + 1) / (a + b + 2):
        return front * _betacf(a, b, x) / a
    return 1.0 - front * _betacf(b, a, 1 - x) / b


def student_t_cdf(t, nu):
    """P(T <= t) for Student's t with nu degrees of freedom."""
    tail = 0.5 * incomplete_beta(0.5 * nu, 0.5, nu / (nu + t * t))
    return 1 - tail if t > 0 else tail


def student_t_critical(confidence, nu):
    """The two-sided critical value t* with P(|T| <= t*) = confidence."""
    target = 0.5 + 0.5 * confidence
    lo, hi = 0.0, 1e3
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if student_t_cdf(mid, nu) < target else (lo, mid)
    return 0.5 * (lo + hi)


def mean_ci95(samples):
    """(mean, half-width of its 95% Student-t interval, n) of the finite samples; the half-width is NaN for n < 2
    (one realization has no interval: say so, never draw a bar of zero)."""
    a = np.asarray([x for x in samples if math.isfinite(x)], dtype=float)
    if len(a) < 2:
        return (float(a.mean()) if len(a) else math.nan), math.nan, len(a)
    n = len(a)
    return float(a.mean()), float(student_t_critical(0.95, n - 1) * a.std(ddof=1) / math.sqrt(n)), n


def wilson(k, n, z=1.96):
    """The 95% Wilson score interval (lo, hi) of a proportion k/n; NaNs for n = 0."""
    if n == 0:
        return math.nan, math.nan
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return max(0.0, centre - half), min(1.0, centre + half)


def bootstrap(stat, samples, rng, k=2000):
    """The 95% percentile interval (lo, hi) of stat over `samples` (a pandas DataFrame or Series of
    realizations), resampling them with replacement k times with `rng` (numpy's Generator). A resample whose stat
    is NaN is left out."""
    out = [stat(samples.iloc[rng.integers(0, len(samples), len(samples))]) for _ in range(k)]
    return tuple(np.nanquantile(out, [0.025, 0.975]))


def bootstrap_groups(stat, table, by, rng, k=2000):
    """The 95% percentile interval (lo, hi) of stat over a pandas DataFrame whose rows come in groups that are not
    independent (the arches of one run share its packing): whole groups, named by column `by`, are resampled with
    replacement k times with `rng`; a resample whose stat is NaN is left out."""
    import pandas as pd
    groups = [g for _, g in table.groupby(by)]
    out = []
    for _ in range(k):
        pick = rng.integers(0, len(groups), len(groups))
        out.append(stat(pd.concat([groups[i] for i in pick])))
    return tuple(np.nanquantile(np.asarray(out, float), [0.025, 0.975]))


def bootstrap_ratio(stat, a, b, rng, k=2000):
    """The 95% percentile interval of stat(a) / stat(b), resampling the realizations of a and b independently."""
    out = []
    for _ in range(k):
        ra = a.iloc[rng.integers(0, len(a), len(a))]
        rb = b.iloc[rng.integers(0, len(b), len(b))]
        out.append(stat(ra) / stat(rb))
    return tuple(np.nanquantile(out, [0.025, 0.975]))


def kaplan_meier(t, observed):
    """Kaplan-Meier survival of durations t (observed: 1 ended, 0 censored): (times, S just after each), at each
    time with an ended duration."""
    order = np.argsort(t, kind="stable")
    t, observed = np.asarray(t, float)[order], np.asarray(observed, int)[order]
    times, surv, s, at_risk = [], [], 1.0, len(t)
    for u in np.unique(t):
        here = t == u
        d = int(observed[here].sum())
        if d:
            s *= 1 - d / at_risk
            times.append(u)
            surv.append(s)
        at_risk -= int(here.sum())
    return np.asarray(times), np.asarray(surv)


def tail_fit(t, observed, tmin):
    """Right-censored maximum likelihood of the tail t >= tmin: a power law P(T > t) = (t / tmin)^(1 - alpha)
    against a shifted exponential exp(-lambda (t - tmin)). Returns alpha, lambda, the log-likelihood ratio R
    (power law minus exponential, > 0 favours the power law), Vuong's p-value for its sign, the tail's size and
    its ended (uncensored) count."""
    t, observed = np.asarray(t, float), np.asarray(observed, int)
    keep = t >= tmin
    t, observed = t[keep], observed[keep]
    d = int(observed.sum())
    if d < 2:
        return math.nan, math.nan, math.nan, math.nan, len(t), d
    logs = np.log(t / tmin)
    a = d / logs.sum()
    lam = d / (t - tmin).sum()
    ll_pl = np.where(observed == 1, math.log(a) - math.log(tmin) - (a + 1) * logs, -a * logs)
    ll_ex = np.where(observed == 1, math.log(lam) - lam * (t - tmin), -lam * (t - tmin))
    diff = ll_pl - ll_ex
    r = float(diff.sum())
    sd = float(diff.std(ddof=1)) if len(diff) > 1 else math.nan
    p = 2 * (1 - NormalDist().cdf(abs(r) / (math.sqrt(len(diff)) * sd))) if sd > 0 else math.nan
    return 1 + a, lam, r, p, len(t), d
