"""export --format gsd (HOOMD, OVITO) and the XYZ export's quaternions: read back with the gsd package and ASE."""
import math
import os
import subprocess

import numpy as np
import pytest

import siloscope
from siloscope._gsd import polygon_extent

gsd_hoomd = pytest.importorskip("gsd.hoomd")


@pytest.fixture(scope="module")
def pentagons(binary, root, tmp_path_factory):
    out = tmp_path_factory.mktemp("pent") / "rec"
    subprocess.run([binary, "record", os.path.join(root, "assets/scenes/pentagons.toml"), "--duration", "1.5",
                    "--size", "320x240", "--fps", "10", "--quiet", "--out", str(out)], check=True)
    return out


def test_gsd_holds_each_species_shape_and_orientation(binary, pentagons, tmp_path):
    path = tmp_path / "p.gsd"
    subprocess.run([binary, "export", str(pentagons), "--format", "gsd", "--out", str(path)], check=True)
    t = siloscope.read_trajectory(str(pentagons))
    with gsd_hoomd.open(str(path), "rb") as f:
        assert len(f) == len(t)
        s = f[len(f) - 1]
        assert s.configuration.dimensions == 2
        assert s.particles.N == t.n and s.particles.types == t.species_names
        shape = s.particles.type_shapes[0]
        assert shape["type"] == "Polygon" and len(shape["vertices"]) == 5
        # The vertices' circumradius: the polygon of equal area to the species' mean disk.
        R = math.hypot(*shape["vertices"][0])
        assert R == pytest.approx(float(t.radius.mean()) * polygon_extent(5), rel=1e-5)
        q = s.particles.orientation.astype(float)
        assert np.allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-6)
        angle = 2.0 * np.arctan2(q[:, 3], q[:, 0])
        want = t.frames["angle"][len(t) - 1].astype(float)
        assert np.allclose(np.cos(angle), np.cos(want), atol=1e-5) and np.allclose(np.sin(angle), np.sin(want),
                                                                                   atol=1e-5)
        origin = s.log["siloscope/origin_m"]
        assert np.allclose(s.particles.position[:, 0] + origin[0], t.frames["x"][len(t) - 1], atol=1e-5)
        # The frame's grain pairs in contact are its bonds, their forces bond properties.
        c = siloscope.read_contacts(str(pentagons))
        pairs = c[(c["frame"] == len(t) - 1) & (c["a"] >= 0)]
        assert s.bonds.N == len(pairs) > 50 and s.bonds.types == ["contact"]
        assert (s.bonds.group[:, 0] == pairs["a"].to_numpy()).all()
        assert np.allclose(s.log["bonds/normal_force_N"], pairs["force_N"], rtol=1e-6)
        assert np.allclose(s.log["bonds/tangential_force_N"], pairs["ft_N"], rtol=1e-6)
    # Its own file is replaced with --force; one that is not GSD is refused.
    assert subprocess.run([binary, "export", str(pentagons), "--format", "gsd", "--out", str(path), "--force"],
                          capture_output=True).returncode == 0
    other = tmp_path / "notes.gsd"
    other.write_text("mine\n")
    done = subprocess.run([binary, "export", str(pentagons), "--format", "gsd", "--out", str(other), "--force"],
                          capture_output=True, text=True)
    assert done.returncode == 2 and "not a GSD file" in done.stderr
    assert other.read_text() == "mine\n"


def test_xyz_carries_the_orientation_quaternion(binary, pentagons, tmp_path):
    ase_io = pytest.importorskip("ase.io")
    path = tmp_path / "p.xyz"
    subprocess.run([binary, "export", str(pentagons), "--format", "xyz", "--out", str(path)], check=True)
    frames = ase_io.read(str(path), index=":")
    last = frames[-1]
    q = last.arrays["orientation"]
    assert q.shape == (len(last), 4)
    angle = last.arrays["angle"]
    # Shoemake's (x, y, z, w), OVITO's Orientation: a turn by the angle about z.
    assert np.allclose(q[:, 2], np.sin(angle / 2), atol=1e-5) and np.allclose(q[:, 3], np.cos(angle / 2), atol=1e-5)
