"""A run in a notebook (issues 55 and 58): Run.player() holds `siloscope share --embed`'s viewer, Jupyter's HTML
representations name what they show, and a run without a trajectory is refused with the binary's message. The
viewer itself is driven in a real browser by tests/share/test_share_browser.py."""
import json
import re

import pytest

import siloscope


def test_player_holds_the_runs_viewer(recording, tmp_path):
    r = siloscope.read_run(str(recording))
    p = r.player(height=400, start=0.5, stop=2.5, stride=2)
    html = p._repr_html_()
    assert html.startswith('<div style="width:100%;height:400px">') and "<!-- siloscope share " in html
    header = json.loads(re.search(r'<script type="application/json" class="ss-header">(.*?)</script>', html,
                                  re.S).group(1))
    t = r.trajectory.t
    chosen = [k for k in range(len(t)) if 0.5 - 1e-9 <= t[k] <= 2.5 + 1e-9]
    assert header["frames"] == len(chosen[::2]) and header["n"] == r.trajectory.n
    assert [c["start"] for c in header["clogs"]] == pytest.approx(list(r.clogs["start_s"]))
    page = p.save(str(tmp_path / "p.html"))
    assert open(page).read().count('class="ss-header"') == 1
    assert "frames" in repr(r.trajectory) and "MB" in repr(p)
    assert "run.player()" in r._repr_html_()


def test_player_needs_a_trajectory(binary, tmp_path, root):
    siloscope.run(f"{root}/assets/scenes/paper.toml", str(tmp_path / "r"), duration=1, set={"settle_time": 1})
    with pytest.raises(siloscope.SiloscopeError, match="no trajectory.sstraj"):
        siloscope.read_run(str(tmp_path / "r")).player()



def test_player_refuses_a_bad_window(recording):
    with pytest.raises(siloscope.SiloscopeError, match="--stride 0"):
        siloscope.read_run(str(recording)).player(stride=0)
    with pytest.raises(siloscope.SiloscopeError, match="no frame of the recording lies in this window"):
        siloscope.read_run(str(recording)).player(start=50)
