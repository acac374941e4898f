"""A run or recording directory: its events, measurements, metadata and trajectory."""
import os
import shutil
import subprocess

import numpy as np

from ._errors import SiloscopeError
from ._native import checked
from ._metadata import read_metadata, species_of
from ._tables import read_table
from ._trajectory import Trajectory


class Run:
    """One realization, as `siloscope run` or `record` wrote it.

    >>> r = siloscope.read_run("runs/r04/s7")
    >>> r.exits            # DataFrame: t_s, id, species (the species' name)
    >>> r.clogs            # start_s, end_s, duration_s, ended_by, arrested
    >>> r.arches           # the long-lasting arches the clog rule removed
    >>> r.summary          # one row: Q, Q~, chi_eff, clogs, avalanches ...
    >>> r.species          # per species: count, exits, q_per_s (None for runs older than species.csv)
    >>> r.metadata["scene"]["seed"], r.scene["duration"]
    >>> r.trajectory       # a Trajectory (memory-mapped), or None when the run kept none
    """

    def __init__(self, path):
        self.path = path
        meta_path = os.path.join(path, "metadata.toml")
        if not os.path.isdir(path):
            raise SiloscopeError(f"{path}: not a directory (a run directory holds metadata.toml and exits.csv)")
        # With the compiled module, the run is opened as the binary opens it: its whole manifest checked.
        checked("check_run", path)
        self.metadata = read_metadata(meta_path)
        self.scene = self.metadata["scene"]
        self.species_names, _ = species_of(self.scene)
        self.exits = read_table(os.path.join(path, "exits.csv"), ("t_s", "id", "species"), counts=("id",),
                                finite=("t_s",))
        times = self.exits["t_s"].to_numpy()
        if len(times) > 1 and (np.diff(times) < 0).any():
            row = int(np.flatnonzero(np.diff(times) < 0)[0]) + 3
            raise SiloscopeError(f"{path}/exits.csv:{row}: t_s goes backwards")
        unknown = set(self.exits["species"]) - set(self.species_names)
        if unknown:
            raise SiloscopeError(f"{path}/exits.csv: species {sorted(unknown)[0]!r} is not one of the scene's "
                                 f"({', '.join(self.species_names)})")
        self.clogs = read_table(os.path.join(path, "clogs.csv"), ("start_s", "end_s", "duration_s", "ended_by"),
                                counts=("arrested",), finite=("start_s", "end_s", "duration_s"))
        if (self.clogs["duration_s"] < 0).any():
            raise SiloscopeError(f"{path}/clogs.csv: a clog with a negative duration")
        self.arches = read_table(os.path.join(path, "arches.csv"), ("t_s", "clog_duration_s", "method"),
                                 counts=("n_members", "n_added"))
        self.summary = read_table(os.path.join(path, "summary.csv"), counts=("exits", "clogs", "long_arches"),
                                  optional=True)
        self.species = read_table(os.path.join(path, "species.csv"), ("species", "count"), counts=("count", "exits"),
                                  optional=True)
        self._trajectory = None

    @property
    def trajectory(self):
        """The run's trajectory.sstraj, memory-mapped (a Trajectory), or None when the run kept none."""
        if self._trajectory is None:
            p = os.path.join(self.path, "trajectory.sstraj")
            if not os.path.exists(p):
                return None
            self._trajectory = Trajectory(p)
        return self._trajectory

    def __repr__(self):
        return (f"Run({self.path!r}: {len(self.exits)} exits, {len(self.clogs)} clogs, {len(self.arches)} "
                f"long-lasting arches, seed {self.scene['seed']})")

    def _repr_html_(self):
        """Jupyter: the run's name, its counts and its summary row (the player is run.player())."""
        import html
        rows = "".join(f"<tr><td>{html.escape(k)}</td><td>{html.escape(str(v))}</td></tr>"
                       for k, v in (("exits", len(self.exits)), ("clogs", len(self.clogs)),
                                    ("long-lasting arches", len(self.arches)), ("seed", self.scene.get("seed")),
                                    ("duration, s", self.scene.get("duration")),
                                    ("trajectory", "yes: run.player() plays it" if os.path.exists(
                                        os.path.join(self.path, "trajectory.sstraj")) else "none")))
        summary = self.summary.to_html(index=False) if self.summary is not None else ""
        return f"<b>siloscope run {html.escape(str(self.path))}</b><table>{rows}</table>{summary}"

    def player(self, height=480, start=None, stop=None, stride=1, look=()):
        """The run in a notebook: `siloscope share --embed`'s viewer (docs/share.md), shown by Jupyter as HTML.

        >>> siloscope.read_run("recordings/demo").player(height=520, start=5, stop=25)

        height: the viewer's height in CSS pixels (its width is the cell's); start, stop: a window in s; stride:
        every n-th frame; look: more command-line options of `share` (e.g. ["--background", "dark"]). The run
        must have a trajectory. Raises SiloscopeError with the binary's message."""
        import tempfile
        with tempfile.TemporaryDirectory(prefix="siloscope-player-") as tmp:
            out = os.path.join(tmp, "player.html")
            args = [binary(), "share", str(self.path), "--embed", "--out", out, "--stride", str(int(stride))]
            if start is not None:
                args += ["--from", repr(float(start))]
            if stop is not None:
                args += ["--to", repr(float(stop))]
            done = subprocess.run(args + [str(a) for a in look], capture_output=True, text=True)
            if done.returncode != 0:
                message = (done.stderr or done.stdout).strip().splitlines()
                raise SiloscopeError(message[-1] if message else f"siloscope share exited with {done.returncode}")
            with open(out, encoding="utf-8") as f:
                return Player(f.read(), height)


class Player:
    """A run's viewer for a notebook (Run.player()): Jupyter shows it; save() writes it as a page."""

    def __init__(self, fragment, height):
        self.fragment = fragment
        self.height = int(height)

    def _repr_html_(self):
        return f'<div style="width:100%;height:{self.height}px">{self.fragment}</div>'

    def save(self, path):
        """An HTML page holding the viewer (open it in any browser)."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(f"<!DOCTYPE html><html><head><meta charset='utf-8'></head><body style='margin:0'>"
                    f"{self._repr_html_()}</body></html>")
        return path

    def __repr__(self):
        return f"Player({len(self.fragment) / 1e6:.2f} MB: show it in Jupyter, or .save('run.html'))"


def read_run(path):
    """A run or recording directory (holding metadata.toml and exits.csv)."""
    return Run(path)


def binary():
    """The siloscope binary: $SILOSCOPE_BINARY, else build/siloscope of this clone, else siloscope on PATH."""
    env = os.environ.get("SILOSCOPE_BINARY")
    if env:
        return env
    here = os.path.dirname(os.path.abspath(__file__))
    # From a clone (src/python/siloscope), from the build's staged copy (build/share/siloscope/python/siloscope)
    # and from an installed one (PREFIX/share/siloscope/python/siloscope: the binary is PREFIX/bin/siloscope).
    for candidate in (os.path.join(here, "..", "..", "..", "build", "siloscope"),
                      os.path.join(here, "..", "..", "..", "..", "siloscope"),
                      os.path.join(here, "..", "..", "..", "..", "bin", "siloscope"),
                      os.path.join(here, "bin", "siloscope")):
        if os.access(candidate, os.X_OK):
            return os.path.normpath(candidate)
    found = shutil.which("siloscope")
    if found:
        return found
    raise SiloscopeError("no siloscope binary: build it (bash .ci/bootstrap) or set SILOSCOPE_BINARY")


def run(scene, out, seed=None, duration=None, set=None, trajectory_fps=None, force=False, extra=()):
    """Run the binary on a scene file and return the run:

    >>> r = siloscope.run("assets/scenes/paper.toml", "runs/s7", seed=7, duration=30,
    ...                   set={"size_ratio": 0.6, "mu": 1.0}, trajectory_fps=30)

    The arguments go to `siloscope run` as an argument vector (no shell); a failure raises SiloscopeError with
    the binary's own message."""
    args = [binary(), "run", str(scene), "--out", str(out), "--quiet"]
    if seed is not None:
        # A seed is a whole number: 2.7 is refused, not run as seed 2.
        import numbers
        if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or seed < 0:
            raise SiloscopeError(f"seed = {seed!r}: expected a whole number >= 0")
        args += ["--seed", str(int(seed))]
    if duration is not None:
        args += ["--duration", repr(float(duration))]
    for key, value in (set or {}).items():
        args += ["--set", f"{key}={value}"]
    if trajectory_fps is not None:
        args += ["--trajectory-fps", repr(float(trajectory_fps))]
    if force:
        args.append("--force")
    args += list(extra)
    done = subprocess.run(args, capture_output=True, text=True)
    if done.returncode != 0:
        message = (done.stderr or done.stdout).strip().splitlines()
        raise SiloscopeError(message[-1] if message else f"siloscope run exited with {done.returncode}")
    return Run(str(out))
