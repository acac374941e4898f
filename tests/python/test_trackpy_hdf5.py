"""`siloscope import TRACKS.h5`: trackpy's HDF5 (pandas tables: one per frame, as trackpy's PandasHDFStore writes,
or one for the whole film) imports as its CSV does."""
import os
import subprocess
import tempfile

import pandas as pd


def test_trackpy_hdf5_imports_as_its_csv(binary, root, tmp_path):
    scene = os.path.join(root, "assets/scenes/paper.toml")
    subprocess.run([binary, "run", scene, "--seed", "3", "--duration", "6", "--trajectory-fps", "30", "--quiet",
                    "--out", str(tmp_path / "r")], check=True)
    subprocess.run([binary, "export", str(tmp_path / "r"), "--format", "csv", "--out", str(tmp_path / "t.csv")],
                   check=True)
    df = pd.read_csv(tmp_path / "t.csv")
    with pd.HDFStore(tmp_path / "frames.h5", mode="w") as store:  # a table per frame, frame_10 after frame_9
        for frame, part in df.groupby("frame"):
            store.put(f"df/frame_{frame}", part, format="table")
    df.to_hdf(tmp_path / "whole.h5", key="tracks", format="table")
    args = ["--geometry", scene, "--quiet"]
    subprocess.run([binary, "import", str(tmp_path / "t.csv"), *args, "--out", str(tmp_path / "csv")], check=True)
    exits = (tmp_path / "csv" / "exits.csv").read_text()
    assert len(exits.splitlines()) > 10
    for name in ("frames", "whole"):
        subprocess.run([binary, "import", str(tmp_path / f"{name}.h5"), *args, "--out", str(tmp_path / name)],
                       check=True)
        assert (tmp_path / name / "exits.csv").read_text() == exits, name
        assert (tmp_path / name / "clogs.csv").read_text() == (tmp_path / "csv" / "clogs.csv").read_text(), name
        assert 'imported_from = "' in (tmp_path / name / "metadata.toml").read_text()
    # A file that is no HDF5 is refused, naming it; nothing is written and no temporary CSV is left.
    (tmp_path / "bad.h5").write_text("frame,particle,x,y\n")
    before = set(os.listdir(tempfile.gettempdir()))
    r = subprocess.run([binary, "import", str(tmp_path / "bad.h5"), *args, "--out", str(tmp_path / "bad")],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert "bad.h5: not trackpy's HDF5" in r.stderr
    assert not (tmp_path / "bad").exists()
    left = set(os.listdir(tempfile.gettempdir())) - before
    assert not [f for f in left if f.startswith("siloscope-") and f.endswith("-tracks.csv")]

