"""trajectory.sstraj (docs/trajectory.md): every recorded frame, memory-mapped; nothing is loaded until used."""
import os
import tomllib

import numpy as np

from ._errors import SiloscopeError
from ._metadata import check_metadata, species_of
from ._tables import regular_file

HEADER = np.dtype([("magic", "S8"), ("version", "<u4"), ("header_bytes", "<u4"), ("n", "<u4"), ("max_arch", "<u4"),
                   ("frame_bytes", "<u4"), ("reserved", "<u4"), ("frame_interval_s", "<f8"),
                   ("clog_timeout_s", "<f8"), ("clog_min_gap_s", "<f8"), ("radius_original_m", "<f8")])


def frame_dtype(n, max_arch):
    return np.dtype([("t", "<f8"), ("since_last_exit", "<f8"), ("exits_original", "<i8"), ("exits_added", "<i8"),
                     ("long_arches", "<i4"), ("arch_count", "<i4"), ("arch", "<i4", max_arch), ("x", "<f4", n),
                     ("y", "<f4", n), ("angle", "<f4", n), ("vx", "<f4", n), ("vy", "<f4", n), ("force", "<f4", n)])


class Trajectory:
    """A trajectory, memory-mapped.

    >>> tr = siloscope.read_trajectory("recordings/demo/trajectory.sstraj")
    >>> len(tr), tr.n                  # frames, grains
    >>> tr.t[:3], tr.x[100, 7]         # times (s); grain 7's x at frame 100 (m)
    >>> tr.arch(100)                   # the blocking arch's grain ids at frame 100, left to right
    >>> tr.species_names, tr.species[:5], tr.sides[:5], tr.radius[:5]
    """

    def __init__(self, path):
        self.path = path
        real = regular_file(path, "trajectory file")
        size = os.path.getsize(real)
        if size < HEADER.itemsize:
            raise SiloscopeError(f"{path}: truncated trajectory header ({size} bytes)")
        head = np.fromfile(real, dtype=HEADER, count=1)[0]
        if head["magic"] != b"SILOTRAJ":
            raise SiloscopeError(f"{path}: not a siloscope trajectory (no SILOTRAJ header)")
        if head["version"] != 1:
            raise SiloscopeError(f"{path}: trajectory version {head['version']}; this reader reads version 1")
        self.n = int(head["n"])
        self.max_arch = int(head["max_arch"])
        self.header_bytes = int(head["header_bytes"])
        self.frame_interval = float(head["frame_interval_s"])
        self.clog_timeout = float(head["clog_timeout_s"])
        self.clog_min_gap = float(head["clog_min_gap_s"])
        dtype = frame_dtype(self.n, self.max_arch)
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
        count = (size - self.header_bytes) // dtype.itemsize  # whole frames only: a cut file reads to its last one
        self.truncated = (size - self.header_bytes) % dtype.itemsize != 0
        self.frames = np.memmap(real, dtype=dtype, mode="r", offset=self.header_bytes, shape=(count,)) if count else \
            np.zeros(0, dtype=dtype)

    def __len__(self):
        return len(self.frames)

    def __getattr__(self, name):
        # t, since_last_exit, exits_original, exits_added, long_arches, arch_count, x, y, angle, vx, vy, force
        if name in ("t", "since_last_exit", "exits_original", "exits_added", "long_arches", "arch_count", "x", "y",
                    "angle", "vx", "vy", "force"):
            return self.frames[name]
        raise AttributeError(name)

    def arch(self, k):
        """The grain ids of the blocking arch at frame k, left to right (empty: none)."""
        f = self.frames[k]
        return np.asarray(f["arch"][: max(0, min(int(f["arch_count"]), self.max_arch))], dtype=np.int64)


def read_trajectory(path):
    """A trajectory file (or a directory holding trajectory.sstraj), memory-mapped."""
    if os.path.isdir(path):
        path = os.path.join(path, "trajectory.sstraj")
    return Trajectory(path)
