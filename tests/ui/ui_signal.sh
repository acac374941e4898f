#!/bin/bash
# Ctrl-C (SIGINT) and SIGTERM sent to an idle inspector window: each closes it within 5 s with exit 130.
# Prints "SIGNAL exit CODE after SECONDS s" for each.
# usage: xvfb-run -a -s '-screen 0 1280x720x24' bash tests/ui/ui_signal.sh SILOSCOPE RECORDING OUTDIR
set -u
bin=$1 rec=$2 out=$3
mkdir -p "$out"
cd "$out" || exit 1
for sig in INT TERM; do
  "$bin" inspect "$rec" --size 640x480 > "stdout-$sig.txt" 2> "stderr-$sig.txt" &
  pid=$!
  wid=$(timeout 30 xdotool search --sync --name "siloscope inspect" | head -n 1)
  if [ -z "$wid" ]; then echo "no window"; kill -9 "$pid"; exit 1; fi
  sleep 1.5  # idle: the window sleeps in its event wait
  t0=$(date +%s.%N)
  kill "-$sig" "$pid"
  for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  if kill -0 "$pid" 2>/dev/null; then
    echo "$sig: still running after 5 s"
    kill -9 "$pid"
  fi
  wait "$pid"
  code=$?
  echo "$sig exit $code after $(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }') s"
done
