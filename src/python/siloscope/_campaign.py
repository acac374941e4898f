"""A campaign's analysis: `siloscope analyze` (or `sweep`) output."""
import os

from ._errors import SiloscopeError
from ._metadata import read_metadata
from ._tables import read_table

POINT_KEYS = ("size_ratio", "chi", "mu", "kick_impulse_max")


class Campaign:
    """The tables of an analysis directory, with their counts checked.

    >>> c = siloscope.read_campaign("docs/campaigns/paper")     # a results directory, or its analysis/
    >>> c.points          # one row per point: n_runs, means and 95% half-widths (q_tilde_per_s, ..._ci95)
    >>> c.realizations    # one row per realization (its summary.csv)
    >>> c.survival        # pooled P~(dt >= tau) per point
    >>> c.avalanches      # pooled P(S >= s) of avalanche sizes per point
    >>> c.species         # per point and species: flow and share of the exits (None before species.csv)
    >>> c.clog_survival   # per point: Kaplan-Meier survival of the clogs' durations (None before it existed)
    >>> c.campaign        # the campaign.toml beside it, as a dict (None when absent)
    """

    def __init__(self, path):
        analysis = path
        if not os.path.exists(os.path.join(path, "points.csv")) and os.path.exists(
                os.path.join(path, "analysis", "points.csv")):
            analysis = os.path.join(path, "analysis")
        if not os.path.exists(os.path.join(analysis, "points.csv")):
            raise SiloscopeError(f"{path} holds no points.csv (run `siloscope analyze` first)")
        self.path = analysis
        # n_runs is required; the other counts are checked where present (a hand-made table may leave them out).
        counts = ("clogs", "clogs_vibration", "clogs_rule", "clogs_spontaneous", "ballistic_runs", "n_refused")
        header = read_table(os.path.join(analysis, "points.csv"), POINT_KEYS).columns
        # Rates, sizes and their intervals are >= 0, shares are fractions (NaN: not measured at that point).
        rates = ("q_per_s", "q_tilde_per_s", "q_p_per_s", "long_arches_per_min", "added_per_long_arch",
                 "avalanche_mean", "q_tilde_over_qp")
        shares = ("chi_eff", "fraction_broken_by_vibration", "airborne_fraction")
        self.points = read_table(os.path.join(analysis, "points.csv"), POINT_KEYS,
                                 counts=("n_runs",) + tuple(c for c in counts if c in header),
                                 nonnegative=rates + tuple(c + "_ci95" for c in rates + shares), fractions=shares)
        if len(self.points) == 0:
            raise SiloscopeError(f"{analysis}/points.csv has no points")
        bad = self.points["n_runs"] < 1
        if bad.any():
            raise SiloscopeError(f"{analysis}/points.csv:{int(bad.to_numpy().nonzero()[0][0]) + 2}: n_runs = 0; a "
                                 "point needs at least one realization")
        self.realizations = read_table(os.path.join(analysis, "realizations.csv"), POINT_KEYS + ("seed",),
                                       counts=("exits", "clogs"), optional=True)
        self.survival = read_table(os.path.join(analysis, "survival.csv"), POINT_KEYS, counts=("gaps",),
                                   finite=("tau_s",), optional=True)
        self.avalanches = read_table(os.path.join(analysis, "avalanches.csv"), POINT_KEYS, counts=("avalanches",),
                                     optional=True)
        self.species = read_table(os.path.join(analysis, "species.csv"), POINT_KEYS, counts=("count", "n_runs"),
                                  optional=True)
        self.clog_survival = read_table(os.path.join(analysis, "clog_survival.csv"), POINT_KEYS,
                                        counts=("at_risk", "clogs"), optional=True)
        meta = os.path.join(analysis, "metadata.toml")
        self.metadata = read_metadata(meta) if os.path.exists(meta) else None
        # analyze writes how many points it wrote: a points.csv cut at a line's end (or a row deleted) keeps its
        # form, and only this count tells.
        declared = ((self.metadata or {}).get("run") or {}).get("points")
        if isinstance(declared, int) and not isinstance(declared, bool) and declared != len(self.points):
            raise SiloscopeError(f"{analysis}/points.csv has {len(self.points)} points where its metadata.toml says "
                                 f"analyze wrote {declared} (cut, or rows removed by hand?)")
        self.campaign = None
        for c in (os.path.join(analysis, "..", "campaign.toml"), os.path.join(analysis, "campaign.toml")):
            if os.path.exists(c):
                import tomllib
                try:
                    with open(c, "rb") as f:
                        self.campaign = tomllib.load(f)
                except tomllib.TOMLDecodeError as e:
                    raise SiloscopeError(f"{c}: malformed TOML ({e})") from None
                break

    @property
    def planned(self):
        """Realizations planned per point (campaign.toml), or None."""
        return int(self.campaign["realizations"]) if self.campaign and "realizations" in self.campaign else None

    def __repr__(self):
        return f"Campaign({self.path!r}: {len(self.points)} points, n = {self.points['n_runs'].min()}-" \
               f"{self.points['n_runs'].max()} per point)"


def read_campaign(path):
    """A sweep's results directory or an analysis directory (points.csv)."""
    return Campaign(path)
