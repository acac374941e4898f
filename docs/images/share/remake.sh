#!/usr/bin/env bash
# The shared-run screenshots in docs/share.md made again (run from the repository's top, after the build):
#   bash docs/images/share/remake.sh
# The paper's scene recorded for 18 s, written as a page (siloscope share) and as a fragment (--embed) pasted
# twice into a host page; Debian's chromium, headless, opens them with the network shut off (shot.py): keys
# n n a (clog 2's arch where it forms), a click on an arch member, and the help list; the host page as is.
# Needs chromium, chromium-driver and python3-selenium (Debian packages).
set -euo pipefail
S=build/siloscope
R=recordings/readme/share
mkdir -p recordings/readme
$S record assets/scenes/paper.toml --duration 18 --size 640x360 --quiet --force --out $R
$S share $R --out recordings/readme/share.html --force
$S share $R --out recordings/readme/share-embed.html --embed --force
/usr/bin/python3 docs/images/share/shot.py recordings/readme/share.html recordings/readme/share-embed.html \
  docs/images/share
