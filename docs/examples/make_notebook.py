#!/usr/bin/env python3
"""Writes docs/examples/protocol.ipynb (no outputs: tests/python/test_notebook.py executes it, and
`jupyter nbconvert --execute --to markdown` renders it as docs/examples/protocol.md)."""
import os

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

cells = [
    new_markdown_cell(
        "# A protocol in a notebook\n\n"
        "The paper's hopper stepped in process: its random kicks switched on only while a clog has stood 0.5 s, "
        "the clog rule off, so a clog ends only when a kick breaks it. The simulation shows itself inline "
        "(drawn by the renderer `record` uses), and the exits are plotted against a run without kicks. One "
        "realization each (seed 11): an illustration, not a measurement."),
    new_code_cell(
        "import numpy as np\n"
        "import matplotlib.pyplot as plt\n"
        "import siloscope\n\n"
        "SECONDS = 12.0   # of discharge per protocol\n"
        "KICK = 5e-3      # N s: 100x the literal value (the literal kick breaks no clog)\n"
        "sim = siloscope.Simulation(\"paper\", seed=11, clog_timeout=0.0, kick_impulse_max=0.0)\n"
        "sim"),
    new_code_cell(
        "def discharge(s, feedback):\n"
        "    \"\"\"Step s to SECONDS; with feedback, kicks on while a clog has stood 0.5 s, off at the next exit.\"\"\"\n"
        "    kicking, kicked = False, 0.0\n"
        "    while s.time < SECONDS - 1e-9:\n"
        "        want = feedback and s.clog is not None and s.time - s.clog[\"start_s\"] >= 0.5\n"
        "        if want != kicking:\n"
        "            s.set(\"kick_impulse_max\", KICK if want else 0.0)\n"
        "            kicking = want\n"
        "        s.advance_to(min(SECONDS, s.time + 0.05))\n"
        "        kicked += 0.05 if kicking else 0.0\n"
        "    return s.exits[\"t_s\"].to_numpy(), kicked\n\n"
        "t_fb, kicked = discharge(sim, feedback=True)\n"
        "t_none, _ = discharge(siloscope.Simulation(\"paper\", seed=11, clog_timeout=0.0, kick_impulse_max=0.0),\n"
        "                      feedback=False)\n"
        "print(f\"kicks when clogged: {len(t_fb)} exits, kicking {kicked:.1f} of {SECONDS:.0f} s; \"\n"
        "      f\"no kicks: {len(t_none)} exits\")\n"
        "sim  # the hopper at the end, as record would draw it"),
    new_code_cell(
        "fig, ax = plt.subplots(figsize=(5.6, 3.4))\n"
        "for t, label, color in ((t_fb, \"kicks when clogged\", \"#d55e00\"), (t_none, \"no kicks\", \"#555555\")):\n"
        "    ax.step(np.r_[0.0, t, SECONDS], np.r_[0, np.arange(1, len(t) + 1), len(t)], where=\"post\",\n"
        "            color=color, label=f\"{label}: {len(t)} exits\")\n"
        "ax.set_xlabel(\"time since the outlet opened [s]\")\n"
        "ax.set_ylabel(\"grains out\")\n"
        "ax.legend(fontsize=8)\n"
        "ax.grid(alpha=0.3)"),
    new_code_cell(
        "frame = sim.render(640, 360, camera=\"outlet\", overlay=\"none\")  # an RGB array, for any analysis\n"
        "frame.shape, frame.dtype"),
]
nb = new_notebook(cells=cells, metadata={"kernelspec": {"name": "python3", "display_name": "Python 3",
                                                        "language": "python"}})
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "protocol.ipynb")
nbformat.write(nb, out)
print(out)
