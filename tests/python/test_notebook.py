"""docs/examples/protocol.ipynb runs top to bottom in a Jupyter kernel (Debian's nbclient and ipykernel) and shows
the simulation inline as a picture."""
import os

import nbclient
import nbformat


def test_the_protocol_notebook_executes_and_shows_the_simulation(root, tmp_path):
    nb = nbformat.read(os.path.join(root, "docs", "examples", "protocol.ipynb"), as_version=4)
    env_path = os.environ.get("PYTHONPATH", "")
    os.environ["PYTHONPATH"] = os.pathsep.join(p for p in (os.path.join(root, "src", "python"), env_path) if p)
    try:
        nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                                resources={"metadata": {"path": str(tmp_path)}}).execute()
    finally:
        os.environ["PYTHONPATH"] = env_path
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.output_type == "error"]
    pictures = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(pictures) >= 3  # the simulation at the start and the end, and the plot
    text = "".join(o.get("text", "") for o in outputs if o.output_type == "stream")
    assert "kicks when clogged:" in text and "no kicks:" in text
