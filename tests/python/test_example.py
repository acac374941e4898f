"""The notebook-style example in docs/examples runs on the committed campaign and draws its figure."""
import os
import subprocess
import sys


def test_avalanche_collapse_example_runs(root, tmp_path):
    out = tmp_path / "collapse.png"
    env = dict(os.environ, PYTHONPATH=os.path.join(root, "src", "python"))
    done = subprocess.run([sys.executable, os.path.join(root, "docs/examples/avalanche_collapse.py"),
                           os.path.join(root, "docs/campaigns/paper"), str(out)], env=env, capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr
    assert "pure, <s> =" in done.stdout and "r = 0.4" in done.stdout
    assert out.stat().st_size > 20000  # a figure, not an empty canvas


def test_kick_when_clogged_example_steps_the_simulation_in_process(root, tmp_path):
    out = tmp_path / "kicks.png"
    env = dict(os.environ, PYTHONPATH=os.path.join(root, "src", "python"))
    done = subprocess.run([sys.executable, os.path.join(root, "docs/examples/kick_when_clogged.py"), "6", str(out)],
                          env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert any(line.startswith("kicks always:") for line in lines)
    never = next(line for line in lines if line.startswith("kicks never:"))
    assert "kicking 0 of 6 s" in never
    assert out.stat().st_size > 20000
