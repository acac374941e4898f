"""contacts.sscon (src/io/contacts.h): each recorded frame's grain-grain contacts and their normal forces, beside a
trajectory. Checked as siloscope's own reader checks it: the magic, the version, the grain count, ids in range,
frames in order, finite non-negative forces; a file cut off by a crash reads up to its last whole frame."""
import os

import numpy as np

from ._errors import SiloscopeError
from ._native import checked
from ._manifest import verify_listed
from ._tables import regular_file


def read_contacts(path, n_particles=None):
    """Every whole frame of a contacts file as a DataFrame: frame (the trajectory's frame index), a, b (grain ids)
    and force_N (normal force). `path`: the file or a recording directory; `n_particles`: the grain count it must
    match (the trajectory's), when given."""
    import pandas as pd
    if os.path.isdir(path):
        path = os.path.join(path, "contacts.sscon")
    regular_file(path, "contacts file")
    verify_listed(path)
    # With the compiled module, read first as the binary reads it: bounded by the run's size and tied to the
    # trajectory beside it (the grains it names must touch there).
    if os.path.exists(os.path.join(os.path.dirname(path), "trajectory.sstraj")):
        checked("check_contacts", os.path.dirname(path) or ".")
    raw = open(path, "rb").read()
    if len(raw) < 16 or raw[:8] != b"SILOCONT":
        raise SiloscopeError(f"{path}: not a siloscope contacts file (no SILOCONT header)")
    version, n = (int(v) for v in np.frombuffer(raw, "<u4", 2, 8))
    if version != 1:
        raise SiloscopeError(f"{path}: contacts file version {version}; this reader knows version 1")
    if n_particles is not None and n != n_particles:
        raise SiloscopeError(f"{path}: written for {n} grains, the trajectory has {n_particles}")
    record = np.dtype([("a", "<i4"), ("b", "<i4"), ("force_N", "<f4")])
    frames, parts, at, last = [], [], 16, -1
    while at + 8 <= len(raw):
        frame, count = (int(v) for v in np.frombuffer(raw, "<u4", 2, at))
        if at + 8 + 12 * count > len(raw):
            break  # cut off: the frames before it stand
        rows = np.frombuffer(raw, record, count, at + 8)
        if frame <= last:
            raise SiloscopeError(f"{path}: frame {frame} after frame {last} (frames out of order)")
        if count and (rows["a"].min() < 0 or rows["b"].min() < 0 or rows["a"].max() >= n or rows["b"].max() >= n):
            raise SiloscopeError(f"{path}: frame {frame} names a grain outside 0..{n - 1}")
        if count and not (np.isfinite(rows["force_N"]).all() and (rows["force_N"] >= 0).all()):
            raise SiloscopeError(f"{path}: frame {frame} holds a non-finite or negative force")
        frames.append(np.full(count, frame, dtype=np.int64))
        parts.append(rows)
        last = frame
        at += 8 + 12 * count
    rows = np.concatenate(parts) if parts else np.zeros(0, record)
    return pd.DataFrame({"frame": np.concatenate(frames) if frames else np.zeros(0, np.int64),
                         "a": rows["a"].astype(np.int64), "b": rows["b"].astype(np.int64),
                         "force_N": rows["force_N"].astype(np.float64)})
