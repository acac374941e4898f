"""Every picture, file and window agrees with clogs.csv (issue 35): for each preset in assets/scenes/, with its
rule and with the rule off (clog_timeout = 0), record 20 s with a PNG of every frame, export XYZ and VTU, ask the
inspector for its clogs and frames, and check frame by frame:

  - the trajectory's clog state is clogs.csv's (a clog is open from start_s + clog_min_gap to end_s);
  - an arch is seen from its formation (issue 51): from formed_s (arch_formation.csv, and the trajectory's
    events) to the clog's end every frame that stores the arch shows its halo, and the frames before the clog is
    confirmed are marked as forming; the inspector's `goto clog K arch` lands within a frame of formed_s when
    the clog's final arch is the one that clogged it;
  - no arch is flagged (trajectory, XYZ, VTU, inspector) or highlighted (gold halo pixels in the movie's frame)
    in a frame outside every clog's [formed_s, end_s);
  - the XYZ and VTU arch flags and the inspector's arch are the trajectory's, frame for frame;
  - every frame of an open, arrested clog has an arch, and its halo is in the picture, unless the arch has
    parted (a kick: its neighbours apart in that frame; an arch is a chain of touching grains);
  - the inspector's clogs are clogs.csv's rows.

usage: events_agree.py SILOSCOPE SCENES_DIR WORK_DIR [--report CSV] [--raw] [PRESET...]
  Each run works in a fresh folder under WORK_DIR, removed when every check passed (kept to look at otherwise).
  --raw reads the trajectory's stored arch without the clog filter (to measure a version-1 recording made by an
  older siloscope) and reports instead of failing.
Prints a table per preset and variant; exits 1 when any check fails.
"""
import csv
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "src", "python"))
import siloscope  # noqa: E402

DURATION = 20.0
EDGE = 0.0015  # s: frames this close to a clog's opening or end are not judged (clogs.csv has 3 decimals)


def run(cmd, check=True):
    done = subprocess.run(cmd, capture_output=True, text=True)
    if check and done.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {done.returncode}\n{done.stderr}")
    return done


def gold_pixels(png):
    # 8-bit channels as the PNG holds them (PIL, which matplotlib reads through: a float copy of every frame
    # took a third of this test's time).
    with Image.open(png) as im:
        a = np.asarray(im.convert("RGB"))
    r, g, b = a[:, :, 0], a[:, :, 1], a[:, :, 2]
    return int(((r > 225) & (g > 165) & (g < 220) & (b < 70)).sum())


def chain_stands(tr, k, ids):
    """Whether the grains `ids` still touch in order at frame k, by their centres: at most their reaches apart
    (a disk's radius, a polygon's circumradius, generously) and 5% of the smaller radius."""
    for a, b in zip(ids, ids[1:]):
        ra, rb = (float(tr.radius[i]) * (1.7 if tr.sides[i] >= 3 else 1.0) for i in (a, b))
        gap = float(np.hypot(tr.x[k, a] - tr.x[k, b], tr.y[k, a] - tr.y[k, b])) - ra - rb
        if gap > 0.05 * min(float(tr.radius[a]), float(tr.radius[b])) + 1e-6:
            return False
    return True


def xyz_arch_flags(path):
    """Per frame, the set of ids flagged as arch members in an extended XYZ file."""
    frames = []
    with open(path) as f:
        while True:
            line = f.readline()
            if not line:
                break
            n = int(line)
            props = f.readline()
            cols = re.search(r"Properties=(\S+)", props).group(1).split(":")
            names = cols[0::3]
            widths = [int(w) for w in cols[2::3]]
            start = sum(widths[: names.index("arch")])
            idcol = sum(widths[: names.index("id")])
            ids = set()
            for _ in range(n):
                w = f.readline().split()
                if w[start] == "1":
                    ids.add(int(w[idcol]))
            frames.append(ids)
    return frames


def vtu_arch_flags(directory):
    out = []
    for path in sorted(glob.glob(os.path.join(directory, "grains_*.vtu"))):
        text = open(path).read()
        m = re.search(r'Name="arch"[^>]*>\s*([^<]*)<', text)
        vals = m.group(1).split()
        out.append({i for i, v in enumerate(vals) if v == "1"})
    return out


def inspector(binary, rec, frames):
    # The script lives beside the recording, not in it: a run directory holds only what siloscope wrote.
    script = rec + ".script"
    with open(script, "w") as f:
        f.write("clogs\n")
        for k in frames:
            f.write(f"goto frame {k}\nprint\n")
    done = run([binary, "inspect", rec, "--script", script, "--quiet"], check=False)
    if done.returncode != 0:
        return None, None, done.stderr.strip().splitlines()[-1] if done.stderr.strip() else "failed"
    clogs, arch = [], {}
    frame = None
    for line in done.stdout.splitlines():
        m = re.match(r"clog (\d+) (\S+) (\S+) (\S+) (\S+) frames", line)
        if m:
            clogs.append((float(m.group(2)), float(m.group(3)), m.group(4), m.group(5) == "arrested"))
        m = re.match(r"frame (\d+) .*arch \[([^\]]*)\]", line)
        if m:
            frame = int(m.group(1))
            arch[frame] = {int(v) for v in m.group(2).split()}
    return clogs, arch, None


def inspector_arch_frame(binary, rec, k):
    """The frame `goto clog K arch` lands on, or None when the inspector refuses."""
    script = rec + f".arch{k}.script"
    with open(script, "w") as f:
        f.write(f"goto clog {k} arch\nprint\n")
    done = run([binary, "inspect", rec, "--script", script, "--quiet"], check=False)
    m = re.search(r"^frame (\d+)", done.stdout, re.M)
    return int(m.group(1)) if done.returncode == 0 and m else None


def check(binary, scenes, work, preset, rule_off, raw):
    name = preset + ("-rule-off" if rule_off else "")
    rec = os.path.join(work, name)
    cmd = [binary, "record", os.path.join(scenes, preset + ".toml"), "--duration", str(DURATION), "--size",
           "320x240", "--camera", "outlet", "--overlay", "none", "--png-every", "1", "--no-movie", "--quiet",
           "--force", "--out", rec]
    if rule_off:
        cmd += ["--set", "clog_timeout=0"]
    run(cmd)
    fails = []
    row = {"preset": name}
    tr = siloscope.read_trajectory(rec)
    min_gap = tr.clog_min_gap
    with open(os.path.join(rec, "clogs.csv")) as f:
        clogs = [(float(r["start_s"]), float(r["end_s"]), r["ended_by"], r["arrested"] == "1")
                 for r in csv.DictReader(f)]
    # When each clog's arch formed (before its confirmation at start_s + clog_min_gap): the movie and the files
    # show it from then on.
    formed = {}
    with open(os.path.join(rec, "arch_formation.csv")) as f:
        for r in csv.DictReader(f):
            formed[int(r["clog"]) - 1] = float(r["formed_s"])
    if tr.clogs is not None and "formed_s" in tr.clogs:
        for i, v in enumerate(tr.clogs["formed_s"]):
            if i in formed and abs(float(v) - formed[i]) > 1e-6:
                fails.append(f"clog {i + 1}: the trajectory's formed_s {float(v)} is not arch_formation.csv's "
                             f"{formed[i]}")
    pngs = sorted(glob.glob(os.path.join(rec, "frames", "frame_*.png")))
    n = len(tr)
    if len(pngs) != n:
        fails.append(f"{len(pngs)} PNG frames for {n} trajectory frames")

    def stored_arch(k):
        if raw:
            f = tr.frames[k]
            ids = f["arch"][: max(0, min(int(f["arch_count"]), tr.max_arch))]
            return set(int(i) for i in ids) if len(ids) >= 2 else set()
        return set(int(i) for i in tr.arch(k))

    xyz_ok = run([binary, "export", rec, "--format", "xyz", "--force"], check=False)
    # ASCII, parsed here as text (the default binary export is read back by VTK in tests/python).
    vtu_ok = run([binary, "export", rec, "--format", "vtu", "--vtu-encoding", "ascii", "--force"], check=False)
    xyz = xyz_arch_flags(os.path.join(rec, "trajectory.xyz")) if xyz_ok.returncode == 0 else None
    vtu = vtu_arch_flags(os.path.join(rec, "vtu")) if vtu_ok.returncode == 0 else None
    if xyz is None:
        fails.append("export xyz: " + xyz_ok.stderr.strip())
    if vtu is None:
        fails.append("export vtu: " + vtu_ok.stderr.strip())
    every = list(range(0, n, 3))
    insp_clogs, insp_arch, insp_err = inspector(binary, rec, every)
    # The inspector's `goto clog K arch` lands on the final arch's first frame: on the formation frame (within
    # one frame of formed_s) when the final arch is the one that clogged.
    for i, t_formed in formed.items():
        landed = inspector_arch_frame(binary, rec, i + 1)
        at_formed = next((k for k in range(len(tr)) if float(tr.t[k]) >= t_formed - 1e-9), None)
        if landed is None or at_formed is None or stored_arch(at_formed) != stored_arch(landed):
            continue
        if abs(float(tr.t[landed]) - t_formed) > 1.5 * tr.frame_interval:
            fails.append(f"clog {i + 1}: goto clog arch lands at t = {float(tr.t[landed]):.3f} s, formed at "
                         f"{t_formed:.3f} s")
    if insp_err:
        fails.append("inspect: " + insp_err)
    elif len(insp_clogs) != len(clogs) or any(
            abs(a[0] - b[0]) > 1e-3 or abs(a[1] - b[1]) > 1e-3 or a[2] != b[2] or a[3] != b[3]
            for a, b in zip(insp_clogs, clogs)):
        fails.append(f"the inspector's {len(insp_clogs)} clogs are not clogs.csv's {len(clogs)} rows")

    counts = dict(frames=0, edge=0, open=0, flowing=0, flowing_flagged=0, flowing_halo=0, state_wrong=0,
                  forming=0, forming_no_halo=0, forming_not_marked=0,
                  arrested_open=0, arrested_parted=0, arrested_no_arch=0, arrested_no_halo=0, xyz_differs=0, vtu_differs=0,
                  inspector_differs=0)
    last_arch = None  # the last frame with an arch, and its members in order
    for k in range(n):
        t = float(tr.t[k])
        if any(abs(t - (s + min_gap)) < EDGE or abs(t - e) < EDGE for s, e, _, _ in clogs):
            counts["edge"] += 1
            continue
        counts["frames"] += 1
        hit = [c for c in clogs if c[0] + min_gap <= t < c[1]]
        is_open = bool(hit)
        forming = [i for i, c in enumerate(clogs) if i in formed and formed[i] <= t < c[0] + min_gap]
        arch = stored_arch(k)
        halo = gold_pixels(pngs[k]) if k < len(pngs) else 0
        if not raw and tr.clog_open(k) != is_open:
            counts["state_wrong"] += 1
        if xyz is not None and (k >= len(xyz) or xyz[k] != arch):
            counts["xyz_differs"] += 1
        if vtu is not None and (k >= len(vtu) or vtu[k] != arch):
            counts["vtu_differs"] += 1
        if insp_arch is not None and k in insp_arch and insp_arch[k] != arch:
            counts["inspector_differs"] += 1
        if arch and (forming or is_open):
            last_arch = (k, [int(i) for i in tr.arch(k)])  # a forming arch too: it may part at confirmation
        if forming and not is_open:
            counts["forming"] += 1
            counts["forming_no_halo"] += bool(arch) and halo == 0
            counts["forming_not_marked"] += bool(arch) and not raw and not tr.arch_forming(k)
            continue
        if not is_open:
            counts["flowing"] += 1
            counts["flowing_flagged"] += bool(arch) or (xyz is not None and k < len(xyz) and bool(xyz[k]))
            counts["flowing_halo"] += halo > 0
            continue
        counts["open"] += 1
        if hit[0][3]:
            counts["arrested_open"] += 1
            # A frame of an arrested clog without an arch is one where the arch has parted (a kick): its last
            # arch's neighbours are apart here. One still standing but not shown is a failure.
            if not arch:
                parted = last_arch is not None and hit[0][0] <= float(tr.t[last_arch[0]]) and \
                    not chain_stands(tr, k, last_arch[1])
                counts["arrested_parted"] += parted
                counts["arrested_no_arch"] += not parted
            else:
                counts["arrested_no_halo"] += halo == 0
    row.update(counts)
    row["clogs"] = len(clogs)
    for key in ("flowing_flagged", "flowing_halo", "state_wrong", "xyz_differs", "vtu_differs",
                "inspector_differs", "arrested_no_arch", "arrested_no_halo", "forming_no_halo", "forming_not_marked"):
        if counts[key]:
            fails.append(f"{key}: {counts[key]} frames")
    row["failures"] = "; ".join(fails)
    return row


def main(argv):
    binary, scenes, work = argv[1:4]
    rest = argv[4:]
    report = None
    raw = "--raw" in rest
    rest = [a for a in rest if a != "--raw"]
    if "--report" in rest:
        i = rest.index("--report")
        report = rest[i + 1]
        del rest[i:i + 2]
    presets = rest or sorted(os.path.splitext(os.path.basename(p))[0]
                             for p in glob.glob(os.path.join(scenes, "*.toml")))
    os.makedirs(work, exist_ok=True)
    work = tempfile.mkdtemp(prefix="agree-", dir=work)
    rows = []
    for preset in presets:
        for rule_off in (False, True):
            try:
                rows.append(check(binary, scenes, work, preset, rule_off, raw))
            except RuntimeError as e:
                rows.append({"preset": preset + ("-rule-off" if rule_off else ""), "failures": str(e)})
            r = rows[-1]
            print(f"{r['preset']:28s} clogs {r.get('clogs', '-'):>3} frames {r.get('frames', '-'):>4} "
                  f"(edge {r.get('edge', '-')}) flowing {r.get('flowing', '-'):>4} flagged "
                  f"{r.get('flowing_flagged', '-'):>3} halo {r.get('flowing_halo', '-'):>3} | arrested-open "
                  f"{r.get('arrested_open', '-'):>4} no-arch {r.get('arrested_no_arch', '-'):>3} no-halo "
                  f"{r.get('arrested_no_halo', '-'):>3} parted {r.get('arrested_parted', '-'):>3} | forming {r.get('forming', '-'):>3} | "
                  f"{r['failures'] or 'ok'}", flush=True)
    if report:
        keys = sorted({k for r in rows for k in r}, key=lambda k: (k != "preset", k == "failures", k))
        with open(report, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys)
            w.writeheader()
            w.writerows(rows)
    failed = [r for r in rows if r["failures"]]
    print(f"agreement: {len(rows) - len(failed)} of {len(rows)} recordings ok")
    if failed:
        print(f"the recordings are kept in {work}")
    else:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if failed and not raw else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
