"""siloscope's runs and campaigns in Python: tables as pandas DataFrames, trajectories as memory-mapped numpy
arrays, metadata as dicts. Pure Python on numpy and pandas (Debian's python3-numpy, python3-pandas); from a clone:

    export PYTHONPATH=$PWD/src/python
    python3 -c "import siloscope"

    >>> import siloscope
    >>> r = siloscope.read_run("recordings/demo")        # a run or recording directory
    >>> r.summary["q_tilde_per_s"][0]                     # the run's Q~, 1/s
    >>> r.exits.head()                                    # t_s, id, species
    >>> r.scene["seed"], r.metadata["siloscope"]["version"]
    >>> tr = r.trajectory                                 # trajectory.sstraj, memory-mapped (None without one)
    >>> tr.t[-1], tr.x.shape                              # last time, (frames, grains)
    >>> r.player(height=480)                              # in Jupyter: the run played in the notebook (share)
    >>> siloscope.read_contacts("recordings/demo")        # frame, a, b, force_N: the force chains of every frame
    >>> c = siloscope.read_campaign("docs/campaigns/paper")   # a sweep's results, or an analysis directory
    >>> c.points[["size_ratio", "q_tilde_per_s", "n_runs"]]
    >>> r = siloscope.run("assets/scenes/pure.toml", "runs/quick", duration=10, seed=3)   # the binary, then read_run
    >>> s = siloscope.Simulation("assets/scenes/paper.toml", seed=7)   # in process (the compiled module)
    >>> s.step(20000); s.exits.tail()                                  # 20 s; exits as exits.csv has them

Every reader checks what it reads: a missing file, a wrong header, a value out of its range (a negative count,
time running backwards) raises siloscope.SiloscopeError with one line naming the file, the field and the value.
"""
from ._errors import SiloscopeError
from ._trajectory import Trajectory, read_trajectory
from ._run import Player, Run, read_run, run
from ._campaign import Campaign, read_campaign
from ._simulation import Simulation
from ._contacts import read_contacts
from ._presets import presets, scene_file

__all__ = ["SiloscopeError", "Trajectory", "read_trajectory", "Run", "Player", "read_run", "run", "Campaign",
           "read_campaign", "Simulation", "read_contacts", "presets", "scene_file"]


def _version():
    """The version CMakeLists.txt defines: written beside the package when it is built or installed
    (_version.py), else read from the clone this package sits in."""
    try:
        from ._version import version
        return version
    except ImportError:
        pass
    import os
    import re
    cmake = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "CMakeLists.txt")
    try:
        with open(cmake) as f:
            return re.search(r"project\(siloscope VERSION ([0-9.]+)", f.read()).group(1)
    except (OSError, AttributeError):
        return "unknown"


__version__ = _version()
