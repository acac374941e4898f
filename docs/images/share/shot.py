#!/usr/bin/env python3
"""Screenshots of a shared run's page and of its fragment embedded twice (docs/images/share/remake.sh).

    python3 docs/images/share/shot.py PAGE.html FRAGMENT.html OUTDIR"""
import os
import sys
import tempfile
import time

from selenium import webdriver
from selenium.webdriver.chrome.options import Options
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.actions.action_builder import ActionBuilder


def browser(width, height):
    o = Options()
    o.binary_location = "/usr/bin/chromium"
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--hide-scrollbars",
              f"--window-size={width},{height}", "--host-resolver-rules=MAP * ~NOTFOUND", "--proxy-server=127.0.0.1:9",
              "--force-device-scale-factor=1"):
        o.add_argument(a)
    d = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=o)
    # The window's inside at the size asked (headless chromium counts no frame, but be sure).
    inner = d.execute_script("return [window.innerWidth, window.innerHeight]")
    d.set_window_size(2 * width - inner[0], 2 * height - inner[1])
    return d


def ready(d, count=1):
    for _ in range(600):
        if d.execute_script("return (window.siloscopeViewers || []).filter(v => v.ready).length") >= count:
            return
        time.sleep(0.05)
    raise SystemExit("the viewer was not ready within 30 s")


def save(d, path):
    d.save_screenshot(path + ".partial.png")
    os.replace(path + ".partial.png", path)
    print(path)


def main():
    page, fragment, out = sys.argv[1:4]
    d = browser(1280, 720)
    try:
        d.get("file://" + os.path.abspath(page))
        ready(d)
        root = d.find_element("css selector", ".siloscope-share")
        root.send_keys("nna")
        time.sleep(0.3)
        member = d.execute_script("const v = window.siloscopeViewers[0]; return v.arch(v.frame)[1]")
        x, y, _ = d.execute_script("return window.siloscopeViewers[0].grainOnPage(arguments[0], 'outlet')", member)
        a = ActionBuilder(d)
        a.pointer_action.move_to_location(int(x), int(y))
        a.pointer_action.click()
        a.perform()
        time.sleep(0.3)
        save(d, os.path.join(out, "viewer.png"))
        root.send_keys("?")
        time.sleep(0.3)
        save(d, os.path.join(out, "viewer-keys.png"))
        # The fragment twice on one page, as a slide deck would hold it.
        text = open(fragment).read()
        host = os.path.join(tempfile.mkdtemp(), "host.html")
        with open(host, "w") as f:
            f.write("<!DOCTYPE html><html><body style='font-family:DejaVu Sans,sans-serif;margin:16px'>"
                    "<h2 style='margin:0 0 8px'>A slide with two viewers</h2><div style='display:flex;gap:16px'>"
                    f"<div style='width:600px;height:560px;border:1px solid #ccc'>{text}</div>"
                    f"<div style='width:600px;height:560px;border:1px solid #ccc'>{text}</div></div></body></html>")
        d.get("file://" + host)
        ready(d, 2)
        d.execute_script("const [a, b] = window.siloscopeViewers; a.setView('outlet'); b.setView('hopper');"
                         "b.root.querySelectorAll('select')[1].value = 'speed';"
                         "b.root.querySelectorAll('select')[1].dispatchEvent(new Event('change'));"
                         "a.seek(a.frames / 3); b.seek(a.frames / 3);")
        time.sleep(0.3)
        save(d, os.path.join(out, "embedded.png"))
    finally:
        d.quit()


if __name__ == "__main__":
    main()
