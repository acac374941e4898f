"""siloscope share in a real browser (issue 58): Debian's chromium, headless, driven by selenium, opens the page
with the network shut off, plays, scrubs, jumps to clogs and clicks grains; the arch is found by its pixels on a
clogged frame and not on a flowing one, a clicked grain's id and position are the trajectory's, and the page
asked for nothing but itself. For a paper recording, a pentagon run and an imported lab run, and the embedded
fragment twice on one host page."""
import io
import os
import subprocess
import sys
import time

import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "src", "python"))
import siloscope  # noqa: E402

webdriver = pytest.importorskip("selenium.webdriver", reason="python3-selenium is not installed (.ci/test installs it)")
from selenium.webdriver.common.action_chains import ActionChains  # noqa: E402
from selenium.webdriver.common.keys import Keys  # noqa: E402

CHROMIUM, DRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
ARCH_GOLD = np.array([255, 194, 0])  # render::arch_color of the paper palette


@pytest.fixture(scope="module")
def binary():
    path = os.environ.get("SILOSCOPE_BINARY", os.path.join(ROOT, "build", "siloscope"))
    if not os.access(path, os.X_OK):
        pytest.fail(f"no siloscope binary at {path}: build first (bash .ci/bootstrap)")
    return path


def sh(*args):
    r = subprocess.run([str(a) for a in args], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    return r.stdout


@pytest.fixture(scope="module")
def browser():
    if not (os.access(CHROMIUM, os.X_OK) and os.access(DRIVER, os.X_OK)):
        pytest.fail("chromium and chromium-driver are not installed (.ci/test installs them)")
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    o = Options()
    o.binary_location = CHROMIUM
    # The network shut off: no name resolves and every connection goes to a closed port.
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1280,800",
              "--host-resolver-rules=MAP * ~NOTFOUND", "--proxy-server=127.0.0.1:9", "--no-first-run",
              "--disable-background-networking", "--disable-component-update", "--force-device-scale-factor=1"):
        o.add_argument(a)
    o.set_capability("goog:loggingPrefs", {"performance": "ALL", "browser": "ALL"})
    d = webdriver.Chrome(service=Service(DRIVER), options=o)
    d.set_page_load_timeout(60)
    yield d
    d.quit()


def open_page(d, path, index=0):
    d.get_log("performance")  # forget earlier pages' requests
    d.get("file://" + str(path))
    deadline = time.time() + 60
    while time.time() < deadline:
        st = d.execute_script(
            "const v = (window.siloscopeViewers || [])[arguments[0]]; return v ? [v.ready, v.error] : null", index)
        if st and (st[0] or st[1]):
            assert st[1] is None, f"the viewer failed: {st[1]}"
            return
        time.sleep(0.05)
    pytest.fail(f"{path}: the viewer was not ready within 60 s")


def requests(d):
    """Every URL the page asked for (the Chrome DevTools protocol's log)."""
    import json
    urls = []
    for entry in d.get_log("performance"):
        m = json.loads(entry["message"])["message"]
        if m["method"] == "Network.requestWillBeSent":
            urls.append(m["params"]["request"]["url"])
    return urls


def js(d, expr, *args):
    return d.execute_script("const v = window.siloscopeViewers[arguments[0]]; return " + expr, 0, *args)


def canvas_pixels(d, index=0):
    """The viewer's canvas as the screen shows it (a screenshot cut to the canvas), RGB."""
    import matplotlib.image as mpimg
    png = d.get_screenshot_as_png()
    img = (mpimg.imread(io.BytesIO(png), format="png")[:, :, :3] * 255).round().astype(int)
    x, y, w, h = d.execute_script(
        "const b = window.siloscopeViewers[arguments[0]].canvas.getBoundingClientRect();"
        "return [b.left, b.top, b.width, b.height]", index)
    return img[int(y):int(y + h), int(x):int(x + w)]


def gold_pixels(img):
    return int((np.abs(img - ARCH_GOLD).max(axis=2) <= 12).sum())


def click_at(d, x, y):
    """A real click of the mouse at (x, y) CSS pixels of the viewport."""
    from selenium.webdriver.common.actions.action_builder import ActionBuilder
    a = ActionBuilder(d)
    a.pointer_action.move_to_location(int(round(x)), int(round(y)))
    a.pointer_action.click()
    a.perform()


def press(d, keys):
    d.find_element("css selector", ".siloscope-share").send_keys(keys)


def check_run(d, page, traj_path, species_colors=None):
    """The checks every kind of run gets."""
    tr = siloscope.read_trajectory(str(traj_path))
    nf = len(tr.t)
    open_page(d, page)
    assert js(d, "v.frames") == nf
    # No request but the page itself.
    others = [u for u in requests(d) if u != "file://" + str(page)]
    assert others == [], f"the page asked for {others}"
    # Keys: n lands on a clog's start, a on its arch; the arch is drawn (gold pixels) exactly where the frame
    # carries one, and never on a flowing frame.
    clogged = [k for k in range(nf) if len(tr.arch(k)) > 0 and (tr.clog_open(k) or tr.arch_forming(k))]
    flowing = [k for k in range(nf) if len(tr.arch(k)) == 0]
    assert clogged and flowing
    js(d, "v.seek(0)")
    press(d, "n")
    k_clog = js(d, "v.frame")
    starts = np.asarray(tr.clogs["start_s"], dtype=float)
    first = starts[starts > float(tr.t[0]) + 0.5 * tr.frame_interval][0]
    assert abs(js(d, "v.time(v.frame)") - first) <= 0.5 * tr.frame_interval + 1e-6, (js(d, "v.time(v.frame)"), first)
    press(d, "a")
    k_arch = js(d, "v.frame")
    assert k_arch >= k_clog and k_arch in clogged, (k_clog, k_arch)
    assert js(d, "v.arch(v.frame)") == [int(i) for i in tr.arch(k_arch)]
    on_arch = gold_pixels(canvas_pixels(d))
    assert on_arch > 50, f"no arch drawn on frame {k_arch} (a clogged frame): {on_arch} gold pixels"
    js(d, "v.seek(arguments[1])", flowing[len(flowing) // 2])
    assert gold_pixels(canvas_pixels(d)) == 0, "an arch drawn on a flowing frame"
    # A click on a grain (an arch member of the clogged frame, in the outlet view) names it: the id, the
    # species and the position are the trajectory's, and the pixel clicked is its species' colour.
    js(d, "v.seek(arguments[1])", k_arch)
    member = int(tr.arch(k_arch)[0])
    X, Y, R = js(d, "v.grainOnPage(arguments[1], 'outlet')", member)
    assert R > 4, f"grain {member} is {R} pixels across in the outlet view"
    if species_colors is not None:  # eight points round the centre: most are its colour (bonds cross a few)
        img = canvas_pixels(d)
        cx, cy = d.execute_script("const b = window.siloscopeViewers[0].canvas.getBoundingClientRect(); return [b.left, b.top]")
        want = species_colors[int(tr.species[member])]
        seen = [img[int(round(Y + 0.6 * R * np.sin(a) - cy)), int(round(X + 0.6 * R * np.cos(a) - cx))]
                for a in np.arange(8) * np.pi / 4 + np.pi / 8]
        assert sum(np.abs(rgb - want).max() <= 12 for rgb in seen) >= 5, (seen, want)
    click_at(d, X, Y)
    assert js(d, "v.picked") == member
    text = js(d, "v.pickedText()")
    assert text.startswith(f"grain {member} ({tr.species_names[int(tr.species[member])]})"), text
    x, y = float(tr.x[k_arch, member]), float(tr.y[k_arch, member])
    shown = text.split("\n")[1].split()[-3:-1]
    assert abs(float(shown[0].rstrip(",")) - x) < 2e-4 and abs(float(shown[1]) - y) < 2e-4, (text, x, y)
    # Scrub: a click on the timeline's middle lands near the middle of the run.
    tl = d.find_element("css selector", ".ss-timeline")
    ActionChains(d).move_to_element(tl).click().perform()
    mid = js(d, "v.frame")
    assert abs(mid - nf / 2) <= 0.02 * nf + 2, mid
    # Play, then pause: frames advance.
    press(d, " ")
    time.sleep(0.6)
    press(d, " ")
    assert js(d, "v.frame") > mid and not js(d, "v.playing")
    # Colourings by key; the right arrow steps one frame.
    press(d, "k")
    assert js(d, "v.coloring") == "speed"
    seen = ["speed"]
    for _ in range(6):  # every colouring drawn once (a failure shows in the console check below)
        press(d, "k")
        seen.append(js(d, "v.coloring"))
    assert seen[:seen.index("species") + 1][-1] == "species" and {"displacement", "coordination", "id"} <= set(seen)
    before = js(d, "v.frame")
    press(d, Keys.ARROW_RIGHT)
    assert js(d, "v.frame") == before + 1
    assert not [e for e in d.get_log("browser") if e["level"] == "SEVERE"]
    others = [u for u in requests(d) if not u.startswith("file://")]
    assert others == [], f"the page asked for {others}"
    return tr


def test_paper_recording(binary, browser, tmp_path):
    rec = tmp_path / "paper"
    sh(binary, "record", os.path.join(ROOT, "assets/scenes/paper.toml"), "--duration", "8", "--seed", "3",
       "--size", "320x240", "--quiet", "--out", rec)
    page = tmp_path / "paper.html"
    out = sh(binary, "share", rec, "--out", page)
    assert "frames" in out and page.stat().st_size < 5e6
    check_run(browser, page, rec / "trajectory.sstraj", species_colors=[(217, 41, 36), (41, 97, 217)])
    # --force replaces the page siloscope wrote; a page a person wrote is never replaced.
    sh(binary, "share", rec, "--out", page, "--force", "--from", "2", "--to", "6", "--stride", "2")
    mine = tmp_path / "mine.html"
    mine.write_text("<html>my notes</html>")
    r = subprocess.run([binary, "share", rec, "--out", mine, "--force"], capture_output=True, text=True)
    assert r.returncode != 0 and mine.read_text() == "<html>my notes</html>"
    r = subprocess.run([binary, "share", rec, "--out", tmp_path / "x.html", "--stride", "0"], capture_output=True,
                       text=True)
    assert r.returncode == 2 and "--stride 0" in r.stderr and not (tmp_path / "x.html").exists()


def test_pentagons(binary, browser, tmp_path):
    run = tmp_path / "pent"
    sh(binary, "run", os.path.join(ROOT, "assets/scenes/pentagons.toml"), "--duration", "6", "--trajectory-fps", "30",
       "--quiet", "--out", run)
    page = tmp_path / "pent.html"
    sh(binary, "share", run, "--out", page)
    check_run(browser, page, run / "trajectory.sstraj")


def write_trackpy(traj, csv, scale=0.004, ox=400, oy=600):
    """A trajectory as a lab's tracker gives it (trackpy's columns, pixels, y down, a new id at each jump)."""
    tr = siloscope.read_trajectory(str(traj))
    ids = np.arange(tr.n)
    nxt = tr.n
    rows = []
    for k in range(len(tr.t)):
        if k:
            jumped = np.abs(tr.y[k] - tr.y[k - 1]) > 0.5
            for i in np.nonzero(jumped)[0]:
                ids[i] = nxt
                nxt += 1
        for i in range(tr.n):
            rows.append(f"{len(rows)},{oy - tr.y[k, i] / scale:.3f},{ox + tr.x[k, i] / scale:.3f},100,3,0.1,10,120,0.1,"
                        f"{k},{ids[i]},{2 * tr.radius[i] / scale:.3f}")
    csv.write_text(",y,x,mass,size,ecc,signal,raw_mass,ep,frame,particle,diameter\n" + "\n".join(rows) + "\n")


def test_imported_lab_run(binary, browser, tmp_path):
    scene = os.path.join(ROOT, "assets/scenes/paper.toml")
    sh(binary, "run", scene, "--seed", "3", "--duration", "8", "--trajectory-fps", "30", "--quiet", "--out",
       tmp_path / "r")
    write_trackpy(tmp_path / "r" / "trajectory.sstraj", tmp_path / "tracks.csv")
    sh(binary, "import", tmp_path / "tracks.csv", "--geometry", scene, "--scale", "0.004", "--origin", "400,600",
       "--fps", "30.303030303", "--out", tmp_path / "imp")
    page = tmp_path / "imp.html"
    sh(binary, "share", tmp_path / "imp", "--out", page)
    check_run(browser, page, tmp_path / "imp" / "trajectory.sstraj")


def test_embedded_twice(binary, browser, tmp_path):
    """The --embed fragment, pasted twice into a host page, gives two viewers each sized by its box."""
    run = tmp_path / "pent"
    sh(binary, "run", os.path.join(ROOT, "assets/scenes/pentagons.toml"), "--duration", "2", "--trajectory-fps", "30",
       "--quiet", "--out", run)
    frag = tmp_path / "frag.html"
    sh(binary, "share", run, "--out", frag, "--embed")
    text = frag.read_text()
    assert not text.lstrip().startswith("<!DOCTYPE")
    host = tmp_path / "host.html"
    host.write_text("<!DOCTYPE html><html><body><h1>slides</h1>"
                    f"<div style='width:640px;height:360px'>{text}</div>"
                    f"<div style='width:400px;height:300px'>{text}</div></body></html>")
    open_page(browser, host, 0)
    open_page(browser, host, 1)
    sizes = browser.execute_script(
        "return window.siloscopeViewers.map(v => { const b = v.root.getBoundingClientRect(); return [b.width, b.height]; })")
    assert sizes == [[640, 360], [400, 300]]
    browser.execute_script("window.siloscopeViewers[1].seek(10)")
    assert browser.execute_script("return window.siloscopeViewers.map(v => v.frame)") == [0, 10]


def test_notebook_player_page(binary, browser, tmp_path, monkeypatch):
    """Run.player() (what Jupyter shows) opens in the browser, as tall as asked."""
    monkeypatch.setenv("SILOSCOPE_BINARY", binary)
    run = tmp_path / "r"
    sh(binary, "run", os.path.join(ROOT, "assets/scenes/paper.toml"), "--duration", "2", "--trajectory-fps", "30",
       "--quiet", "--out", run)
    page = siloscope.read_run(str(run)).player(height=333).save(str(tmp_path / "player.html"))
    open_page(browser, page)
    assert browser.execute_script("return window.siloscopeViewers[0].root.getBoundingClientRect().height") == 333
    assert [u for u in requests(browser) if not u.startswith("file://")] == []
