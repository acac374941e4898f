#!/bin/bash
# A session in the inspector window under Xvfb (run through xvfb-run -s '-screen 0 1280x720x24'), driven as a
# person would: clog navigation (n, n, a), the "force" colouring (a click on its radio button), a wheel zoom
# over the picture, a click on a grain, a snapshot (s), the session saved as a script (w), q. Then the saved
# script is replayed off-screen in another folder. Prints the saved script, "window FILE" and "replay FILE"
# for the two snapshots, and the exit codes.
# usage: xvfb-run -a -s '-screen 0 1280x720x24' bash tests/ui/ui_session.sh SILOSCOPE RECORDING OUTDIR
set -u
bin=$1 rec=$2 out=$3
mkdir -p "$out/window" "$out/replay"
cd "$out/window" || exit 1
"$bin" inspect "$rec" --size 1280x720 > stdout.txt 2> stderr.txt &
pid=$!
wid=$(timeout 30 xdotool search --sync --name "siloscope inspect" | head -n 1)
if [ -z "$wid" ]; then echo "no window"; kill "$pid"; exit 1; fi
xdotool windowfocus --sync "$wid" 2>/dev/null || true
sleep 2
xdotool key --delay 300 n n a
sleep 0.5
# The "force" radio button of the panel at 1280x720 (text size 1).
xdotool mousemove 1043 249 click 1
sleep 0.5
# Two wheel steps up over the outlet view, then a click on a grain of the outlet view.
xdotool mousemove 460 300 click 4 click 4
sleep 0.5
xdotool mousemove 470 330 click 1
sleep 0.5
xdotool mousemove 700 600
sleep 0.3
xdotool key s
sleep 3
xdotool key w
sleep 1
xdotool key q
for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
kill "$pid" 2>/dev/null
wait "$pid"
echo "window exit $?"
session=$(ls session-*.txt 2>/dev/null | head -n 1)
shot=$(ls snapshot-*.png 2>/dev/null | head -n 1)
echo "window-snapshot $out/window/$shot"
echo "--- $session"
cat "$session"
echo "---"
cd "$out/replay" || exit 1
"$bin" inspect "$rec" --script "$out/window/$session" --quiet
echo "replay exit $?"
echo "replay-snapshot $out/replay/$(ls snapshot-*.png 2>/dev/null | head -n 1)"
cat "$out/window/stderr.txt"
