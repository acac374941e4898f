#!/bin/bash
# Drive the live window under Xvfb (run through xvfb-run), in OUTDIR (snapshots land in the working directory):
# pause with space, measure its CPU while paused, snapshot twice (s s), step three frames (right x3), snapshot
# again, close with q. Prints "paused_cpu_fraction F", the snapshot names and the window's stderr.
# usage: xvfb-run -a bash tests/ui/ui_live.sh SILOSCOPE SCENE OUTDIR
set -u
bin=$1 scene=$2 out=$3
cd "$out" || exit 1
"$bin" live "$scene" --set settle_time=1 > stdout.txt 2> stderr.txt &
pid=$!
wid=$(timeout 60 xdotool search --sync --name "siloscope live" | head -n 1)
if [ -z "$wid" ]; then echo "no window"; kill "$pid"; exit 1; fi
xdotool windowfocus --sync "$wid" 2>/dev/null || true
sleep 3  # settle, the first frames and the font atlas
xdotool key space
sleep 1
ticks() { awk '{print $14 + $15}' "/proc/$pid/stat"; }
hz=$(getconf CLK_TCK)
t0=$(ticks); s0=$(date +%s.%N)
sleep 3
t1=$(ticks); s1=$(date +%s.%N)
awk -v a="$t0" -v b="$t1" -v hz="$hz" -v s0="$s0" -v s1="$s1" 'BEGIN { printf "paused_cpu_fraction %.4f\n", (b - a) / hz / (s1 - s0) }'
# Each snapshot is waited for (up to 20 s), not a fixed time: on a loaded machine a frame can take longer.
shots() { ls -1 live-t*.png 2>/dev/null | wc -l; }
wait_shots() { for _ in $(seq 100); do [ "$(shots)" -ge "$1" ] && return; sleep 0.2; done; }
xdotool key s
wait_shots 1
xdotool key s
wait_shots 2
xdotool key --delay 25 Right Right Right
sleep 1
xdotool key s
wait_shots 3
xdotool key q
for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
kill "$pid" 2>/dev/null
wait "$pid"
echo "exit $?"
ls -1 live-t*.png | sed 's/^/snapshot /'
cat stderr.txt
