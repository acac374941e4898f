"""A scene stepped in process (the compiled module _siloscope, pybind11): grains, contacts, arches and events
between steps, and the keys that may change during a run set between them.

    >>> import siloscope
    >>> s = siloscope.Simulation("assets/scenes/paper.toml", seed=7)    # deposited, settled, the outlet open
    >>> s.step(20000)                  # 20000 time steps (20 s at dt = 1 ms); returns what they did
    >>> s.time                         # s since the outlet opened, as --duration counts
    >>> s.positions, s.velocities      # (n, 2) numpy arrays, m and m/s, the container's frame
    >>> s.exits                        # DataFrame: t_s, id, species (the columns of exits.csv)
    >>> s.contacts                     # DataFrame: a, b, force (N), grain pairs in contact now
    >>> s.clog, s.arch                 # the open clog (None when flowing), the arch over the outlet now
    >>> s.set("outlet_open", False)    # keys that may change during a run: siloscope.Simulation.SETTABLE
    >>> t = siloscope.Simulation.from_state(s.state())   # or pickle / copy.deepcopy: the same next events
"""
import numbers
import os
import tempfile

import numpy as np

from ._errors import SiloscopeError
from ._native import module_or_none
from ._presets import scene_file


def _module():
    """The compiled module: installed beside this file, else the one a build of this clone staged."""
    m = module_or_none()
    if m is None:
        raise SiloscopeError("siloscope.Simulation needs the compiled module _siloscope: build the project "
                             "(bash .ci/bootstrap) or install the package (pip install ./)")
    return m


def _toml(value):
    """A Python value as --set takes it (TOML)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    raise SiloscopeError(f"{value!r}: a scene key takes a number, a boolean or a string")


class Simulation:
    """One simulation, stepped from Python. `scene`: a scene file (or a run's metadata.toml), None for the
    built-in default; `seed`: a whole number (the scene's own when None); every other keyword is a scene key
    (`aperture=0.35`), and `keys` takes those a keyword cannot spell (`{"species.beads.count": 200}`).

    The same scene and seed stepped here give the events `siloscope run` writes, byte for byte
    (`event_files()`)."""

    SETTABLE = ("kick_impulse_max", "outlet_open")

    def __init__(self, scene=None, seed=None, keys=None, **more):
        m = _module()
        if seed is not None and (isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or seed < 0
                                 or seed > 2**63 - 1):
            raise SiloscopeError(f"seed = {seed!r}: expected a whole number from 0 to 2^63 - 1")
        assignments = [f"{k}={_toml(v)}" for k, v in {**(keys or {}), **more}.items()]
        try:
            self._s = m.Simulation("" if scene is None else scene_file(scene), -1 if seed is None else int(seed),
                                   assignments)
        except (m.InputError, m.Unstable, m.RuntimeFault) as e:
            raise SiloscopeError(str(e)) from None
        self._m = m
        self.species_names = list(self._s.species_names())
        # What was done to it since it was made: ("to", time after a step or advance_to call), ("set", key,
        # value), ("finish",). With the scene and seed it is the state (state()): replayed, it gives the same
        # simulation step for step (time grows with every step, so a time names a step count).
        self._protocol = []

    STATE_FORMAT = "siloscope.Simulation state 1"

    def state(self):
        """This simulation as plain data (picklable, JSON-able): its scene with its seed, and every call that
        changed it since it was made. from_state() replays it to the same simulation, step for step, and the
        next steps give the same events as this one's; the replay costs the simulated time again (the scene is
        re-deposited and re-stepped: a snapshot of Box2D's internal state cannot be restored exactly)."""
        return {"format": self.STATE_FORMAT, "version": self._m.version, "scene": self.scene_toml(),
                "protocol": [list(p) for p in self._protocol]}

    @classmethod
    def from_state(cls, state):
        """The simulation a state() describes, replayed (see state()); ValueError for a state of another
        format or of another siloscope version (whose steps may differ)."""
        if not isinstance(state, dict) or state.get("format") != cls.STATE_FORMAT:
            raise SiloscopeError(f"from_state: not a Simulation state (format {state.get('format') if isinstance(state, dict) else type(state).__name__!r}; expected {cls.STATE_FORMAT!r})")
        m = _module()
        if state.get("version") != m.version:
            raise SiloscopeError(f"from_state: the state was saved by siloscope {state.get('version')}, this is "
                                 f"{m.version}: its steps would not be the same (replay with that version, or "
                                 "start again from the scene)")
        fd, path = tempfile.mkstemp(suffix=".toml", prefix="siloscope-state-")
        try:
            with os.fdopen(fd, "w") as f:
                f.write(state["scene"])
            sim = cls(path)
        finally:
            os.remove(path)
        for entry in state["protocol"]:
            if entry[0] == "to":
                sim.advance_to(float(entry[1]))
            elif entry[0] == "set":
                sim.set(entry[1], entry[2])
            elif entry[0] == "finish":
                sim.finish()
            else:
                raise SiloscopeError(f"from_state: unknown protocol entry {entry!r}")
        return sim

    def write_run(self, out, trajectory_fps=None, force=False):
        """Write what this simulation did as a run directory, the one `siloscope run` writes (events, summary,
        metadata with the protocol's timed changes under [run] protocol, manifest; a trajectory at
        trajectory_fps frames per simulated second if given), which analyze, inspect, frame, gallery, share and
        export accept. The binary replays this simulation's scene and protocol (runs are deterministic: the same
        steps and changes give the same events byte for byte) and ends it as a run ends (an open clog closed,
        censored). Returns the Run. This simulation is not changed."""
        steps = [p for p in self._protocol if p[0] != "finish"]
        if not any(p[0] == "to" and p[1] > 0 for p in steps):
            raise SiloscopeError("write_run: nothing was simulated yet (step or advance_to first)")
        lines = []
        for p in steps:
            if p[0] == "to":
                lines.append(f"to {p[1]!r}")
            elif p[1] == "outlet_open":
                lines.append(f"set outlet_open {'true' if p[2] else 'false'}")
            else:
                lines.append(f"set {p[1]} {float(p[2])!r}")
        from ._run import run as _run
        with tempfile.TemporaryDirectory(prefix="siloscope-run-") as tmp:
            scene = os.path.join(tmp, "scene.toml")
            protocol = os.path.join(tmp, "protocol.txt")
            with open(scene, "w") as f:
                f.write(self.scene_toml())
            with open(protocol, "w") as f:
                f.write("\n".join(lines) + "\n")
            return _run(scene, out, trajectory_fps=trajectory_fps, force=force, extra=("--protocol", protocol))

    def __reduce__(self):
        return (Simulation.from_state, (self.state(),))

    def __deepcopy__(self, memo):
        return Simulation.from_state(self.state())

    def __copy__(self):
        return Simulation.from_state(self.state())

    def _stepped(self, f, *args):
        """A stepping call; its end time enters the protocol even when Ctrl-C cut it short."""
        try:
            return self._call(f, *args)
        finally:
            now = self._s.time
            if self._protocol and self._protocol[-1][0] == "to":
                self._protocol[-1] = ("to", now)
            elif now > 0 or self._protocol:
                self._protocol.append(("to", now))

    def _call(self, f, *args):
        try:
            return f(*args)
        except (self._m.InputError, self._m.Unstable, self._m.RuntimeFault) as e:
            raise SiloscopeError(str(e)) from None

    def step(self, n=1):
        """Step n time steps; returns the events of those steps: exits [(t_s, id, species index)],
        clogs_opened [clog number], clogs_closed [(start_s, end_s, arrested)], rule_removed [(t_s, ids)].

        Ctrl-C stops it between two steps (KeyboardInterrupt within about 20 ms); the steps done stand and their
        events come with the next call. One thread at a time: a second thread calling this Simulation while it
        steps gets a RuntimeError (use one Simulation per thread; they run in parallel)."""
        if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 0:
            raise SiloscopeError(f"step(n): n = {n!r} must be a whole number >= 0")
        return self._stepped(self._s.step, int(n))

    def advance_to(self, t):
        """Step until time >= t (s since the outlet opened). t must be finite and not before `time`
        (ValueError otherwise); Ctrl-C and threads as for `step`."""
        return self._stepped(self._s.advance_to, float(t))

    @property
    def time(self):
        """Seconds since the outlet opened (as --duration counts)."""
        return self._s.time

    @property
    def dt(self):
        """The time step, s (the scene's dt)."""
        return self._s.dt

    @property
    def n(self):
        """The number of grains."""
        return self._s.n

    @property
    def seed(self):
        """The random seed (the scene's, or the one given)."""
        return self._s.seed

    @property
    def positions(self):
        """(n, 2) array of the grains' centres, m, in the container's frame."""
        return self._s.positions()

    def grains(self):
        """Every grain now: position (n, 2) m, velocity (n, 2) m/s, angle rad, radius m (of the disk of equal
        area), species (index into species_names), sides (0: a disk)."""
        return self._s.grains()

    @property
    def velocities(self):
        """(n, 2) array of the grains' velocities, m/s."""
        return self._s.grains()["velocity"]

    @property
    def angles(self):
        """The grains' orientations, rad (polygons turn; a disk's angle is its own spin)."""
        return self._s.grains()["angle"]

    @property
    def radii(self):
        """The grains' radii, m (a polygon's: of the disk of equal area)."""
        return self._s.grains()["radius"]

    @property
    def species(self):
        """Each grain's species, as an index into species_names."""
        return self._s.grains()["species"]

    @property
    def contacts(self):
        """Grain pairs in contact now, with their forces over the last step: DataFrame a, b, force (normal, N),
        ft (tangential, N, signed along (ny, -nx)), x, y (where they touch, m), nx, ny (unit normal from a to
        b)."""
        import pandas as pd
        return pd.DataFrame(self._s.contacts())

    @property
    def clog(self):
        """The open clog as a dict (number, start_s, arrested, arch: its members), or None while flowing."""
        return self._s.clog()

    @property
    def arch(self):
        """The arch standing over the outlet now (Box2D's contacts), member ids left to right; [] if none."""
        return self._s.arch()

    @property
    def exits(self):
        """Every exit so far: DataFrame t_s, id, species (the species' name), the columns of exits.csv."""
        import pandas as pd
        e = self._s.exits()
        names = np.array(self.species_names, dtype=object)
        return pd.DataFrame({"t_s": e["t_s"], "id": e["id"], "species": names[e["species"]] if len(e["id"])
                             else np.array([], dtype=object)})

    def event_files(self):
        """exits.csv, clogs.csv and arches.csv as `siloscope run` would write them now (text)."""
        return self._s.event_files()

    def finish(self):
        """Close an open clog as censored, as the end of a run does (once, at the end)."""
        self._call(self._s.finish)
        self._protocol.append(("finish",))

    def set(self, key, value):
        """Change a key from the next step on: kick_impulse_max (N*s), outlet_open (True/False)."""
        if isinstance(value, np.bool_):
            value = bool(value)
        elif isinstance(value, numbers.Real) and not isinstance(value, bool):
            value = float(value)
        self._call(self._s.set, str(key), value)
        self._protocol.append(("set", str(key), value))

    @property
    def outlet_open(self):
        """Whether the outlet is open (set("outlet_open", False) puts the lid back across it)."""
        return self._s.outlet_open

    def scene_toml(self):
        """The scene as a scene file (TOML), seed included: what reproduces this simulation."""
        return self._s.scene_toml()

    def render(self, width=1280, height=720, camera="split", overlay="all", color="species", dark=False):
        """The simulation now as `record` draws it (the same renderer, off-screen): an (height, width, 3) uint8
        RGB array. camera: hopper, outlet, split or window:X0,Y0,X1,Y1 (record's --camera); overlay: all, none
        or a list such as "time,counts,arch" (--overlay); color: species, speed or force (--color); dark: the
        dark background. Each picture stands alone (no trails or box layout carried over)."""
        for name, side in (("width", width), ("height", height)):
            if isinstance(side, bool) or not isinstance(side, numbers.Integral):
                raise SiloscopeError(f"render({name}={side!r}): expected a whole number of pixels")
        return self._call(self._s.render, int(width), int(height), str(camera), str(overlay), str(color),
                          bool(dark))

    def _repr_png_(self):
        """Jupyter shows a Simulation as its picture now (640x360, split camera)."""
        import io as _io
        import matplotlib.image as mpimg
        buf = _io.BytesIO()
        mpimg.imsave(buf, self.render(640, 360), format="png")
        return buf.getvalue()

    def __repr__(self):
        return f"Simulation({self.n} grains, t = {self.time:.3f} s, seed {self.seed})"
