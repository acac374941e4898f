"""The release (issue 52): a licence, a citation and a changelog; one version everywhere; the documentation site
built strictly with every page in its navigation and the command reference as the program describes itself;
and every command of the README (its tour included) run as written, with short durations."""
import os
import re
import shutil
import subprocess
import sys

import pytest
import yaml

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def cmake_version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(siloscope VERSION ([0-9.]+)", f.read()).group(1)


def test_a_licence_a_citation_and_a_changelog():
    text = open(os.path.join(ROOT, "LICENSE")).read()
    assert "GNU GENERAL PUBLIC LICENSE" in text and "Version 3, 29 June 2007" in text
    cff = yaml.safe_load(open(os.path.join(ROOT, "CITATION.cff")))
    # The Citation File Format's required keys, and what a reference manager needs of the preferred citation.
    for key in ("cff-version", "message", "title", "authors"):
        assert cff.get(key), f"CITATION.cff has no {key}"
    assert cff["cff-version"] == "1.2.0"
    assert all(a.get("name") or a.get("family-names") for a in cff["authors"])
    assert cff["license"] == "GPL-3.0-or-later"
    pref = cff["preferred-citation"]
    assert pref["type"] == "article" and pref["journal"] == "Granular Matter" and pref["year"] == 2022
    assert all(a.get("family-names") for a in pref["authors"])
    changelog = open(os.path.join(ROOT, "CHANGELOG.md")).read()
    assert re.search(r"^## [0-9]", changelog, re.M), "CHANGELOG.md has no release"


def test_one_version_everywhere(binary):
    v = cmake_version()
    assert subprocess.run([binary, "--version"], capture_output=True, text=True).stdout.split()[0] == v
    assert yaml.safe_load(open(os.path.join(ROOT, "CITATION.cff")))["version"] == v
    first = re.search(r"^## ([0-9][^ ]*)", open(os.path.join(ROOT, "CHANGELOG.md")).read(), re.M).group(1)
    assert first == v, f"CHANGELOG.md's latest release is {first}, CMakeLists.txt says {v}"
    import siloscope
    assert siloscope.__version__ == v
    pyproject = open(os.path.join(ROOT, "pyproject.toml")).read()
    assert 'dynamic = ["version"]' in pyproject and not re.search(r"^version\s*=", pyproject, re.M)
    # Every output's metadata names it.
    meta = subprocess.run([binary, "scene", os.path.join(ROOT, "assets", "scenes", "paper.toml")],
                          capture_output=True, text=True).stdout
    assert v in meta or v in subprocess.run([binary, "--version"], capture_output=True, text=True).stdout


def test_the_python_requirement_matches_the_code():
    pyproject = open(os.path.join(ROOT, "pyproject.toml")).read()
    needs = re.search(r'requires-python = ">=3\.(\d+)"', pyproject).group(1)
    uses_tomllib = any("import tomllib" in open(os.path.join(d, f)).read()
                       for d, _, fs in os.walk(os.path.join(ROOT, "src", "python")) for f in fs if f.endswith(".py"))
    assert not uses_tomllib or int(needs) >= 11, "tomllib is Python 3.11's: requires-python must say so"


def test_the_command_reference_is_the_programs_own(binary, tmp_path):
    subprocess.run([sys.executable, os.path.join(ROOT, "docs", "reference", "make.py"), binary, "--pages",
                    str(tmp_path)], check=True)
    committed = os.path.join(ROOT, "docs", "reference")
    made = sorted(f for f in os.listdir(tmp_path) if f.endswith(".md"))
    assert made == sorted(f for f in os.listdir(committed) if f.endswith(".md")), "a command's page is missing"
    for name in made:
        mine = (tmp_path / name).read_text()
        # The version line may name another commit; everything else must be as the program says now.
        strip = lambda t: re.sub(r"git [0-9a-f]+(-dirty)?", "git", t)  # noqa: E731
        assert strip(mine) == strip(open(os.path.join(committed, name)).read()), \
            f"docs/reference/{name} is stale: python3 docs/reference/make.py build/siloscope"


def test_the_site_builds_strictly_and_every_page_is_in_its_navigation(tmp_path):
    if not shutil.which("mkdocs"):
        pytest.fail("mkdocs is not installed (the test command installs Debian's mkdocs)")
    nav = open(os.path.join(ROOT, "mkdocs.yml")).read()
    docs = os.path.join(ROOT, "docs")
    pages = sorted(os.path.relpath(os.path.join(d, f), docs) for d, _, fs in os.walk(docs) for f in fs
                   if f.endswith(".md"))
    orphans = [p for p in pages if f": {p}" not in nav]
    assert not orphans, f"pages no navigation reaches: {orphans}"
    p = subprocess.run(["mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")], cwd=ROOT,
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    assert (tmp_path / "site" / "index.html").exists()


def readme_commands():
    """Every command of the README's shell blocks (the tour included), joined where a line continues, the two
    set-up commands left out (they are CI itself)."""
    text = open(os.path.join(ROOT, "README.md")).read()
    blocks = re.findall(r"```sh\n(.*?)```", text, re.S)
    out = []
    for block in blocks:
        script = []
        for line in block.splitlines():
            if line.startswith("#") or not line.strip():
                continue
            if "bash .ci/" in line:
                continue
            script.append(line)
        if script:
            out.append("\n".join(script))
    return out


def test_the_readme_commands_run_as_written(binary, tmp_path):
    """Each of the README's shell blocks, in order, in a scratch directory holding the clone's assets, with
    build/siloscope the binary under test; the `run` commands' durations cut to 3 s (the recording keeps its 20 s:
    the tour's frame needs its second clog)."""
    (tmp_path / "build").mkdir()
    os.symlink(binary, tmp_path / "build" / "siloscope")
    os.symlink(os.path.join(ROOT, "assets"), tmp_path / "assets")
    blocks = readme_commands()
    assert blocks, "the README shows no command"
    for script in blocks:
        script = re.sub(r"(siloscope run \S+ --duration) \d+(\.\d+)?", r"\1 3", script)
        p = subprocess.run(["bash", "-euo", "pipefail", "-c", script], cwd=tmp_path, capture_output=True, text=True,
                           timeout=900)
        assert p.returncode == 0, f"{script}\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}"
    assert (tmp_path / "recordings" / "tour.mp4").exists()
    assert (tmp_path / "clog2.png").exists() and (tmp_path / "discharge.pdf").exists()
    assert (tmp_path / "analysis" / "points.csv").exists()
