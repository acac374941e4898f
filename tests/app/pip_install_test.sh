#!/usr/bin/env bash
# pip installs the package with the binary and the in-process module into a fresh virtual environment, with
# Debian's build tools and no network (pip install --no-build-isolation --no-index), from a copy of the clone;
# from another directory the installed package steps a scene and its exits equal the installed command's run,
# byte for byte; a preset is named by name, a picture drawn in process, the type stubs are installed. The two
# targets come from the suite's own build (SILOSCOPE_BUILD_DIR): a plain `pip install ./`
# builds them itself (build-pip/), which the README's set-up was tried with by hand.
set -euo pipefail
build=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/clone"
(cd "$src" && git ls-files -z | xargs -0 cp --parents -t "$tmp/clone")  # the clone's files, no build trees
/usr/bin/python3 -m venv --system-site-packages "$tmp/env"
SILOSCOPE_BUILD_DIR="$build" "$tmp/env/bin/pip" install -q --no-build-isolation --no-index "$tmp/clone" \
  > "$tmp/pip.log" 2>&1 || { cat "$tmp/pip.log"; exit 1; }
cd "$tmp"
scene="$tmp/clone/assets/scenes/paper.toml"
env -u SILOSCOPE_BINARY "$tmp/env/bin/python3" -c "
import siloscope
assert siloscope.__file__.startswith('$tmp/env/'), siloscope.__file__
s = siloscope.Simulation('$scene', seed=7)
s.step(20000)
s.finish()
open('py-exits.csv', 'w').write(s.event_files()['exits.csv'])
# A preset by name, a picture in process, the type stubs installed beside the package.
import os
here = os.path.dirname(siloscope.__file__)
assert os.path.exists(os.path.join(here, '__init__.pyi')) and os.path.exists(os.path.join(here, 'py.typed'))
p = siloscope.Simulation('paper')
p.step(1000)
assert p.render(320, 180).shape == (180, 320, 3)
"
env -u SILOSCOPE_BINARY "$tmp/env/bin/siloscope" run paper --duration 1 --quiet --out preset
# A film read back: the picture and video readers are a module beside the package's binary (bin/lib/siloscope).
env -u SILOSCOPE_BINARY "$tmp/env/bin/siloscope" record paper --duration 0.3 --set settle_time=1 --size 640x360 \
  --camera window:-1,-0.2,1,0.9 --overlay none --arch-halo off --quiet --out film
env -u SILOSCOPE_BINARY "$tmp/env/bin/siloscope" detect film.mp4 --out film.csv > detect.log ||
  { cat detect.log; exit 1; }
[ "$(wc -l < film.csv)" -gt 100 ] || { echo "FAIL: detect found $(wc -l < film.csv) rows"; exit 1; }
env -u SILOSCOPE_BINARY "$tmp/env/bin/siloscope" run "$scene" --seed 7 --duration 20 --quiet --out run
cmp py-exits.csv run/exits.csv
echo "pip-installed siloscope: Simulation and the siloscope command agree ($(wc -l < run/exits.csv) lines)"

# Another Python than Debian's (pyenv's, a conda's), where one is installed: without the wheel package pip stops
# with siloscope's one line naming that Python and what to do, not setuptools' "invalid command 'bdist_wheel'".
for other in $(type -ap python3 python3.11 python3.12 python3.13 2>/dev/null | sort -u); do
  [ "$(readlink -f "$other")" = "$(readlink -f /usr/bin/python3)" ] && continue
  "$other" -c 'import venv' 2>/dev/null || continue
  "$other" -m venv "$tmp/other" 2>/dev/null || continue
  "$tmp/other/bin/python3" -c 'import wheel' 2>/dev/null && { rm -rf "$tmp/other"; continue; }
  status=0
  "$tmp/other/bin/pip" install -q --no-build-isolation --no-index "$tmp/clone" > "$tmp/other.log" 2>&1 || status=$?
  if [ "$status" -eq 0 ] || ! grep -q "siloscope: building a wheel needs the wheel package for $tmp/other/bin/python3" \
      "$tmp/other.log"; then
    cat "$tmp/other.log"
    echo "pip on $other: expected siloscope's message about the wheel package"
    exit 1
  fi
  echo "pip on another Python ($other): refused with siloscope's message"
  rm -rf "$tmp/other"
  break
done
