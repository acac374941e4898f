"""trajectory.sstraj (docs/trajectory.md): every recorded frame, memory-mapped; nothing is loaded until used."""
import os
import tomllib

import numpy as np

from ._errors import SiloscopeError
from ._metadata import check_metadata, species_of
from ._manifest import verify_listed
from ._tables import regular_file

HEADER = np.dtype([("magic", "S8"), ("version", "<u4"), ("header_bytes", "<u4"), ("n", "<u4"), ("max_arch", "<u4"),
                   ("frame_bytes", "<u4"), ("n_species", "<u4"), ("frame_interval_s", "<f8"),
                   ("clog_timeout_s", "<f8"), ("clog_min_gap_s", "<f8"), ("radius_original_m", "<f8")])


ENDED_BY = ("spontaneous", "vibration", "rule", "run_end")


def frame_dtype(n, max_arch, version=2, n_species=2):
    """One frame record (docs/trajectory.md); version 2 adds the open clog's state and counts exits per species."""
    if version >= 2:
        fields = [("t", "<f8"), ("since_last_exit", "<f8"), ("clog_start", "<f8"), ("rule_due_in", "<f8"),
                  ("long_arches", "<i4"), ("clog_number", "<i4"), ("clog_flags", "<u4"), ("arch_count", "<i4"),
                  ("arch", "<i4", (max_arch,)), ("exits", "<i8", (n_species,))]
    else:
        fields = [("t", "<f8"), ("since_last_exit", "<f8"), ("exits_original", "<i8"), ("exits_added", "<i8"),
                  ("long_arches", "<i4"), ("arch_count", "<i4"), ("arch", "<i4", (max_arch,))]
    fields += [(name, "<f4", (n,)) for name in ("x", "y", "angle", "vx", "vy", "force")]
    return np.dtype(fields)


def _read_events(raw, at, end, n, path, version=3):
    """The events block of a version 2 or 3 file (docs/trajectory.md): exits, clogs (version 3: with their arch's
    formation) and the rule's removals."""
    import pandas as pd

    def bad(what):
        return SiloscopeError(f"{path}: corrupted events block ({what})")

    if raw[at:at + 8] != b"SILOEVTS":
        raise bad("no SILOEVTS at its offset")
    n_exits, n_clogs, n_arches = (int(v) for v in np.frombuffer(raw, "<u4", 3, at + 8))
    at += 24
    clog_bytes = 32 if version >= 3 else 24
    if n_exits * 16 + n_clogs * clog_bytes + n_arches * 48 > end - at:
        raise bad(f"{n_exits} exits, {n_clogs} clogs and {n_arches} arches do not fit")
    ex = np.frombuffer(raw, [("t_s", "<f8"), ("id", "<i4"), ("species", "<u4")], n_exits, at)
    at += 16 * n_exits
    fields = [("start_s", "<f8"), ("end_s", "<f8"), ("ended_by", "<u4"), ("arrested", "<u4")]
    cl = np.frombuffer(raw, fields + ([("formed_s", "<f8")] if version >= 3 else []), n_clogs, at)
    at += clog_bytes * n_clogs
    if not (np.all(np.isfinite(ex["t_s"])) and np.all((ex["id"] >= 0) & (ex["id"] < n))):
        raise bad("an exit's time or id is out of range")
    if not (np.all(np.isfinite(cl["start_s"])) and np.all(cl["end_s"] >= cl["start_s"])
            and np.all(cl["ended_by"] <= 3) and np.all(cl["arrested"] <= 1)):
        raise bad("a clog's times or ending are out of range")
    arches = []
    for k in range(n_arches):
        if at + 48 > end:
            raise bad(f"arch {k + 1} is cut off")
        t, duration, span, height, angle = np.frombuffer(raw, "<f8", 5, at)
        count, method = (int(v) for v in np.frombuffer(raw, "<u4", 2, at + 40))
        at += 48
        if count > n or 16 * count > end - at or method > 1:
            raise bad(f"arch {k + 1} has values out of range")
        members = np.frombuffer(raw, [("id", "<i4"), ("species", "<u4"), ("x", "<f4"), ("y", "<f4")], count, at)
        at += 16 * count
        arches.append({"t_s": float(t), "clog_s": float(duration), "span_m": float(span), "height_m": float(height),
                       "max_angle_deg": float(angle), "method": ("contact_path", "visible")[method],
                       "ids": members["id"].astype(np.int64), "x": members["x"].astype(float),
                       "y": members["y"].astype(float)})
    if at != end:
        raise bad(f"{end - at} bytes left over")
    exits = pd.DataFrame({"t_s": ex["t_s"].astype(float), "id": ex["id"].astype(np.int64),
                          "species": ex["species"].astype(np.int64)})
    clogs = pd.DataFrame({"start_s": cl["start_s"].astype(float), "end_s": cl["end_s"].astype(float),
                          "duration_s": (cl["end_s"] - cl["start_s"]).astype(float),
                          "ended_by": [ENDED_BY[int(v)] for v in cl["ended_by"]],
                          "arrested": cl["arrested"].astype(np.int64),
                          "formed_s": cl["formed_s"].astype(float) if version >= 3 else np.full(n_clogs, np.nan)})
    return exits, clogs, arches


class Trajectory:
    """A trajectory, memory-mapped.

    >>> tr = siloscope.read_trajectory("recordings/demo/trajectory.sstraj")
    >>> len(tr), tr.n                  # frames, grains
    >>> tr.t[:3], tr.x[100, 7]         # times (s); grain 7's x at frame 100 (m)
    >>> tr.arch(100)                   # the open clog's arch at frame 100, grain ids left to right
    >>> tr.clogs, tr.arch_events       # the run's clogs (clogs.csv's columns) and the rule's removals
                                       # (None for a version 1 or cut-off file)
    >>> tr.species_names, tr.species[:5], tr.sides[:5], tr.radius[:5]
    """

    def __init__(self, path):
        self.path = path
        real = regular_file(path, "trajectory file")
        verify_listed(path)
        size = os.path.getsize(real)
        if size < HEADER.itemsize:
            raise SiloscopeError(f"{path}: truncated trajectory header ({size} bytes)")
        head = np.fromfile(real, dtype=HEADER, count=1)[0]
        if head["magic"] != b"SILOTRAJ":
            raise SiloscopeError(f"{path}: not a siloscope trajectory (no SILOTRAJ header)")
        self.version = int(head["version"])
        if self.version not in (1, 2, 3):
            raise SiloscopeError(f"{path}: trajectory version {self.version}; this reader reads versions 1 to 3")
        self.n = int(head["n"])
        self.max_arch = int(head["max_arch"])
        self.header_bytes = int(head["header_bytes"])
        self.frame_interval = float(head["frame_interval_s"])
        self.clog_timeout = float(head["clog_timeout_s"])
        self.clog_min_gap = float(head["clog_min_gap_s"])
        self.n_species = int(head["n_species"]) if self.version >= 2 else 2
        if not 1 <= self.n_species <= 16:
            raise SiloscopeError(f"{path}: corrupted trajectory header ({self.n_species} species; allowed: 1 to 16)")
        # Checked before any array is sized from them: a header may promise more than the file holds.
        if HEADER.itemsize + 5 * self.n > size or self.header_bytes > size or not 0 < self.max_arch <= 1024:
            raise SiloscopeError(f"{path}: corrupted trajectory header (it promises {self.n} grains and a "
                                 f"{self.header_bytes}-byte header; the file holds {size} bytes)")
        dtype = frame_dtype(self.n, self.max_arch, self.version, self.n_species)
        if int(head["frame_bytes"]) != dtype.itemsize or self.header_bytes > size:
            raise SiloscopeError(f"{path}: corrupted trajectory header (frame size or header size)")
        self.radius = np.fromfile(real, dtype="<f4", count=self.n, offset=HEADER.itemsize)
        self.species = np.fromfile(real, dtype="u1", count=self.n, offset=HEADER.itemsize + 4 * self.n)
        meta_at = (HEADER.itemsize + 5 * self.n + 7) // 8 * 8
        length = int(np.fromfile(real, dtype="<u4", count=1, offset=meta_at)[0])
        if meta_at + 4 + length > self.header_bytes:
            raise SiloscopeError(f"{path}: corrupted trajectory header (metadata length)")
        with open(real, "rb") as f:
            f.seek(meta_at + 4)
            text = f.read(length).decode("utf-8", errors="replace")
        try:
            self.metadata = check_metadata(tomllib.loads(text), f"{path} (its metadata)")
        except tomllib.TOMLDecodeError as e:
            raise SiloscopeError(f"{path}: its metadata is malformed TOML ({e})") from None
        self.species_names, species_sides = species_of(self.metadata["scene"])
        if self.n and int(self.species.max()) >= len(self.species_names):
            raise SiloscopeError(f"{path}: a grain has species {int(self.species.max())}; the scene has "
                                 f"{len(self.species_names)}")
        self.sides = np.asarray(species_sides, dtype=np.int32)[self.species] if self.n else np.zeros(0, np.int32)
        # Version 2 ends with the run's events and a footer pointing at them; without the footer (a cut file, or
        # version 1) the frames run to the end and the events are not there.
        frames_end = size
        self.exit_events = self.clogs = self.arch_events = None
        if self.version >= 2 and size >= self.header_bytes + 16:
            with open(real, "rb") as f:
                f.seek(size - 16)
                tail = f.read(16)
            if tail[8:] == b"SILOEND\0":
                offset = int(np.frombuffer(tail, "<u8", 1)[0])
                if not (self.header_bytes <= offset <= size - 40) or (offset - self.header_bytes) % dtype.itemsize:
                    raise SiloscopeError(f"{path}: corrupted events block (its offset {offset} points at no events)")
                with open(real, "rb") as f:
                    f.seek(offset)
                    raw = f.read(size - 16 - offset)
                self.exit_events, self.clogs, self.arch_events = _read_events(raw, 0, len(raw), self.n, path,
                                                                              self.version)
                frames_end = offset
        count = (frames_end - self.header_bytes) // dtype.itemsize  # whole frames: a cut file reads to its last
        self.truncated = (frames_end - self.header_bytes) % dtype.itemsize != 0
        self.frames = np.memmap(real, dtype=dtype, mode="r", offset=self.header_bytes, shape=(count,)) if count else \
            np.zeros(0, dtype=dtype)
        self._check_frames(path)

    def _check_frames(self, path):
        """The frames' values, checked as `siloscope inspect` checks them (io/trajectory.cpp): time finite and
        running forwards, exit counts never negative nor falling, the clog timer not negative, clog state in
        range, every grain value finite and no grain farther from the container than ten times its size."""
        f = self.frames
        if not len(f):
            return

        def refuse(k, what):
            raise SiloscopeError(f"{path}: frame {int(k)} is corrupted: {what}")

        t = f["t"]
        bad = np.flatnonzero(~np.isfinite(t))
        if len(bad):
            refuse(bad[0], "its time is not a finite number")
        back = np.flatnonzero(np.diff(t) <= 0)
        if len(back):
            k = back[0] + 1
            refuse(k, f"its time {t[k]!r} s does not come after the previous frame's {t[k - 1]!r} s")
        exits = np.asarray(self.exits, dtype=np.int64).reshape(len(f), -1)
        low = np.flatnonzero((exits < 0).any(axis=1) | np.r_[False, (np.diff(exits, axis=0) < 0).any(axis=1)])
        if len(low):
            refuse(low[0], "an exit count is negative or lower than the previous frame's")
        since = f["since_last_exit"]
        bad = np.flatnonzero(~np.isfinite(since) | (since < 0))
        if len(bad):
            refuse(bad[0], "its time since the last exit is negative or not a finite number")
        if self.version >= 2:
            bad = np.flatnonzero(~np.isfinite(f["clog_start"]) | np.isnan(f["rule_due_in"]) |
                                 (f["clog_number"] < 0) | (f["clog_flags"] > (7 if self.version >= 3 else 3)))
            if len(bad):
                refuse(bad[0], "its clog state (start, rule time, number or flags) is out of range")
        scene = self.metadata.get("scene", {}) if isinstance(self.metadata, dict) else {}
        size = max(float(scene.get("silo_height", 0)) + float(scene.get("hopper_height", 0)),
                   float(scene.get("silo_width", 0)))
        reach = 10.0 * size + 1.0 if size > 0 else 1e3
        for name in ("x", "y", "angle", "vx", "vy", "force"):
            v = f[name]
            bad = np.argwhere(~np.isfinite(v))
            if len(bad):
                refuse(bad[0][0], f"{name} of particle {int(bad[0][1])} is not a finite number")
            if name in ("x", "y"):
                far = np.argwhere(np.abs(v) > reach)
                if len(far):
                    k, i = far[0]
                    refuse(k, f"{name} of particle {int(i)} is {float(v[k, i]):.7g} m, far outside the container "
                              f"(allowed: within {reach:g} m)")

    def __repr__(self):
        t = self.frames["t"] if len(self.frames) else np.zeros(0)
        span = f"{float(t[0]):g} to {float(t[-1]):g} s" if len(t) else "no frames"
        clogs = "" if self.clogs is None else f", {len(self.clogs)} clogs"
        return (f"Trajectory({self.path!r}: {len(self.frames)} frames, {self.n} grains, {span}{clogs}, "
                f"version {self.version})")

    def __len__(self):
        return len(self.frames)

    def __getattr__(self, name):
        # t, since_last_exit, long_arches, arch_count, x, y, angle, vx, vy, force; version 2 also clog_start,
        # rule_due_in, clog_number, clog_flags and exits (frames x species); version 1 exits_original, exits_added
        if name.startswith("__") or "frames" not in self.__dict__:
            raise AttributeError(name)
        if name in self.frames.dtype.names and name != "arch":
            return self.frames[name]
        if name == "exits" and self.version < 2:
            return np.stack([self.frames["exits_original"], self.frames["exits_added"]], axis=1)
        raise AttributeError(name)

    def clog_open(self, k):
        """Whether a clog is open at frame k (version 1: the clog timer has reached clog_min_gap)."""
        f = self.frames[k]
        if self.version >= 2:
            return bool(int(f["clog_flags"]) & 1)
        return bool(f["since_last_exit"] >= self.clog_min_gap and f["t"] > 0)

    def arch_forming(self, k):
        """Whether the arch of frame k is forming: it stands, its clog not yet confirmed (version 3)."""
        return self.version >= 3 and bool(int(self.frames[k]["clog_flags"]) & 4)

    def arch(self, k):
        """The arch at frame k, grain ids left to right: the open clog's, or (version 3) the forming one; empty
        when there is none."""
        f = self.frames[k]
        ids = np.asarray(f["arch"][: max(0, min(int(f["arch_count"]), self.max_arch))], dtype=np.int64)
        shown = self.clog_open(k) or self.arch_forming(k)
        return ids if len(ids) >= 2 and shown else np.zeros(0, dtype=np.int64)


def read_trajectory(path):
    """A trajectory file (or a directory holding trajectory.sstraj), memory-mapped."""
    if os.path.isdir(path):
        path = os.path.join(path, "trajectory.sstraj")
    return Trajectory(path)
