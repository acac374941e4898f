#!/usr/bin/env python3
"""siloscope's `detect` against two detectors a lab would try first, on the same frames with the truth known.

Records the paper's hopper at 1280x720 without an overlay (the camera of `bench roundtrip`), runs `siloscope
detect` on the movie, then OpenCV's HoughCircles and scikit-image's blob_log on the same decoded frames. Each is
scored against the recording's trajectory: recall (whole disks in the picture found within half their radius),
precision (detections that are such disks), the median position error in original diameters, and frames per
second. HoughCircles' and blob_log's main thresholds are chosen on the first tenth of the frames (the best F1 of a
small grid) and measured on the rest (blob_log, at seconds a frame, on every fourth); siloscope runs with its
defaults.

    python3 docs/lab/detectors.py --binary build/siloscope --work WORKDIR [--duration 6] [--csv F]

Needs python3-opencv and python3-skimage (Debian). Prints a table; --csv writes it.
"""
import argparse
import csv
import os
import subprocess
import sys
import time
import tomllib

import cv2
import numpy as np
from skimage.feature import blob_log

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "src", "python"))
import siloscope  # noqa: E402


def run(cmd):
    subprocess.run(cmd, check=True)


def truth_frames(trajectory, times, scale, ox, oy, width, height):
    """Per movie frame: the pixel centres and radii of the disks whole inside the picture."""
    out = []
    r_px = np.asarray(trajectory.radius) / scale
    for t in times:
        k = int(np.argmin(np.abs(trajectory.t - t)))
        x = ox + np.asarray(trajectory.x[k]) / scale
        y = oy - np.asarray(trajectory.y[k]) / scale
        whole = (x - r_px >= 0) & (x + r_px <= width) & (y - r_px >= 0) & (y + r_px <= height)
        seen = (x + r_px > 0) & (x - r_px < width) & (y + r_px > 0) & (y - r_px < height)
        out.append((x[whole], y[whole], r_px[whole], x[seen], y[seen], r_px[seen]))
    return out


def score(truth, found, d_px):
    """Recall, precision and the matched errors (pixels) of one frame's detections (N x 2) against the truth:
    recall over the disks whole in the picture; a detection is false unless it lies within half a radius of a
    disk seen at all (one cut by the picture's edge is not a false detection)."""
    tx, ty, tr, sx, sy, sr = truth
    if len(found) == 0:
        return 0, len(tx), 0, []
    ds = np.hypot(sx[:, None] - found[None, :, 0], sy[:, None] - found[None, :, 1])
    n_false = int(np.sum(~np.any(ds <= 0.5 * sr[:, None], axis=0)))
    d = np.hypot(tx[:, None] - found[None, :, 0], ty[:, None] - found[None, :, 1])
    matched, errors, used = 0, [], set()
    for i in np.argsort(d.min(axis=1)):
        j = int(np.argmin(d[i]))
        if d[i, j] <= 0.5 * tr[i] and j not in used:
            used.add(j)
            matched += 1
            errors.append(d[i, j])
    # Precision's denominator: the matches to whole disks and the false detections (detections of cut disks
    # count neither way).
    return matched, len(tx), matched + n_false, errors


def hough(gray, r_min, r_max, param2):
    c = cv2.HoughCircles(cv2.medianBlur(gray, 3), cv2.HOUGH_GRADIENT, dp=1, minDist=0.9 * r_min, param1=100,
                         param2=param2, minRadius=int(r_min), maxRadius=int(np.ceil(r_max)))
    return np.zeros((0, 2)) if c is None else c[0, :, :2]


def log_blobs(gray, r_min, r_max, threshold):
    b = blob_log(255 - gray, min_sigma=r_min / np.sqrt(2), max_sigma=r_max / np.sqrt(2), num_sigma=8,
                 threshold=threshold, overlap=0.3)
    return np.zeros((0, 2)) if len(b) == 0 else b[:, [1, 0]]


def evaluate(frames, truths, detect, d_px):
    m = n_true = n_found = 0
    errors = []
    t0 = time.perf_counter()
    found = [detect(g) for g in frames]
    seconds = time.perf_counter() - t0
    for tr, f in zip(truths, found):
        a, b, c, e = score(tr, f, d_px)
        m, n_true, n_found = m + a, n_true + b, n_found + c
        errors += e
    recall = m / max(1, n_true)
    precision = m / max(1, n_found)
    return recall, precision, float(np.median(errors)) / d_px if errors else float("nan"), len(frames) / seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--binary", default="build/siloscope")
    ap.add_argument("--work", required=True)
    ap.add_argument("--duration", type=float, default=6.0)
    ap.add_argument("--csv")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    rec = os.path.join(a.work, "rec")
    run([a.binary, "record", os.path.join(HERE, "..", "..", "assets", "scenes", "paper.toml"), "--duration",
         str(a.duration), "--size", "1280x720", "--camera", "window:-1.4,-0.4,1.4,1.6", "--overlay", "none",
         "--arch-halo", "off", "--seed", "3", "--quiet", "--force", "--out", rec])
    movie = rec + ".mp4"
    det = os.path.join(a.work, "det.csv")
    run([a.binary, "detect", movie, "--out", det, "--force", "--quiet"])
    with open(os.path.join(a.work, "det.meta.toml"), "rb") as f:
        meta = tomllib.load(f)
    cal = meta["calibration"]
    scale, ox, oy = cal["scale_m_per_px"], cal["origin_x_px"], cal["origin_y_px"]
    facts = meta.get("facts", meta.get("run", {}))
    # The movie's frames, decoded once, grey.
    cap = cv2.VideoCapture(movie)
    frames = []
    while True:
        ok, bgr = cap.read()
        if not ok:
            break
        frames.append(cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY))
    height, width = frames[0].shape
    rows = np.genfromtxt(det, delimiter=",", names=True)
    n = len(frames)
    times = [float(rows["t"][rows["frame"] == k][0]) if np.any(rows["frame"] == k) else k / cal["fps"]
             for k in range(n)]
    run_dir = siloscope.read_run(rec)
    truths = truth_frames(run_dir.trajectory, times, scale, ox, oy, width, height)
    radii = sorted(set(np.round(np.asarray(run_dir.trajectory.radius) / scale, 6)))
    r_min, r_max = 0.75 * radii[0], 1.25 * radii[-1]
    d_px = 2 * radii[-1]
    tune = max(1, n // 10)
    results = []
    # siloscope: its own detections, its own clock (decoding and linking included).
    sil = [np.stack([rows["x"][rows["frame"] == k], rows["y"][rows["frame"] == k]], axis=1) for k in range(n)]
    m = n_true = n_found = 0
    errors = []
    for k in range(tune, n):
        x, y, z, e = score(truths[k], sil[k], d_px)  # detect writes pixels, as trackpy does
        m, n_true, n_found = m + x, n_true + y, n_found + z
        errors += e
    wall = None
    for key in ("wall_time_s",):
        for section in meta.values():
            if isinstance(section, dict) and key in section:
                wall = section[key]
    results.append(("siloscope detect", "defaults", m / n_true, m / max(1, n_found),
                    float(np.median(errors)) / d_px, n / wall if wall else float("nan")))
    for name, fn, grid in (("OpenCV HoughCircles", hough, (10, 15, 20, 25, 30)),
                           ("scikit-image blob_log", log_blobs, (0.02, 0.05, 0.1, 0.2))):
        best = max(grid, key=lambda p: (lambda r: 2 * r[0] * r[1] / max(1e-9, r[0] + r[1]))(
            evaluate(frames[:tune], truths[:tune], lambda g: fn(g, r_min, r_max, p), d_px)))
        every = 4 if fn is log_blobs else 1  # blob_log takes seconds a frame: every fourth
        r = evaluate(frames[tune::every], truths[tune::every], lambda g: fn(g, r_min, r_max, best), d_px)
        results.append((name, f"{'param2' if fn is hough else 'threshold'} = {best}", *r))
    base = results[0]
    header = ("detector", "tuned", "recall", "precision", "error median (d)", "frames/s", "frames/s vs siloscope")
    print(f"{n - tune} frames of {width}x{height} scored ({n} decoded; the first {tune} tuned the others' thresholds),"
          f" about {int(np.mean([len(t[0]) for t in truths]))} whole disks a frame")
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    table = []
    for r in results:
        row = (r[0], r[1], f"{r[2]:.4f}", f"{r[3]:.4f}", f"{r[4]:.4f}", f"{r[5]:.1f}", f"{r[5] / base[5]:.2f}")
        table.append(row)
        print("| " + " | ".join(row) + " |")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(header)
            w.writerows(table)


if __name__ == "__main__":
    main()
