#!/usr/bin/env bash
# The breaking-kick campaign (docs/arches.md): short runs of a scene, each arrested clog's arch kicked harder
# until it breaks (siloscope breaking), resumable: a seed whose breaking.csv exists is skipped.
#   bash docs/arches/campaign.sh BINARY SCENE RESULTS FIRST_SEED LAST_SEED [KICK]
# Each run lasts 7 s: its first clogs are the arches tested (replays cost what precedes the clog).
set -euo pipefail
binary=$1 scene=$2 results=$3 first=$4 last=$5 kick=${6:-uniform}
mkdir -p "$results"
for seed in $(seq "$first" "$last"); do
  out="$results/s$seed"
  [ -s "$out/breaking/breaking.csv" ] && continue
  rm -rf "$out.partial"
  mkdir -p "$out.partial"
  "$binary" run "$scene" --seed "$seed" --duration 7 --quiet --out "$out.partial/run"
  "$binary" breaking "$out.partial/run" --out "$out.partial/breaking" --kick "$kick" --bisections 5 \
    --jobs 1 2>/dev/null
  rm -rf "$out"
  mv "$out.partial" "$out"
done
