"""siloscope.read_contacts: a recording's contacts.sscon, checked as the C++ reader checks it."""
import shutil

import numpy as np
import pytest

import siloscope


def test_contacts_of_a_recording(recording, tmp_path):
    t = siloscope.read_trajectory(str(recording))
    c = siloscope.read_contacts(str(recording), n_particles=t.n)
    assert list(c.columns) == ["frame", "a", "b", "force_N"]
    assert c["frame"].nunique() == len(t) and (np.diff(c["frame"].to_numpy()) >= 0).all()
    assert (c["force_N"] >= 0).all() and c["a"].between(0, t.n - 1).all() and c["b"].between(0, t.n - 1).all()
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
