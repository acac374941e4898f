"""Simulation.render: pictures in process, drawn by the renderer `record` and `frame` use (the information box
placed as frame places it)."""
import os
import subprocess

import matplotlib.image as mpimg
import numpy as np
import pytest

import siloscope


def test_render_equals_the_frame_command_pixel_for_pixel(binary, root, tmp_path):
    # The same scene and seed, the same instant: frame 60 of a 30 frames/s trajectory (t = 1.98 s).
    scene = os.path.join(root, "assets/scenes/paper.toml")
    subprocess.run([binary, "run", scene, "--seed", "3", "--duration", "2.5", "--trajectory-fps", "30", "--quiet",
                    "--out", str(tmp_path / "run")], check=True)
    s = siloscope.Simulation(scene, seed=3)
    s.advance_to(1.98)
    for camera, overlay in (("split", "none"), ("outlet", "none"), ("split", "all")):
        png = tmp_path / f"{camera}-{overlay}.png"
        subprocess.run([binary, "frame", str(tmp_path / "run"), "--at", "frame:60", "--size", "640x360",
                        "--camera", camera, "--overlay", overlay, "--out", str(png)], check=True,
                       capture_output=True)
        a = s.render(640, 360, camera=camera, overlay=overlay)
        b = (mpimg.imread(png)[:, :, :3] * 255).round().astype(np.uint8)
        assert a.shape == (360, 640, 3) and a.dtype == np.uint8
        assert np.array_equal(a, b), f"{camera}, overlay {overlay}: {(a != b).any(axis=2).sum()} pixels differ"
    # And record's own frame 60 (a 30 frames/s movie's PNG frames, no overlay: the movie's layout keeps none).
    subprocess.run([binary, "record", scene, "--seed", "3", "--duration", "2.5", "--size", "640x360", "--overlay",
                    "none", "--png-every", "1", "--no-movie", "--quiet", "--out", str(tmp_path / "movie")],
                   check=True)
    b = (mpimg.imread(tmp_path / "movie" / "frames" / "frame_000060.png")[:, :, :3] * 255).round().astype(np.uint8)
    a = s.render(640, 360, overlay="none")
    assert np.array_equal(a, b), f"record's frame 60: {(a != b).any(axis=2).sum()} pixels differ"


def test_render_options_and_refusals(root):
    s = siloscope.Simulation(os.path.join(root, "assets/scenes/paper.toml"), seed=3)
    s.advance_to(1.0)
    plain = s.render(320, 180, overlay="none")
    assert not np.array_equal(plain, s.render(320, 180))  # the overlay's boxes
    assert plain.mean() > s.render(320, 180, overlay="none", dark=True).mean()  # the dark background
    assert not np.array_equal(plain, s.render(320, 180, overlay="none", color="speed"))
    assert np.array_equal(plain, s.render(320, 180, overlay="none"))  # each picture stands alone
    assert s._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"
    for bad, says in ((dict(camera="sideways"), "sideways"), (dict(color="rainbow"), "rainbow"),
                      (dict(width=8), "16 to 8192"), (dict(width=2.5), "whole number")):
        with pytest.raises(siloscope.SiloscopeError, match=says):
            s.render(**bad)
    assert s.time == pytest.approx(1.0, abs=1e-9)  # pictures do not step


def test_no_arch_ring_in_the_legend_when_the_halo_is_off(binary, root, tmp_path):
    # Issue 57: --arch-halo off kept the legend's gold ring; now no pixel of the picture is the arch's gold.
    scene = os.path.join(root, "assets/scenes/paper.toml")
    subprocess.run([binary, "run", scene, "--seed", "3", "--duration", "2.5", "--trajectory-fps", "30", "--quiet",
                    "--out", str(tmp_path / "run")], check=True)
    gold = np.array([255, 194, 0])

    def gold_pixels(halo):
        png = tmp_path / f"halo-{halo}.png"
        subprocess.run([binary, "frame", str(tmp_path / "run"), "--at", "frame:60", "--size", "960x540",
                        "--arch-halo", halo, "--out", str(png)], check=True, capture_output=True)
        px = (mpimg.imread(png)[:, :, :3] * 255).round().astype(int)
        return int((np.abs(px - gold).max(axis=2) <= 12).sum())

    assert gold_pixels("on") > 500  # the halo on three disks, and the legend's ring
    assert gold_pixels("off") == 0
