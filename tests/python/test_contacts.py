"""siloscope.read_contacts: a recording's contacts.sscon, checked as the C++ reader checks it."""
import os
import shutil
import subprocess

import numpy as np
import pytest

import siloscope


def test_contacts_of_a_recording(recording, tmp_path):
    t = siloscope.read_trajectory(str(recording))
    c = siloscope.read_contacts(str(recording), n_particles=t.n)
    assert list(c.columns) == ["frame", "a", "b", "force_N", "ft_N", "x_m", "y_m", "nx", "ny"]
    assert c["frame"].nunique() == len(t) and (np.diff(c["frame"].to_numpy()) >= 0).all()
    walls = c["a"] < 0
    assert walls.any() and (~walls).any()  # grains rest on the walls
    assert (c["force_N"] >= 0).all() and c["a"].between(-4096, t.n - 1).all() and c["b"].between(0, t.n - 1).all()
    assert np.allclose(np.hypot(c["nx"], c["ny"]), 1, atol=1e-4)
    # Coulomb: friction within its cone (the paper's friction 0.5), and some friction carried. Box2D clamps the
    # friction impulse against the normal impulse of its iteration, which later iterations may lower: of the
    # contacts carrying 0.1 N or more while the silo settles, 1.1% were past the cone by more than 5% (measured),
    # none by a factor.
    loaded = c[c["force_N"] > 0.1]
    ratio = loaded["ft_N"].abs() / loaded["force_N"]
    assert (ratio > 0.525).mean() < 0.03 and ratio.max() < 1.0 and (ratio > 0.1).mean() > 0.3
    # Disks: the contact point on the line of centres, a radius from b's centre.
    last = c[(c["frame"] == len(t) - 1) & ~walls]
    f = t.frames[len(t) - 1]
    b, r = last["b"].to_numpy(), np.asarray(t.radius)
    reach = np.hypot(f["x"][b] - last["x_m"], f["y"][b] - last["y_m"])
    assert np.allclose(reach, r[b], rtol=0.05)
    # A file cut in its last frame reads its whole frames; a foreign or corrupted one raises naming it.
    cut = tmp_path / "cut.sscon"
    raw = (recording / "contacts.sscon").read_bytes()
    cut.write_bytes(raw[:-5])
    assert siloscope.read_contacts(str(cut))["frame"].nunique() == len(t) - 1
    with pytest.raises(siloscope.SiloscopeError, match="written for 250 grains"):
        siloscope.read_contacts(str(recording), n_particles=99)
    bad = tmp_path / "bad.sscon"
    b = bytearray(raw)
    b[16 + 8:16 + 12] = (10**6).to_bytes(4, "little")  # the first contact's grain id
    bad.write_bytes(bytes(b))
    with pytest.raises(siloscope.SiloscopeError, match="outside 0..249"):
        siloscope.read_contacts(str(bad))
    other = tmp_path / "notes.sscon"
    shutil.copy(recording / "metadata.toml", other)
    with pytest.raises(siloscope.SiloscopeError, match="not a siloscope contacts file"):
        siloscope.read_contacts(str(other))


def test_every_listed_contact_touches_in_its_frame(binary, root, tmp_path):
    """A grain re-injected at the top after a step kept its contact with a grain below the outlet: the run's
    last frame of 18 s of the paper's scene (seed 1) listed 7 pairs 3 m apart, which the reader then took for
    the contacts of another recording. Every pair of every frame now touches in that frame's positions."""
    out = tmp_path / "run"
    subprocess.run([binary, "run", os.path.join(root, "assets/scenes/paper.toml"), "--duration", "18",
                    "--trajectory-fps", "30", "--quiet", "--out", str(out)], check=True)
    t = siloscope.read_trajectory(str(out))
    c = siloscope.read_contacts(str(out), n_particles=t.n)
    r = np.asarray(t.radius)
    apart = 0
    for k, pairs in c[c["a"] >= 0].groupby("frame"):
        f = t.frames[int(k)]
        a, b = pairs["a"].to_numpy(), pairs["b"].to_numpy()
        apart += int((np.hypot(f["x"][a] - f["x"][b], f["y"][a] - f["y"][b]) > 1.1 * (r[a] + r[b])).sum())
    assert c["frame"].nunique() == len(t) and apart == 0
