"""pytest set-up: the package from this clone (src/python) and the binary the build made ($SILOSCOPE_BINARY,
set by ctest; else build/siloscope)."""
import os
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "src", "python"))


@pytest.fixture(scope="session")
def binary():
    path = os.environ.get("SILOSCOPE_BINARY", os.path.join(ROOT, "build", "siloscope"))
    if not os.access(path, os.X_OK):
        pytest.fail(f"no siloscope binary at {path}: build first (bash .ci/bootstrap)")
    os.environ["SILOSCOPE_BINARY"] = path
    return path


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def recording(binary, tmp_path_factory):
    """A 3 s recording of the paper's scene (with a trajectory), shared by the tests that read one."""
    out = tmp_path_factory.mktemp("rec") / "demo"
    subprocess.run([binary, "record", os.path.join(ROOT, "assets/scenes/paper.toml"), "--duration", "3", "--set",
                    "settle_time=2", "--size", "320x240", "--fps", "10", "--quiet", "--out", str(out)], check=True)
    return out
