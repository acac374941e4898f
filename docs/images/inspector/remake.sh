#!/usr/bin/env bash
# The inspector's screenshots in docs/inspector.md made again (run from the repository's top, after the build):
#   bash docs/images/inspector/remake.sh
# A run of the paper's scene (18 s, a trajectory at 30 frames/s) is opened in the window under Xvfb at 1280x720
# and 1920x1080; keys n n a (clog 2's final arch as it first stands), a click on grain 45, and ? for the key
# overlay; FFmpeg's x11grab takes the screen. Then "what if": grain 45 clicked, the what-if tab, "branch here",
# "remove grain 45", "continue 1 s" (w720-branch.png), and the same by a script as a snapshot
# (branch-snapshot.png) with the branch saved as a run. Needs xvfb, xdotool and ffmpeg (Debian packages).
set -euo pipefail
S=build/siloscope
R=recordings/readme/inspector
mkdir -p recordings/readme
$S run assets/scenes/paper.toml --duration 18 --trajectory-fps 30 --quiet --force --out $R
shot() {  # WIDTH HEIGHT NAME X Y: the window at WIDTHxHEIGHT, grain 45 (at pixel X,Y) clicked; then the keys
  local w=$1 h=$2 name=$3
  xvfb-run -a -s "-screen 0 ${w}x${h}x24" bash -s "$S" "$R" "$w" "$h" "$name" "$4" "$5" <<'INNER'
set -eu
S=$1 R=$2 w=$3 h=$4 name=$5 gx=$6 gy=$7
"$S" inspect "$R" --size "${w}x${h}" --quiet < /dev/null &
pid=$!
wid=$(timeout 60 xdotool search --sync --name "siloscope inspect" | head -n 1)
xdotool windowmove "$wid" 0 0 windowfocus --sync "$wid" 2>/dev/null || true
sleep 3
xdotool key --delay 300 n n a
sleep 1.5
xdotool mousemove "$gx" "$gy" click 1
sleep 1.5
grab() { ffmpeg -nostdin -loglevel error -y -f x11grab -video_size "${w}x${h}" -i "$DISPLAY" -frames:v 1 "$1"; }
grab "docs/images/inspector/${name}-grain.png.partial.png"
xdotool key question
sleep 1.5
grab "docs/images/inspector/${name}-keys.png.partial.png"
xdotool key Escape q
wait "$pid" || true
INNER
  mv "docs/images/inspector/${name}-grain.png.partial.png" "docs/images/inspector/${name}-grain.png"
  mv "docs/images/inspector/${name}-keys.png.partial.png" "docs/images/inspector/${name}-keys.png"
  echo "docs/images/inspector/${name}-grain.png, ${name}-keys.png"
}
# Grain 45 (the arch's middle disk) where each window shows it (read off the pictures: the panel then names it).
shot 1280 720 w720 463 420
shot 1920 1080 w1080 694 630

# "What if" in the window at 1280x720: the buttons where the what-if tab puts them (read off the pictures). The
# branch re-simulates 7.3 s of the run before it shows (a few seconds): the clicks wait for it.
xvfb-run -a -s "-screen 0 1280x720x24" bash -s "$S" "$R" <<'INNER'
set -eu
S=$1 R=$2
"$S" inspect "$R" --size 1280x720 --quiet < /dev/null &
pid=$!
wid=$(timeout 60 xdotool search --sync --name "siloscope inspect" | head -n 1)
xdotool windowmove "$wid" 0 0 windowfocus --sync "$wid" 2>/dev/null || true
sleep 3
xdotool key --delay 300 n n a
for xy in "463 420" "1027 437" "929 490" "944 477" "1062 523"; do
  sleep 1.5
  xdotool mousemove $xy click 1
  [ "$xy" = "929 490" ] && sleep 8  # "branch here": the re-simulation
done
sleep 3
ffmpeg -nostdin -loglevel error -y -f x11grab -video_size 1280x720 -i "$DISPLAY" -frames:v 1 \
  docs/images/inspector/w720-branch.png.partial.png
xdotool key Escape q
wait "$pid" || true
INNER
mv docs/images/inspector/w720-branch.png.partial.png docs/images/inspector/w720-branch.png
# The same by a script, off-screen: the outlet, both panels at 1600x800, the branch saved as a run.
rm -rf recordings/readme/branch recordings/readme/branch-snapshot.png
cat > recordings/readme/branch.txt <<'SCRIPT'
goto frame 249
branch at 249
remove grain 45
continue 1
zoom outlet
snapshot recordings/readme/branch-snapshot.png 1600x800
save branch recordings/readme/branch
SCRIPT
$S inspect $R --quiet --script recordings/readme/branch.txt
cp recordings/readme/branch-snapshot.png docs/images/inspector/branch-snapshot.png
echo "docs/images/inspector/w720-branch.png, branch-snapshot.png; the branch: recordings/readme/branch"
