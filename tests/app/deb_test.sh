#!/usr/bin/env bash
# The Debian package (issue 52): made by cpack from the suite's build, checked by lintian (no errors), unpacked
# into a temporary root and used from there as a user would: the installed binary runs a preset by its name, the
# man page of a command is there and reads, Debian's python3 imports the package (through its .pth file) and
# finds the presets.
#   bash tests/app/deb_test.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && cpack --config "$build/CPackConfig.cmake" -G DEB > cpack.log 2>&1) || { cat "$work/cpack.log"; exit 1; }
deb=$(ls "$work"/siloscope_*.deb)
echo "package: $(basename "$deb") ($(du -h "$deb" | cut -f1))"
dpkg-deb --info "$deb" | grep -E "Package|Version|Depends" | sed 's/^ *//'
# lintian: no errors (warnings are listed, not fatal). As root it must be told it may run.
if command -v lintian > /dev/null; then
  lintian --allow-root --tag-display-limit 0 "$deb" > "$work/lintian.txt" 2>&1 || true
  cat "$work/lintian.txt"
  if grep -q '^E:' "$work/lintian.txt"; then
    echo "lintian reports errors"
    exit 1
  fi
else
  echo "lintian is not installed (the test command installs it)"
  exit 1
fi
root="$work/root"
dpkg-deb -x "$deb" "$root"
test -x "$root/usr/bin/siloscope"
"$root/usr/bin/siloscope" --version
# A preset by its name, from the installed share directory.
(cd "$work" && "$root/usr/bin/siloscope" run paper --duration 2 --quiet --out "$work/r")
test -s "$work/r/summary.csv"
# A man page per command, gzipped, that reads.
for page in siloscope siloscope-record siloscope-run siloscope-inspect; do
  test -s "$root/usr/share/man/man1/$page.1.gz"
done
zcat "$root/usr/share/man/man1/siloscope-record.1.gz" | grep -q 'SILOSCOPE-RECORD'
if command -v groff > /dev/null; then
  zcat "$root/usr/share/man/man1/siloscope-record.1.gz" | groff -man -Tutf8 2>/dev/null | grep -q -- '--duration'
fi
test -s "$root/usr/share/bash-completion/completions/siloscope"
test -s "$root/usr/share/doc/siloscope/copyright"
# Debian's python3 imports the package: the .pth file names where it is (rewritten for this temporary root).
pth=$(cat "$root/usr/lib/python3/dist-packages/siloscope.pth")
test "$pth" = "/usr/share/siloscope/python"
# The compiled module is under /usr/lib/siloscope (architecture-dependent), and the package finds it.
ls "$root"/usr/lib/siloscope/_siloscope*.so > /dev/null
# ... and the picture and video readers the binary loads when it reads a film (vision/codecs.h).
(cd "$work" && "$root/usr/bin/siloscope" record paper --duration 0.3 --set settle_time=1 --size 640x360 \
  --camera window:-1,-0.2,1,0.9 --overlay none --arch-halo off --quiet --out "$work/film" &&
  "$root/usr/bin/siloscope" detect "$work/film.mp4" --out "$work/film.csv" > "$work/detect.log") ||
  { cat "$work/detect.log"; exit 1; }
[ "$(wc -l < "$work/film.csv")" -gt 100 ] || { echo "FAIL: detect found $(wc -l < "$work/film.csv") rows"; exit 1; }
version=$("$root/usr/bin/siloscope" --version | cut -d' ' -f1)
PYTHONPATH="$root/usr/share/siloscope/python" /usr/bin/python3 -c "
import siloscope
from siloscope import _native
assert _native.module_or_none() is not None, 'the compiled module was not found'
print('import siloscope', siloscope.__version__)
assert siloscope.__version__ == '$version', siloscope.__version__
"
echo "deb: built, lintian clean, used from $root"
