"""contacts.sscon (src/io/contacts.h): each recorded frame's contacts and their forces, beside a trajectory.
Checked as siloscope's own reader checks it: the magic, the version (1: grain-grain normal forces; 2: with the
tangential force, the contact point and normal, and the grains' contacts with walls), the grain count, ids in
range, frames in order, finite non-negative normal forces, unit normals; a file cut off by a crash reads up to
its last whole frame."""
import os

import numpy as np

from ._errors import SiloscopeError
from ._native import checked
from ._manifest import verify_listed
from ._tables import regular_file

MAX_WALLS = 4096  # io::Contacts::kMaxWalls: a wall's record names -1 .. -MAX_WALLS

RECORDS = {
    1: np.dtype([("a", "<i4"), ("b", "<i4"), ("force_N", "<f4")]),
    2: np.dtype([("a", "<i4"), ("b", "<i4"), ("force_N", "<f4"), ("ft_N", "<f4"), ("x_m", "<f4"), ("y_m", "<f4"),
                 ("nx", "<f4"), ("ny", "<f4")]),
}


def read_contacts(path, n_particles=None):
    """Every whole frame of a contacts file as a DataFrame: frame (the trajectory's frame index), a, b and force_N
    (the normal force, >= 0). Version-2 files (what siloscope writes now) add ft_N (the tangential force, signed along
    (ny, -nx)), x_m, y_m (where the two touch) and nx, ny (the unit normal from a to b), and list each grain's
    contacts with walls too: there b is the grain and a = -1 - the wall's index. On b the force is
    force_N * n + ft_N * (ny, -nx). `path`: the file or a recording directory; `n_particles`: the grain count it
    must match (the trajectory's), when given."""
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
    if version not in RECORDS:
        raise SiloscopeError(f"{path}: contacts file version {version}; this reader knows versions 1 and 2")
    if n_particles is not None and n != n_particles:
        raise SiloscopeError(f"{path}: written for {n} grains, the trajectory has {n_particles}")
    record = RECORDS[version]
    lowest = -MAX_WALLS if version >= 2 else 0
    frames, parts, at, last = [], [], 16, -1
    while at + 8 <= len(raw):
        frame, count = (int(v) for v in np.frombuffer(raw, "<u4", 2, at))
        if at + 8 + record.itemsize * count > len(raw):
            break  # cut off: the frames before it stand
        rows = np.frombuffer(raw, record, count, at + 8)
        if frame <= last:
            raise SiloscopeError(f"{path}: frame {frame} after frame {last} (frames out of order)")
        if count and (rows["a"].min() < lowest or rows["b"].min() < 0 or rows["a"].max() >= n
                      or rows["b"].max() >= n):
            walls = f" (a wall: -1..-{MAX_WALLS} in a)" if version >= 2 else ""
            raise SiloscopeError(f"{path}: frame {frame} names a grain outside 0..{n - 1}{walls}")
        if count and not (np.isfinite(rows["force_N"]).all() and (rows["force_N"] >= 0).all()):
            raise SiloscopeError(f"{path}: frame {frame} holds a non-finite or negative force")
        if count and version >= 2:
            numbers = np.stack([rows[k] for k in ("ft_N", "x_m", "y_m", "nx", "ny")])
            if not np.isfinite(numbers).all():
                raise SiloscopeError(f"{path}: frame {frame} holds a non-finite number")
            if (np.abs(np.hypot(rows["nx"].astype(np.float64), rows["ny"]) - 1) > 1e-3).any():
                raise SiloscopeError(f"{path}: frame {frame} holds a contact normal that is not a unit vector")
        frames.append(np.full(count, frame, dtype=np.int64))
        parts.append(rows)
        last = frame
        at += 8 + record.itemsize * count
    rows = np.concatenate(parts) if parts else np.zeros(0, record)
    out = {"frame": np.concatenate(frames) if frames else np.zeros(0, np.int64),
           "a": rows["a"].astype(np.int64), "b": rows["b"].astype(np.int64)}
    for name in record.names[2:]:
        out[name] = rows[name].astype(np.float64)
    return pd.DataFrame(out)
