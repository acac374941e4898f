#!/usr/bin/env bash
# The standing tables of docs/filming.md, made again on this machine (run it idle; about 8 minutes):
#   1. this build against the build before the overlay's free-space layout (or any OLD binary), in one run
#      (bench record --binary: the cases interleaved, medians of 3, 20 s of the default scene);
#   2. the draw stage with each overlay element, force chains, trails and notes, at 720p and 1080p;
#   3. docs/filming/reference.csv: this build's per-stage figures, which `bench record` compares every later
#      build with (a stage 1.5x slower is flagged).
# Usage: bash docs/filming/remake.sh OLD_BINARY
# (OLD_BINARY: e.g. a build of commit 7fc777e^, the one before the layout: git worktree add OLD 7fc777e^ &&
#  cmake -S OLD -B OLD/build -DBUILD_TESTING=OFF && cmake --build OLD/build --target siloscope, OLD any directory)
set -euo pipefail
cd "$(dirname "$0")/../.."
old=${1:?usage: bash docs/filming/remake.sh OLD_BINARY}
bin=build/siloscope
old_name=${OLD_NAME:-the build before the layout, 7fc777e^}
out=docs/filming
machine="$(nproc)-core $(uname -m) $(date -u +%Y-%m-%d)"
commit=$(git rev-parse --short HEAD)
# No reference while it is being made: the comparison below is against the old build.
$bin bench record --repeats 3 --binary "$old" --reference none --csv "$out/ab.csv" > "$out/ab.txt" || true
$bin bench record --elements --repeats 3 --csv "$out/elements.csv" > "$out/elements.txt"
# The tables name files as the repository holds them, never by this machine's paths.
sed -i -e "s|$PWD/||g" -e "s|$old|OLD ($old_name)|g" "$out/ab.txt" "$out/elements.txt"
# The reference: this build's medians per stage (and the wall ratios) from the A/B run.
python3 - "$out/ab.csv" "$out/reference.csv" "$machine" "$commit" <<'PY'
import csv, statistics, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["binary"] == "this"]
out = ["case,stage,ms_per_frame,machine,commit"]
for case in ("record_720p30", "record_1080p30", "png_1080p"):
    mine = [r for r in rows if r["case"] == case]
    for stage in ("sim", "draw", "readback", "convert", "encode", "png"):
        v = statistics.median(float(r["ms_" + stage]) for r in mine)
        if v > 0:
            out.append(f"{case},{stage},{v:.3g},{sys.argv[3]},{sys.argv[4]}")
    if case != "png_1080p":
        v = statistics.median(float(r["ratio_to_run"]) for r in mine)
        out.append(f"{case},wall_ratio,{v:.3g},{sys.argv[3]},{sys.argv[4]}")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
PY
echo "made $out/ab.txt, $out/elements.txt and $out/reference.csv ($machine, $commit)"
