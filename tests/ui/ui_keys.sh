#!/bin/bash
# Drive the inspector window under Xvfb (run through xvfb-run): measure its CPU while idle, tap the right arrow
# five times quickly, close it with q. Prints "idle_cpu_fraction F" and the inspector's stderr.
# usage: xvfb-run -a bash tests/ui/ui_keys.sh SILOSCOPE RECORDING OUTDIR
set -u
bin=$1 rec=$2 out=$3
"$bin" inspect "$rec" > "$out/stdout.txt" 2> "$out/stderr.txt" &
pid=$!
wid=$(timeout 30 xdotool search --sync --name "siloscope inspect" | head -n 1)
if [ -z "$wid" ]; then echo "no window"; kill "$pid"; exit 1; fi
xdotool windowfocus --sync "$wid" 2>/dev/null || true
sleep 2  # let the first frames and the font atlas settle
ticks() { awk '{print $14 + $15}' "/proc/$pid/stat"; }
hz=$(getconf CLK_TCK)
t0=$(ticks); s0=$(date +%s.%N)
sleep 4
t1=$(ticks); s1=$(date +%s.%N)
awk -v a="$t0" -v b="$t1" -v hz="$hz" -v s0="$s0" -v s1="$s1" 'BEGIN { printf "idle_cpu_fraction %.4f\n", (b - a) / hz / (s1 - s0) }'
xdotool key --delay 25 Right Right Right Right Right
sleep 1.5
xdotool key q
for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
kill "$pid" 2>/dev/null
wait "$pid"
echo "exit $?"
cat "$out/stderr.txt"
