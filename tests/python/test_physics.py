"""The physics page's estimators on data of known law (docs/physics/physics.py): the censored power-law tail
fit recovers its exponent and tells a power law from an exponential; Kaplan-Meier matches the empirical survival
without censoring."""
import importlib.util
import os

import numpy as np
import pytest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


@pytest.fixture(scope="module")
def physics():
    spec = importlib.util.spec_from_file_location("physics", os.path.join(ROOT, "docs", "physics", "physics.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_censored_power_law_tail_is_recovered(physics):
    rng = np.random.default_rng(7)
    for alpha in (1.5, 2.5):
        t = (1 - rng.random(4000)) ** (-1 / (alpha - 1))  # P(T > t) = t^(1 - alpha), t >= 1
        observed = (t < 30).astype(int)  # the run's end censors at 30
        t = np.minimum(t, 30)
        fit, lam, llr, vuong, n, d = physics.tail_fit(t, observed, 1.0)
        assert abs(fit - alpha) < 0.08, (alpha, fit)
        assert n == 4000 and d == int(observed.sum())
        assert llr > 0 and vuong < 0.01  # a power law, not an exponential
    # An exponential tail is not called a power law.
    t = 1 + rng.exponential(2.0, 4000)
    fit, lam, llr, vuong, n, d = physics.tail_fit(t, np.ones(4000, int), 1.0)
    assert llr < 0 and vuong < 0.01
    assert abs(1 / lam - 2.0) < 0.15


def test_kaplan_meier_without_censoring_is_the_empirical_survival(physics):
    t = np.array([3.0, 1.0, 2.0, 2.0, 5.0])
    times, surv = physics.kaplan_meier(t, np.ones(5, int))
    assert list(times) == [1.0, 2.0, 3.0, 5.0]
    assert np.allclose(surv, [0.8, 0.4, 0.2, 0.0])
    # One censored at 2: the survivors at risk shrink, the step at 3 is taken over 2 at risk.
    times, surv = physics.kaplan_meier(t, np.array([1, 1, 1, 0, 1]))
    assert np.allclose(surv, [0.8, 0.6, 0.3, 0.0])


def test_the_group_bootstrap_resamples_whole_groups():
    """Rows of one group move together: with every row of a group alike, the interval over groups is that of the
    group means' own bootstrap with the same draws, not the narrower one over rows as if independent."""
    import pandas as pd
    from siloscope import stats
    values = np.arange(8.0)
    table = pd.DataFrame({"run": np.repeat(np.arange(8), 10), "v": np.repeat(values, 10)})
    grouped = stats.bootstrap_groups(lambda t: t.v.mean(), table, "run", np.random.default_rng(3), k=500)
    means = stats.bootstrap(lambda s: s.mean(), pd.Series(values), np.random.default_rng(3), k=500)
    assert grouped == pytest.approx(means)
    rows = stats.bootstrap(lambda s: s.mean(), table.v, np.random.default_rng(3), k=500)
    assert rows[1] - rows[0] < 0.6 * (grouped[1] - grouped[0])
