"""The Python package reads what the binary wrote, exactly, and refuses what it did not write in one line."""
import os
import shutil
import subprocess

import numpy as np
import pytest

import siloscope


def test_read_run_gives_tables_metadata_and_a_memory_mapped_trajectory(recording, binary, tmp_path):
    r = siloscope.read_run(str(recording))
    assert r.scene["seed"] == 1 and r.metadata["siloscope"]["version"]
    assert list(r.exits.columns) == ["t_s", "id", "species"]
    assert set(r.exits["species"]) <= {"original", "added"}
    assert r.summary["exits"][0] == len(r.exits[r.exits["t_s"] <= r.scene["duration"]])
    assert list(r.species["species"]) == ["original", "added"]
    tr = r.trajectory
    assert isinstance(tr.frames, np.memmap)  # not loaded: mapped
    assert tr.n == 250 and len(tr) > 20
    assert tr.species_names == ["original", "added"]
    assert int((tr.species == 1).sum()) == 100 and abs(float(tr.radius[0]) - 0.065) < 1e-7
    # The same numbers the binary's own CSV export gives for a frame.
    subprocess.run([binary, "export", str(recording), "--format", "csv", "--frames", "15", "--out",
                    str(tmp_path / "f.csv")], check=True, capture_output=True)
    import pandas as pd
    csv = pd.read_csv(tmp_path / "f.csv")
    k = 15
    assert abs(csv["t_s"][0] - tr.t[k]) < 1e-6
    for i in (0, 7, 249):
        row = csv[csv["id"] == i].iloc[0]
        assert abs(row["x_m"] - tr.x[k, i]) < 1e-6 and abs(row["y_m"] - tr.y[k, i]) < 1e-6
    assert list(tr.arch(k)) == list(csv[csv["in_arch"] == 1]["id"]) or len(tr.arch(k)) == int(csv["in_arch"].sum())


def test_run_calls_the_binary_with_an_argument_vector(binary, tmp_path, root):
    out = tmp_path / "odd name; $(touch nope)"
    r = siloscope.run(os.path.join(root, "assets/scenes/pure.toml"), out, seed=3, duration=2,
                      set={"settle_time": 2})
    assert r.scene["seed"] == 3 and r.scene["duration"] == 2.0 and r.scene["chi"] == 0.0
    assert not os.path.exists("nope")
    with pytest.raises(siloscope.SiloscopeError, match="chi = 2.0 is not allowed"):
        siloscope.run(os.path.join(root, "assets/scenes/pure.toml"), tmp_path / "bad", set={"chi": 2})
    # A seed is a whole number: 2.7 is refused before anything runs, not run as seed 2.
    for seed in (2.7, -1, True, "3"):
        with pytest.raises(siloscope.SiloscopeError, match="seed = .*whole number"):
            siloscope.run(os.path.join(root, "assets/scenes/pure.toml"), tmp_path / "seed", seed=seed)
    assert not os.path.exists(tmp_path / "seed")


def test_read_campaign_gives_the_committed_tables(root):
    c = siloscope.read_campaign(os.path.join(root, "docs/campaigns/paper"))
    assert len(c.points) == 34 and c.points["n_runs"].min() == 50 and c.planned == 50
    assert len(c.realizations) == 1700
    assert set(c.avalanches.columns) >= {"size", "survival", "avalanches"}


def one_line(excinfo):
    text = str(excinfo.value)
    assert "\n" not in text and "Traceback" not in text
    return text


def test_bad_files_give_one_line_naming_file_field_and_value(recording, root, tmp_path):
    run = tmp_path / "run"
    shutil.copytree(recording, run)
    meta = (run / "metadata.toml").read_text()
    (run / "metadata.toml").write_text(meta[: meta.index("[scene]") + 10])  # truncated
    with pytest.raises(siloscope.SiloscopeError) as e:
        siloscope.read_run(str(run))
    assert "metadata.toml" in one_line(e)
    (run / "metadata.toml").write_text(meta)
    # Without the manifest (a run of an older version), so that the value check itself is what refuses: with it,
    # the manifest refuses first (tests/python/test_readers.py).
    (run / "manifest.toml").unlink()
    (run / "metadata.toml").write_text(meta.replace('manifest = "manifest.toml"\n', "", 1))
    exits = (run / "exits.csv").read_text().splitlines()
    exits.insert(2, "9.5,3,original")  # time runs backwards after it
    (run / "exits.csv").write_text("\n".join(exits) + "\n")
    with pytest.raises(siloscope.SiloscopeError, match="backwards") as e:
        siloscope.read_run(str(run))
    one_line(e)
    camp = tmp_path / "camp"
    shutil.copytree(os.path.join(root, "docs/campaigns/kicks/analysis"), camp)
    rows = (camp / "points.csv").read_text().splitlines()
    cells = rows[1].split(",")
    header = rows[0].split(",")
    cells[header.index("n_runs")] = "-3"
    rows[1] = ",".join(cells)
    (camp / "points.csv").write_text("\n".join(rows) + "\n")
    with pytest.raises(siloscope.SiloscopeError, match="n_runs = -3") as e:
        siloscope.read_campaign(str(camp))
    assert "points.csv:2" in one_line(e)
    with pytest.raises(siloscope.SiloscopeError, match="no points.csv"):
        siloscope.read_campaign(str(tmp_path))
    with pytest.raises(siloscope.SiloscopeError, match="not a siloscope trajectory"):
        (tmp_path / "t.sstraj").write_bytes(b"NOTATRAJ" + bytes(100))
        siloscope.read_trajectory(str(tmp_path / "t.sstraj"))


def test_corrupt_trajectory_frames_are_refused_by_python_and_by_inspect(recording, binary, tmp_path):
    """The same corrupted files to both readers: time running backwards, a grain 1e30 m away, a NaN speed, a
    negative exit count. The Python reader raises naming the file and frame, `siloscope inspect` exits 2."""
    import shutil
    import subprocess
    import numpy as np
    src = os.path.join(recording, "trajectory.sstraj")
    tr = siloscope.read_trajectory(src)
    assert len(tr) > 20
    cases = {"time": lambda m: m["t"].__setitem__(12, m["t"][3]),
             "x": lambda m: m["x"].__setitem__((15, 2), 1e30),
             "vy": lambda m: m["vy"].__setitem__((16, 5), np.nan),
             "exits": lambda m: m["exits"].__setitem__((17, 0), -2)}
    for name, corrupt in cases.items():
        path = tmp_path / f"{name}.sstraj"
        shutil.copy(src, path)
        m = np.memmap(path, dtype=tr.frames.dtype, mode="r+", offset=tr.header_bytes, shape=(len(tr),))
        corrupt(m)
        m.flush()
        del m
        with pytest.raises(siloscope.SiloscopeError, match=rf"{name}.sstraj: frame 1[2-7] is corrupted"):
            siloscope.read_trajectory(path)
        script = tmp_path / "print.txt"
        script.write_text("print\n")
        done = subprocess.run([binary, "inspect", str(path), "--script", str(script), "--quiet"],
                              capture_output=True, text=True)
        assert done.returncode == 2, (name, done.stderr)
        assert "is corrupted" in done.stderr


def test_campaign_values_out_of_range_are_refused(root, tmp_path):
    import shutil
    analysis = tmp_path / "analysis"
    shutil.copytree(os.path.join(root, "docs/campaigns/harmonic/analysis"), analysis)
    siloscope.read_campaign(analysis)  # as committed: accepted
    text = (analysis / "points.csv").read_text().split("\n")
    header = text[0].split(",")
    for column, value, allowed in (("q_tilde_per_s", "-3", ">= 0"), ("chi_eff", "1.5", "from 0 to 1"),
                                   ("q_per_s", "lots", ">= 0")):
        row = text[1].split(",")
        row[header.index(column)] = value
        (analysis / "points.csv").write_text("\n".join([text[0], ",".join(row)] + text[2:]))
        with pytest.raises(siloscope.SiloscopeError, match=rf"points.csv:2: {column} = .* {allowed}"):
            siloscope.read_campaign(analysis)
