#!/usr/bin/env bash
# The build tree installs (cmake --install) and the installed binary finds its scripts, Python package and
# scenes relative to itself, with the build tree out of reach: figures from a committed analysis, a gallery
# sheet of a fresh run, a shared page of a short recording (the installed viewer), and the package imported
# from the installed share/.
set -euo pipefail
build=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log"
bin="$tmp/prefix/bin/siloscope"
test -x "$bin"
cp -r "$src/docs/campaigns/kicks/analysis" "$tmp/analysis"
# Run from elsewhere, with the build tree renamed away for the duration: nothing may be found through it.
mv "$build/share" "$build/share.away"
trap 'mv "$build/share.away" "$build/share" 2>/dev/null || true; rm -rf "$tmp"' EXIT
cd "$tmp"
"$bin" figures analysis --out figs > figs.log
test -s figs/kicks.png
"$bin" run "$tmp/prefix/share/siloscope/scenes/paper.toml" --duration 7 --seed 4 --quiet --out run  # a rule at 5.4 s
"$bin" gallery run --out sheet.png > gallery.log || { cat gallery.log; exit 1; }
test -s sheet.png
"$bin" run "$tmp/prefix/share/siloscope/scenes/paper.toml" --duration 1 --trajectory-fps 10 --quiet --out rec
"$bin" share rec --out rec.html > share.log || { cat share.log; exit 1; }
grep -q "siloscope.share" rec.html
# A film read back (detect): the picture and video readers are a module the binary loads from PREFIX/lib/siloscope.
"$bin" record "$tmp/prefix/share/siloscope/scenes/paper.toml" --duration 0.3 --set settle_time=1 --size 640x360 \
  --camera window:-1,-0.2,1,0.9 --overlay none --arch-halo off --quiet --out film
"$bin" detect film.mp4 --out film.csv > detect.log || { cat detect.log; exit 1; }
[ "$(wc -l < film.csv)" -gt 100 ] || { echo "FAIL: detect found $(wc -l < film.csv) rows"; cat detect.log; exit 1; }
PYTHONPATH="$tmp/prefix/share/siloscope/python" /usr/bin/python3 -c "import siloscope; print(siloscope.read_run('run'))"
# The installed package: its in-process module (not in a sanitized build, which makes none: CMakeLists.txt), and
# siloscope.run() finding PREFIX/bin/siloscope (not PATH).
module=no
if ls "$tmp/prefix/lib/siloscope/"_siloscope*.so > /dev/null 2>&1; then module=yes; fi
grep -q "SILOSCOPE_SANITIZE:BOOL=ON" "$build/CMakeCache.txt" || test "$module" = yes
env -u SILOSCOPE_BINARY PATH=/usr/bin:/bin PYTHONPATH="$tmp/prefix/share/siloscope/python" /usr/bin/python3 -c "
import siloscope
scene = '$tmp/prefix/share/siloscope/scenes/paper.toml'
if '$module' == 'yes':
    s = siloscope.Simulation(scene, seed=4, settle_time=2.0)
    s.step(200)
    assert s.n == 250 and abs(s.time - 0.2) < 1e-9
assert siloscope._run.binary() == '$tmp/prefix/bin/siloscope', siloscope._run.binary()
print(siloscope.run(scene, 'run2', seed=1, duration=1, set={'settle_time': 2}))
"
echo "installed siloscope works from $tmp/prefix"
