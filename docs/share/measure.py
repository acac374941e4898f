#!/usr/bin/env python3
"""Size and speed of a shared run's page (siloscope share, issue 58), measured in Debian's chromium, headless.

    python3 docs/share/measure.py build/siloscope [--repeats 5] [--out docs/share]

Records the paper's scene for 60 s (30 frames/s), writes its page, then opens it `repeats` times in a fresh
headless chromium (network shut off) at 1280x720 and 1920x1080: the time from navigation to the first picture,
the time to inflate and decode the frames, and, while it plays for 5 s at 1x and 4x, the time each frame's
drawing takes in JavaScript and the interval between painted frames (the display's rate). Prints a table and
writes timing.csv (one row per window size: medians over the repeats; for the 99th percentile and the slowest
frame also the worst load's)."""
import argparse
import csv
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def chromium(width, height):
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    o = Options()
    o.binary_location = "/usr/bin/chromium"
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
              f"--window-size={width},{height}", "--host-resolver-rules=MAP * ~NOTFOUND", "--proxy-server=127.0.0.1:9",
              "--force-device-scale-factor=1"):
        o.add_argument(a)
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=o)


def once(page, width, height):
    d = chromium(width, height)
    try:
        d.get("file://" + page)
        while not d.execute_script("const v = (window.siloscopeViewers || [])[0]; return v && (v.ready || v.error)"):
            time.sleep(0.01)
        r = {"ready_ms": d.execute_script("return window.siloscopeViewers[0].sinceNavigationMs"),
             "decode_ms": d.execute_script("return window.siloscopeViewers[0].loadMs")}
        # Painted frames: requestAnimationFrame's timestamps while playing.
        for speed in ("1", "4"):
            d.execute_script("""
                const v = window.siloscopeViewers[0]; v.seek(0); v.drawTimes.length = 0;
                const ticks = window.__ticks = []; const tick = (t) => { if (window.__ticks === ticks) { ticks.push(t); requestAnimationFrame(tick); } };
                requestAnimationFrame(tick);
                v.root.querySelectorAll('select')[0].value = arguments[0];
                v.root.querySelectorAll('select')[0].dispatchEvent(new Event('change'));
                v.root.querySelectorAll('button')[2].click();""", speed)
            time.sleep(5)
            draws, ticks, frame = d.execute_script(
                "const v = window.siloscopeViewers[0]; v.root.querySelectorAll('button')[2].click();"
                "return [v.drawTimes.slice(), window.__ticks.slice(), v.frame]")
            gaps = [b - a for a, b in zip(ticks, ticks[1:])]
            r[f"draw_ms_median_{speed}x"] = statistics.median(draws)
            r[f"draw_ms_p99_{speed}x"] = sorted(draws)[int(0.99 * (len(draws) - 1))]
            r[f"draw_ms_max_{speed}x"] = max(draws)
            r[f"paint_interval_ms_median_{speed}x"] = statistics.median(gaps)
            r[f"frames_drawn_{speed}x"] = len(draws)
            r[f"frame_reached_{speed}x"] = frame
        return r
    finally:
        d.quit()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("binary")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "share"))
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="share-measure-")
    rec = os.path.join(tmp, "paper")
    subprocess.run([a.binary, "record", os.path.join(ROOT, "assets/scenes/paper.toml"), "--duration", "60", "--size",
                    "640x360", "--quiet", "--out", rec], check=True)
    page = os.path.join(tmp, "paper.html")
    subprocess.run([a.binary, "share", rec, "--out", page], check=True)
    size_mb = os.path.getsize(page) / 1e6
    rows = []
    for width, height in ((1280, 720), (1920, 1080)):
        runs = [once(page, width, height) for _ in range(a.repeats)]
        row = {"page": "paper 60 s, 30 frames/s", "size_MB": round(size_mb, 3), "window": f"{width}x{height}",
               "repeats": a.repeats}
        for key in runs[0]:
            values = [r[key] for r in runs]
            row[key] = round(statistics.median(values), 2)
            if "p99" in key or "max" in key:
                row[key + "_worst_load"] = round(max(values), 2)
        rows.append(row)
    keys = list(rows[0])
    with open(os.path.join(a.out, "timing.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    for k in keys:
        print(f"{k:32s}" + "".join(f"{str(r[k]):>26s}" for r in rows))
    print(f"(medians of {a.repeats} page loads each; _worst_load: the worst of them) -> {a.out}/timing.csv")


if __name__ == "__main__":
    sys.exit(main())
