"""Every reader refuses a damaged input, naming the file (issue 37): the same damaged files are given to the
binary's readers (analyze, export, inspect, gallery, timeline, claims, figures) and to the Python package
(read_run, read_trajectory, read_campaign), and each must fail, not read on. The damage: a file cut short, a
file edited after siloscope wrote it (the manifest tells), the manifest itself edited, a file copied in from
another run, the manifest removed (the directory's metadata.toml declares one), a non-finite value (in an output
without a manifest, as versions before manifests wrote, so that the value check itself is what refuses), and a
header promising more than the file holds or a file beyond any size siloscope writes."""
import os
import shutil
import subprocess

import pytest

import siloscope

PAPER = os.path.join(os.path.dirname(__file__), "..", "..", "assets", "scenes", "paper.toml")


def _run(binary, out, seed):
    subprocess.run([binary, "run", PAPER, "--duration", "4", "--set", "settle_time=2", "--seed", str(seed),
                    "--trajectory-fps", "5", "--quiet", "--out", str(out)], check=True)


@pytest.fixture(scope="module")
def made(binary, tmp_path_factory):
    d = tmp_path_factory.mktemp("readers")
    _run(binary, d / "runs" / "a", 1)
    _run(binary, d / "runs" / "b", 2)
    subprocess.run([binary, "analyze", str(d / "runs"), "--out", str(d / "analysis")], check=True,
                   capture_output=True)
    subprocess.run([binary, "analyze", str(d / "runs" / "b"), "--out", str(d / "analysis_b")], check=True,
                   capture_output=True)
    return d


def _flip_digit(path):
    """Changes one digit of the last line, keeping the size (only the hash can tell)."""
    data = bytearray(open(path, "rb").read())
    for i in range(len(data) - 2, 0, -1):
        if chr(data[i]).isdigit():
            data[i] = ord("1") if data[i] != ord("1") else ord("2")
            break
    open(path, "wb").write(bytes(data))


def _cut(path):
    data = open(path, "rb").read()
    open(path, "wb").write(data[: len(data) - 7])


def _edit_manifest(path):
    m = os.path.join(os.path.dirname(path), "manifest.toml")
    text = open(m).read()
    name = os.path.basename(path)
    at = text.index(f'["{name}", ') + len(f'["{name}", ')
    open(m, "w").write(text[:at] + "1" + text[at:])  # its size grows a digit


DECLARATION = 'manifest = "manifest.toml"\n'


def _strip_manifest(directory):
    """Makes `directory` an output as written before manifests: no manifest, none declared."""
    os.remove(os.path.join(directory, "manifest.toml"))
    meta = os.path.join(directory, "metadata.toml")
    text = open(meta).read()
    assert DECLARATION in text, "siloscope declares the manifest it writes"
    open(meta, "w").write(text.replace(DECLARATION, "", 1))


def _remove_manifest(path):
    os.remove(os.path.join(os.path.dirname(path), "manifest.toml"))


def _non_finite(path):
    _strip_manifest(os.path.dirname(path))
    lines = open(path).read().splitlines(keepends=True)
    header = lines[0].rstrip("\n").split(",")
    # The first column of a data row that must be a finite number: time in an events file, Q in a table.
    col = header.index("q_per_s") if "q_per_s" in header else 0
    row = lines[1].rstrip("\n").split(",")
    row[col] = "inf"
    lines[1] = ",".join(row) + "\n"
    open(path, "w").write("".join(lines))


def _oversized(path):
    if path.endswith(".sstraj"):
        _strip_manifest(os.path.dirname(path))
        data = bytearray(open(path, "rb").read())
        data[16:20] = (1 << 30).to_bytes(4, "little")  # a header promising 2^30 grains
        open(path, "wb").write(bytes(data))
    else:
        with open(path, "r+b") as f:  # sparse: no disk is used
            f.truncate(3 << 30)


DAMAGE = {"cut": _cut, "edited": _flip_digit, "manifest edited": _edit_manifest,
          "manifest removed": _remove_manifest, "non-finite": _non_finite, "oversized": _oversized}

# (reader, the file it is given damaged, how the binary or the package reads it)
RUN_READERS = [
    ("analyze", "exits.csv", lambda b, r, t: [b, "analyze", r, "--out", t + "/out"]),
    ("export", "trajectory.sstraj", lambda b, r, t: [b, "export", r, "--format", "csv", "--out", t + "/x.csv"]),
    ("inspect", "trajectory.sstraj", lambda b, r, t: [b, "inspect", r, "--script", t + "/s.txt"]),
    ("gallery", "metadata.toml", lambda b, r, t: [b, "gallery", r, "--out", t + "/g.png"]),
    ("timeline", "exits.csv", lambda b, r, t: [b, "timeline", r, "--out", t + "/t.png"]),
    ("read_run", "exits.csv", lambda r: siloscope.read_run(r)),
    ("read_trajectory", "trajectory.sstraj", lambda r: siloscope.read_trajectory(r)),
]
ANALYSIS_READERS = [
    ("claims", "points.csv", lambda b, a, t: [b, "claims", "x=" + a, "--out", t + "/c.md"]),
    ("figures", "points.csv", lambda b, a, t: [b, "figures", a, "--out", t + "/f"]),
    ("read_campaign", "points.csv", lambda a: siloscope.read_campaign(a)),
]


def _expect_refusal(reader, how, target, tmp_path, damaged_file, binary, without_manifest=False):
    (tmp_path / "s.txt").write_text("goto frame 0\n")
    if reader.startswith("read_"):
        with pytest.raises(siloscope.SiloscopeError) as e:
            how(target)
        message = str(e.value)
    else:
        p = subprocess.run(how(binary, target, str(tmp_path)), capture_output=True, text=True, timeout=120)
        assert p.returncode != 0, f"{reader} read a damaged {damaged_file} and exited 0:\n{p.stdout}"
        message = p.stderr
    if without_manifest:  # the check of the value itself refused, naming the file
        assert damaged_file in message and "manifest" not in message, f"{reader}: {message}"
    else:
        assert damaged_file in message or "manifest.toml" in message, f"{reader}: {message}"


@pytest.mark.parametrize("damage", DAMAGE)
@pytest.mark.parametrize("reader,file,how", RUN_READERS, ids=[r[0] for r in RUN_READERS])
def test_a_run_reader_refuses_a_damaged_file_naming_it(made, tmp_path, binary, reader, file, how, damage):
    if damage == "non-finite" and file.endswith((".sstraj", ".toml")):
        pytest.skip("non-finite values in trajectories and metadata: test_trajectory.cpp and test_package.py")
    if damage == "oversized" and file.endswith(".toml"):
        pytest.skip("an oversized metadata file: test_trust.cpp (1 MiB bound)")
    run = tmp_path / "run"
    shutil.copytree(made / "runs" / "a", run)
    DAMAGE[damage](str(run / file))
    _expect_refusal(reader, how, str(run), tmp_path, file, binary, not (run / "manifest.toml").exists()
                    and damage != "manifest removed")


@pytest.mark.parametrize("reader,file,how", RUN_READERS, ids=[r[0] for r in RUN_READERS])
def test_a_run_reader_refuses_a_file_of_another_run(made, tmp_path, binary, reader, file, how):
    run = tmp_path / "run"
    shutil.copytree(made / "runs" / "a", run)
    shutil.copyfile(made / "runs" / "b" / file, run / file)
    _expect_refusal(reader, how, str(run), tmp_path, file, binary)


@pytest.mark.parametrize("damage", DAMAGE)
@pytest.mark.parametrize("reader,file,how", ANALYSIS_READERS, ids=[r[0] for r in ANALYSIS_READERS])
def test_an_analysis_reader_refuses_a_damaged_table_naming_it(made, tmp_path, binary, reader, file, how, damage):
    analysis = tmp_path / "analysis"
    shutil.copytree(made / "analysis", analysis)
    DAMAGE[damage](str(analysis / file))
    _expect_refusal(reader, how, str(analysis), tmp_path, file, binary,
                    not (analysis / "manifest.toml").exists() and damage != "manifest removed")


@pytest.mark.parametrize("reader,file,how", ANALYSIS_READERS, ids=[r[0] for r in ANALYSIS_READERS])
def test_an_analysis_reader_refuses_a_table_of_another_analysis(made, tmp_path, binary, reader, file, how):
    analysis = tmp_path / "analysis"
    shutil.copytree(made / "analysis", analysis)
    shutil.copyfile(made / "analysis_b" / file, analysis / file)
    _expect_refusal(reader, how, str(analysis), tmp_path, file, binary)


def test_the_undamaged_inputs_are_read(made, binary, tmp_path):
    """The control: every reader above reads the same files undamaged."""
    run, analysis = str(made / "runs" / "a"), str(made / "analysis")
    for reader, _, _ in RUN_READERS + ANALYSIS_READERS:
        (tmp_path / reader).mkdir()
        (tmp_path / reader / "s.txt").write_text("goto frame 0\n")
    for reader, _, how in RUN_READERS:
        if reader == "gallery":
            continue  # re-simulates the run (minutes); its refusals are what this file tests
        if reader.startswith("read_"):
            how(run)
        else:
            p = subprocess.run(how(binary, run, str(tmp_path / reader)), capture_output=True, text=True)
            assert p.returncode == 0, f"{reader}: {p.stderr}"
    for reader, _, how in ANALYSIS_READERS:
        if reader.startswith("read_"):
            how(analysis)
        else:
            p = subprocess.run(how(binary, analysis, str(tmp_path / reader)), capture_output=True, text=True)
            assert p.returncode == 0, f"{reader}: {p.stderr}"


@pytest.mark.parametrize("reader,file,how", ANALYSIS_READERS, ids=[r[0] for r in ANALYSIS_READERS])
def test_an_analysis_reader_refuses_a_points_table_cut_at_a_line_end(root, tmp_path, binary, reader, file, how):
    """A committed pack (no manifest, as before manifests) whose points.csv lost its last row whole: the table
    keeps its form, and only the count analyze wrote into metadata.toml tells."""
    analysis = tmp_path / "analysis"
    shutil.copytree(os.path.join(root, "docs", "campaigns", "kicks", "analysis"), analysis)
    assert not (analysis / "manifest.toml").exists()
    rows = (analysis / "points.csv").read_text().splitlines(keepends=True)
    (analysis / "points.csv").write_text("".join(rows[:-1]))
    _expect_refusal(reader, how, str(analysis), tmp_path, file, binary, without_manifest=True)
