#!/bin/bash
# Clicks as a person makes them, each followed by the window going idle: 12 on the panel's "next frame" button
# (">"), then 8 alternating between the "speed" and "species" colourings, at 1280x720 (text size 1). After
# each click and 0.6 s of quiet, FFmpeg's x11grab takes the screen as raw RGB (shot-NN.rgb, 1280x720x3 bytes):
# a click whose effect is not on screen then would show as two equal pictures of the scene. Prints the
# inspector's stderr, its exit code and the session it saved at the end.
# usage: xvfb-run -a -s '-screen 0 1280x720x24' bash tests/ui/ui_clicks.sh SILOSCOPE RECORDING OUTDIR
set -u
bin=$1 rec=$2 out=$3
mkdir -p "$out"
cd "$out" || exit 1
"$bin" inspect "$rec" --size 1280x720 > stdout.txt 2> stderr.txt &
pid=$!
wid=$(timeout 30 xdotool search --sync --name "siloscope inspect" | head -n 1)
if [ -z "$wid" ]; then echo "no window"; kill "$pid"; exit 1; fi
xdotool windowfocus --sync "$wid" 2>/dev/null || true
sleep 2
grab() {
  ffmpeg -nostdin -loglevel error -y -f x11grab -video_size 1280x720 -i "$DISPLAY" -frames:v 1 \
    -f rawvideo -pix_fmt rgb24 "$1"
}
grab shot-00.rgb
for k in $(seq 1 20); do
  if [ "$k" -le 12 ]; then
    xdotool mousemove 1049 76 click 1  # ">": the next frame
  elif [ $((k % 2)) = 1 ]; then
    xdotool mousemove 998 249 click 1  # "speed"
  else
    xdotool mousemove 898 249 click 1  # "species"
  fi
  sleep 0.6
  grab "shot-$(printf %02d "$k").rgb"
done
# A grain of the outlet view clicked, the key overlay opened and closed by a click beside it: the grain
# stays selected. The session saved (w) says so.
xdotool mousemove 438 262 click 1
sleep 0.4
xdotool key question
sleep 0.4
xdotool mousemove 60 300 click 1
sleep 0.4
xdotool key w
sleep 0.5
# A frame typed into the "go to" field and a quick Return (pressed and released between two frames).
xdotool mousemove 950 122 click 1
sleep 0.4
xdotool type --delay 30 30
xdotool key --delay 0 Return
sleep 0.5
xdotool key q
for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
kill "$pid" 2>/dev/null
wait "$pid"
echo "inspector exit $?"
cat stderr.txt
echo "--- session"
cat session-*.txt
