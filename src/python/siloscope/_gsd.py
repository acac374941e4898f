"""A trajectory as GSD (HOOMD-blue's format; python3-gsd from Debian), for OVITO and HOOMD users: each species a
particle type with its shape (a disk, or the regular polygon's vertices), each grain's orientation as a
quaternion, the box the container's bounding box (2D). `siloscope export RUN --format gsd` calls write_gsd."""
import math

import numpy as np

from ._errors import SiloscopeError


def polygon_extent(sides):
    """Circumradius over the radius of the disk of equal area, for a regular polygon (core/frame.h)."""
    return math.sqrt(2.0 * math.pi / (sides * math.sin(2.0 * math.pi / sides)))


def type_shapes(trajectory):
    """Per species, HOOMD's shape specification at the species' mean size: a Sphere of its mean diameter (a disk
    in 2D) or a Polygon of its vertices (the polygon of equal area, first vertex on +x at angle 0)."""
    shapes = []
    for k, _ in enumerate(trajectory.species_names):
        mine = trajectory.species == k
        r = float(trajectory.radius[mine].mean()) if mine.any() else 0.0
        sides = int(trajectory.sides[mine][0]) if mine.any() else 0
        if sides >= 3:
            R = r * polygon_extent(sides)
            vertices = [[R * math.cos(2 * math.pi * j / sides), R * math.sin(2 * math.pi * j / sides)]
                        for j in range(sides)]
            shapes.append({"type": "Polygon", "rounding_radius": 0.0, "vertices": vertices})
        else:
            shapes.append({"type": "Sphere", "diameter": 2.0 * r})
    return shapes


def write_gsd(trajectory, path, first=0, last=None, box=None, contacts=None):
    """Frames first..last (inclusive) of `trajectory` into the GSD file `path`. `box`: (x0, y0, x1, y1) of the
    container, m; positions are shifted so that its centre is the box's origin (HOOMD's convention), the shift
    is logged as siloscope/origin. `contacts` (read_contacts' DataFrame): each frame's grain pairs in contact
    become its bonds (type "contact"), their forces the bond properties log/bonds/normal_force_N and (a
    version-2 file's) log/bonds/tangential_force_N, which OVITO loads as bond properties."""
    try:
        import gsd.hoomd
    except ImportError:
        raise SiloscopeError("GSD export needs python3-gsd (apt install python3-gsd)") from None
    last = len(trajectory) - 1 if last is None else last
    x0, y0, x1, y1 = box if box is not None else (float(np.min(trajectory.frames["x"][first:last + 1])),
                                                  float(np.min(trajectory.frames["y"][first:last + 1])),
                                                  float(np.max(trajectory.frames["x"][first:last + 1])),
                                                  float(np.max(trajectory.frames["y"][first:last + 1])))
    cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    lx, ly = (x1 - x0) * 1.02 + 1e-6, (y1 - y0) * 1.02 + 1e-6
    shapes = type_shapes(trajectory)
    n = trajectory.n
    by_frame = {}
    if contacts is not None and len(contacts):
        pairs = contacts[contacts["a"] >= 0]  # grain pairs: a wall is no particle
        starts = np.searchsorted(pairs["frame"].to_numpy(), np.arange(first, last + 2))
        for k in range(first, last + 1):
            by_frame[k] = pairs.iloc[starts[k - first]:starts[k - first + 1]]
    with gsd.hoomd.open(path, "wb") as f:
        for k in range(first, last + 1):
            fr = trajectory.frames[k]
            s = gsd.hoomd.Snapshot()
            s.configuration.step = k
            s.configuration.dimensions = 2
            s.configuration.box = [lx, ly, 0.0, 0.0, 0.0, 0.0]
            s.particles.N = n
            s.particles.types = list(trajectory.species_names)
            s.particles.type_shapes = shapes
            s.particles.typeid = trajectory.species.astype(np.uint32)
            pos = np.zeros((n, 3), dtype=np.float32)
            pos[:, 0] = fr["x"] - cx
            pos[:, 1] = fr["y"] - cy
            s.particles.position = pos
            half = 0.5 * fr["angle"].astype(np.float64)
            q = np.zeros((n, 4), dtype=np.float32)  # HOOMD's order: (w, x, y, z), a turn about z
            q[:, 0] = np.cos(half)
            q[:, 3] = np.sin(half)
            s.particles.orientation = q
            s.particles.diameter = (2.0 * trajectory.radius).astype(np.float32)
            vel = np.zeros((n, 3), dtype=np.float32)
            vel[:, 0], vel[:, 1] = fr["vx"], fr["vy"]
            s.particles.velocity = vel
            s.log["siloscope/time_s"] = np.array([float(fr["t"])])
            s.log["siloscope/origin_m"] = np.array([cx, cy])
            s.log["siloscope/force_N"] = np.asarray(fr["force"], dtype=np.float32)
            if contacts is not None:
                c = by_frame.get(k, contacts.iloc[0:0])
                s.bonds.N = len(c)
                s.bonds.types = ["contact"]
                s.bonds.typeid = np.zeros(len(c), dtype=np.uint32)
                s.bonds.group = np.stack([c["a"].to_numpy(), c["b"].to_numpy()], axis=1).astype(np.uint32) \
                    .reshape(len(c), 2)
                s.log["bonds/normal_force_N"] = c["force_N"].to_numpy(dtype=np.float32)
                if "ft_N" in c:
                    s.log["bonds/tangential_force_N"] = c["ft_N"].to_numpy(dtype=np.float32)
            f.append(s)
    return path
