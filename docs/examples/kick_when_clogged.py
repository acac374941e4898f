#!/usr/bin/env python3
"""Notebook-style example of a protocol the command line cannot run: the paper's hopper with its random kicks
switched on only while the outlet is clogged (a feedback on the clog siloscope detects), against kicks all the
time and no kicks at all. The clog rule is off (clog_timeout = 0), so a clog ends only when a kick breaks it.
Kicks 100x the literal value (5e-3 N*s): the literal kick breaks no clog (docs/campaigns/README.md).

    PYTHONPATH=src/python python3 docs/examples/kick_when_clogged.py [SECONDS [OUT.png]]

SECONDS of discharge per protocol (default 40), OUT defaults to docs/examples/kick_when_clogged.png. One
realization per protocol (seed 11): an illustration, not a measurement.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import siloscope  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 40.0
out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(here, "kick_when_clogged.png")
scene = os.path.join(here, "..", "..", "assets", "scenes", "paper.toml")
KICK = 5e-3  # N*s
CHUNK = 0.05  # s between decisions


def discharge(protocol):
    """Exits over time and the seconds spent kicking, for 'always', 'when clogged' or 'never'."""
    s = siloscope.Simulation(scene, seed=11, clog_timeout=0.0,
                             kick_impulse_max=KICK if protocol == "always" else 0.0)
    kicking = protocol == "always"
    kicked_s = 0.0
    while s.time < seconds - 1e-9:
        if protocol == "when clogged":
            # A clog that has stood 0.5 s (siloscope's clog: no exit for clog_min_gap) switches the kicks on;
            # the next exit switches them off.
            want = s.clog is not None and s.time - s.clog["start_s"] >= 0.5
            if want != kicking:
                s.set("kick_impulse_max", KICK if want else 0.0)
                kicking = want
        s.advance_to(min(seconds, s.time + CHUNK))
        kicked_s += CHUNK if kicking else 0.0
    return s.exits["t_s"].to_numpy(), kicked_s


fig, ax = plt.subplots(figsize=(5.6, 3.8))
for protocol, color in (("always", "#0072b2"), ("when clogged", "#d55e00"), ("never", "#555555")):
    t, kicked = discharge(protocol)
    label = f"kicks {protocol}: {len(t)} exits, kicking {kicked:.0f} of {seconds:.0f} s"
    print(label)
    ax.step(np.concatenate([[0.0], t, [seconds]]), np.concatenate([[0], np.arange(1, len(t) + 1), [len(t)]]),
            where="post", color=color, label=label)
ax.set_xlabel("time since the outlet opened [s]")
ax.set_ylabel("grains out")
ax.set_title("Kicks only while clogged (paper's hopper, one realization each)", fontsize=9)
ax.legend(fontsize=7, loc="upper left")
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(out, dpi=150)
print(f"figure {out}")
