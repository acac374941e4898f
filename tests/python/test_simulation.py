"""siloscope.Simulation: the scene stepped in process (the compiled module)."""
import os
import subprocess

import numpy as np
import pytest

import siloscope


def test_stepped_from_python_gives_the_events_run_writes(binary, root, tmp_path):
    scene = os.path.join(root, "assets/scenes/paper.toml")
    subprocess.run([binary, "run", scene, "--seed", "7", "--duration", "20", "--quiet", "--out",
                    str(tmp_path / "run")], check=True)
    s = siloscope.Simulation(scene, seed=7)
    assert s.time == 0.0 and s.n == 250
    s.step(20000)
    assert s.time == pytest.approx(20.0, abs=1e-9)
    s.finish()
    files = s.event_files()
    for name in ("exits.csv", "clogs.csv", "arches.csv"):
        assert files[name] == (tmp_path / "run" / name).read_text(), name
    # The exits table has exits.csv's columns and rows.
    e = s.exits
    assert list(e.columns) == ["t_s", "id", "species"]
    assert len(e) == len(files["exits.csv"].splitlines()) - 1
    assert set(e["species"]) <= {"original", "added"}


def test_arrays_contacts_and_the_arch(root):
    s = siloscope.Simulation(os.path.join(root, "assets/scenes/pentagons.toml"), seed=3, duration=5.0)
    s.step(500)
    g = s.grains()
    n = s.n
    assert g["position"].shape == (n, 2) and g["velocity"].shape == (n, 2)
    assert np.isfinite(g["position"]).all()
    assert (g["radius"] > 0).all() and (g["sides"] == 5).all()
    assert np.array_equal(s.positions, g["position"])
    c = s.contacts
    assert len(c) > n // 2 and (c["force"] >= 0).all() and (c["a"] != c["b"]).all()
    arch = s.arch
    assert all(0 <= i < n for i in arch)
    if s.clog is not None:
        assert s.clog["start_s"] <= s.time


def test_the_outlet_closed_and_opened_between_steps(root):
    s = siloscope.Simulation(os.path.join(root, "assets/scenes/silo-obstacle.toml"), seed=2, obstacle="none",
                             clog_timeout=0.0)
    s.set("outlet_open", False)
    assert not s.outlet_open
    s.advance_to(0.5)  # grains above the outlet meet the lid
    before = len(s.exits)
    s.advance_to(3.0)
    assert len(s.exits) == before  # closed: none leaves
    s.set("outlet_open", True)
    s.advance_to(6.0)
    assert len(s.exits) > before + 20
    s.set("kick_impulse_max", 1e-3)
    s.step(10)


def test_bad_input_raises_one_line_naming_it(root):
    scene = os.path.join(root, "assets/scenes/paper.toml")
    with pytest.raises(siloscope.SiloscopeError, match="seed = 2.7"):
        siloscope.Simulation(scene, seed=2.7)
    with pytest.raises(siloscope.SiloscopeError, match="aperture"):
        siloscope.Simulation(scene, aperture=-1.0)
    with pytest.raises(siloscope.SiloscopeError, match="no_such_key"):
        siloscope.Simulation(scene, no_such_key=1)
    s = siloscope.Simulation(scene, seed=1, settle_time=2.0)
    with pytest.raises(siloscope.SiloscopeError, match="kick_impulse_max.*outlet_open"):
        s.set("mu", 1.0)
    with pytest.raises(siloscope.SiloscopeError, match="True or False"):
        s.set("outlet_open", 1)
    with pytest.raises(siloscope.SiloscopeError, match="n = -1"):
        s.step(-1)
