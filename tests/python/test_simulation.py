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
    # With the tangential force, where they touch and the unit normal from a to b (pentagons: not the line of
    # centres, but within a grain's reach of both).
    assert list(c.columns) == ["a", "b", "force", "ft", "x", "y", "nx", "ny"]
    assert np.allclose(np.hypot(c["nx"], c["ny"]), 1, atol=1e-5) and (c["ft"] != 0).any()
    pos, r = s.positions, s.grains()["radius"]
    a, b = c["a"].to_numpy(), c["b"].to_numpy()
    reach = 1.2 * np.maximum(r[a], r[b]) * 1.3
    assert (np.hypot(c["x"] - pos[a, 0], c["y"] - pos[a, 1]) < reach).all()
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


def test_two_threads_on_one_simulation_raise_never_abort(root):
    # One Simulation stepped from two threads: the second gets a RuntimeError naming the cause (before: Box2D's
    # assertion aborted Python). Two Simulations in two threads both finish.
    import threading
    scene = os.path.join(root, "assets/scenes/paper.toml")
    s = siloscope.Simulation(scene, seed=7)
    errors, done = [], []

    def work(sim):
        try:
            for _ in range(10):
                sim.step(2000)
            done.append(sim)
        except RuntimeError as e:
            errors.append(str(e))

    threads = [threading.Thread(target=work, args=(s,)) for _ in range(2)]
    reader_errors = []

    def read():  # a reader while another thread steps: refused the same way, never a crash
        for _ in range(200):
            try:
                s.grains()
            except RuntimeError as e:
                reader_errors.append(str(e))
    threads.append(threading.Thread(target=read))
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(done) >= 1
    assert all("another thread" in e for e in errors + reader_errors)
    assert len(errors) + len(reader_errors) >= 1
    s.step(10)  # still usable
    pair = [siloscope.Simulation(scene, seed=k) for k in (1, 2)]
    done.clear()
    threads = [threading.Thread(target=work, args=(p,)) for p in pair]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(done) == 2


def test_ctrl_c_stops_a_long_step_and_leaves_it_usable(root):
    import signal
    import threading
    import time
    s = siloscope.Simulation(os.path.join(root, "assets/scenes/paper.toml"), seed=7)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        s.step(10**9)
    late = time.monotonic() - start - 0.5
    assert late < 0.5, f"KeyboardInterrupt {late:.2f} s after SIGINT"
    t = s.time
    assert 0 < t < 10**6 * s.dt
    s.step(100)
    assert s.time == pytest.approx(t + 100 * s.dt, rel=1e-9)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        s.advance_to(10**7)


def test_advance_to_refuses_times_it_cannot_reach(root):
    s = siloscope.Simulation(os.path.join(root, "assets/scenes/paper.toml"), seed=1)
    s.advance_to(0.5)
    for bad in (float("nan"), float("inf"), -1.0, 0.1):
        with pytest.raises(ValueError, match=r"advance_to\(t\): t = "):
            s.advance_to(bad)
    assert s.time == pytest.approx(0.5, abs=s.dt)
    with pytest.raises(ValueError):  # the package's error is a ValueError
        s.step(-1)


def test_a_saved_state_continues_with_the_same_events(root):
    import copy
    import json
    import pickle
    import time
    s = siloscope.Simulation(os.path.join(root, "assets/scenes/paper.toml"), seed=7)
    s.step(3000)
    s.set("kick_impulse_max", np.float64(1e-4))  # a numpy value, kept as a float
    s.advance_to(5.0)
    s.set("outlet_open", np.bool_(False))         # a numpy bool is a bool
    s.step(500)
    s.set("outlet_open", True)
    s.step(1234)
    state = s.state()
    assert json.loads(json.dumps(state)) == state   # plain data
    start = time.monotonic()
    copies = [siloscope.Simulation.from_state(state), pickle.loads(pickle.dumps(s)), copy.deepcopy(s)]
    restore = (time.monotonic() - start) / 3
    for c in copies:
        assert c.time == s.time and c.seed == s.seed and c.outlet_open
        assert np.array_equal(c.positions, s.positions)
    s.step(4000)
    s.finish()
    for c in copies:
        c.step(4000)
        c.finish()
        assert c.event_files() == s.event_files()
    print(f"restore {restore:.2f} s for {s.time:.1f} s simulated")
    with pytest.raises(ValueError, match="version"):
        siloscope.Simulation.from_state({**state, "version": "0.0.1"})
    with pytest.raises(ValueError, match="not a Simulation state"):
        siloscope.Simulation.from_state({"format": "x"})


def test_import_does_not_load_pandas():
    # pandas (0.3 s of a 0.4 s import) loads when a table is first asked for, not at `import siloscope`.
    import sys
    pkg = os.path.dirname(os.path.dirname(siloscope.__file__))
    code = "import sys, siloscope; print('pandas' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env=dict(os.environ, PYTHONPATH=pkg)).stdout.strip()
    assert out == "False"


def test_a_protocol_written_from_python_is_a_run_the_commands_take(binary, root, tmp_path):
    # Issue 55: kicks switched on and off by Python; the run written gives the simulation's own events, byte
    # for byte, and inspect and analyze take it.
    s = siloscope.Simulation("paper", seed=7, clog_timeout=0.0, kick_impulse_max=0.0)
    s.advance_to(3.0)
    s.set("kick_impulse_max", 5e-3)
    s.step(2500)
    s.set("kick_impulse_max", 0.0)
    s.advance_to(6.0)
    r = s.write_run(tmp_path / "run", trajectory_fps=30)
    assert s.time == pytest.approx(6.0, abs=1e-9)  # the simulation itself goes on as it was
    s.finish()
    files = s.event_files()
    for name in ("exits.csv", "clogs.csv", "arches.csv"):
        assert (tmp_path / "run" / name).read_text() == files[name], name
    assert len(r.exits) > 0
    assert 0 < 6.0 - float(r.trajectory.t[-1]) <= r.trajectory.frame_interval  # frames to the protocol's end
    assert "set kick_impulse_max 0.005" in r.metadata["run"]["protocol"]
    script = tmp_path / "s.txt"
    script.write_text("goto end\nprint\n")
    shown = subprocess.run([binary, "inspect", str(tmp_path / "run"), "--quiet", "--script", str(script)],
                           capture_output=True, text=True)
    assert shown.returncode == 0, shown.stderr
    analysed = subprocess.run([binary, "analyze", str(tmp_path / "run"), "--out", str(tmp_path / "an")],
                              capture_output=True, text=True)
    assert analysed.returncode == 0, analysed.stderr
    assert (tmp_path / "an" / "points.csv").exists()
    # Nothing simulated yet: nothing to write; a protocol file with a bad line is refused naming it.
    with pytest.raises(siloscope.SiloscopeError, match="nothing was simulated"):
        siloscope.Simulation("paper", seed=7).write_run(tmp_path / "none")
    bad = tmp_path / "bad.txt"
    bad.write_text("to 1\nset mu 3\n")
    done = subprocess.run([binary, "run", os.path.join(root, "assets/scenes/paper.toml"), "--protocol", str(bad),
                           "--out", str(tmp_path / "bad")], capture_output=True, text=True)
    assert done.returncode == 2 and "bad.txt:2: 'set mu 3'" in done.stderr
    assert not (tmp_path / "bad").exists()
