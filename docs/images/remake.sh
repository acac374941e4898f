#!/usr/bin/env bash
# The README's movie frames made again, each by the command the README prints under it (run from the
# repository's top, after the build): bash docs/images/remake.sh
# Each recording goes to recordings/readme/ (replaced with --force: siloscope's own outputs only) and the
# frame the README shows is copied over docs/images/NAME.png. About 4 minutes on 2 cores.
set -euo pipefail
S=build/siloscope
R=recordings/readme
mkdir -p "$R"
frame() {  # NAME DIR FRAME: copy DIR's frame FRAME to docs/images/NAME.png
  cp "$R/$2/frames/frame_$(printf %06d "$3").png" "docs/images/$1.png"
  echo "docs/images/$1.png <- $R/$2 frame $3"
}

# The main job's movie 3.8 s into its second clog, a three-disk arch (from 7.104 s; frame 330 is t = 10.89 s).
$S record assets/scenes/paper.toml --duration 11 --no-movie --png-every 330 --quiet --force --out $R/demo
frame demo_frame demo 330
# The demo run's second clog at four times, and its discharge as a figure (both from the recording above).
$S filmstrip $R/demo --clog 2 --times=-1,-0.5,0,2 --force --out docs/images/filmstrip.png
$S timeline $R/demo --force --out docs/images/timeline.png
$S record assets/scenes/paper.toml --duration 7.2 --slowmo 4 --overlay all+plot --size 1280x720 --no-movie \
  --png-every 250 --quiet --force --out $R/events
frame events_frame events 250
$S record assets/scenes/paper.toml --compare mu=0 --compare mu=2.2 --duration 15 --no-movie --png-every 450 \
  --quiet --force --out $R/compare
frame compare_frame compare 450
$S record assets/scenes/silo-obstacle.toml --duration 5.7 --size 1280x720 --no-movie --png-every 170 --quiet \
  --force --out $R/obstacle
frame scene_obstacle obstacle 170
$S record assets/scenes/pentagons.toml --duration 5.6 --size 1280x720 --no-movie --png-every 167 --quiet \
  --force --out $R/pentagons
frame scene_pentagons pentagons 167
$S record assets/scenes/vibrated-silo.toml --duration 3.1 --size 1280x720 --no-movie --png-every 91 --quiet \
  --force --out $R/vibrated
frame scene_vibrated vibrated 91
$S record assets/scenes/three-species.toml --duration 9.1 --size 1280x720 --no-movie --png-every 273 --quiet \
  --force --out $R/three
frame scene_three_species three 273
$S record assets/scenes/paper.toml --duration 8.5 --size 1280x720 --camera-path 0:hopper,5:arch:2 --no-movie \
  --png-every 240 --quiet --force --out $R/archcam
frame camera_arch archcam 240
$S record assets/scenes/paper.toml --duration 8 --size 1280x720 --no-movie --png-every 240 --force-chains 1:10 \
  --quiet --force --out $R/chains
frame force_chains chains 240
$S record assets/scenes/paper-vibrated.toml --duration 4 --set aperture=0.45 --size 1280x720 --no-movie \
  --png-every 60 --track 3,40,77,150,222,180,199 --trail 2 --quiet --force --out $R/tracked
frame tracked_grains tracked 120
$S record assets/scenes/paper.toml --duration 8 --size 1280x720 --no-movie --png-every 240 \
  --color displacement --displacement-from 6 --colormap magma --quiet --force --out $R/displacement
frame displacement displacement 240
# The forces on an arrested arch (docs/arches.md): the paper's scene without kicks or the rule, at rest 5.91 s
# in; grains by stress, the arch's outside forces as arrows. frame never writes over a file: the old one goes.
$S run assets/scenes/paper.toml --set kick_impulse_max=0 --set clog_timeout=0 --duration 6 --trajectory-fps 30 \
  --quiet --force --out $R/forces 2>/dev/null
rm -f docs/images/arch_forces.png
$S frame $R/forces --at frame:179 --camera outlet --color stress --arch-forces on --size 1280x720 \
  --out docs/images/arch_forces.png
