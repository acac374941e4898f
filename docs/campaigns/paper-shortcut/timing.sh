#!/usr/bin/env bash
# Core-seconds per realization before and after the shortcut: each seed run with arrest_skip = 0 and = 1 side by
# side (one core each), at both presets and three points of the literal campaign; 150 s, the campaign's seeds.
set -u
S=build/siloscope  # run from the repository root
out=${1:-timing}; mkdir -p $out
csv=$out/timing.csv
[ -f $csv ] || echo "preset,point,seed,arrest_skip,settle_s,discharge_s,core_s,skipped_s,exits,clogs" > $csv
R=docs/campaigns/paper/analysis/realizations.csv
seeds() { awk -F, -v r="$1" -v c="$2" '$1==r && $2==c && $3=="0.0" {print $5}' $R | head -n 3; }
for preset in paper paper-vibrated; do
  for point in "pure 0.4 0.0" "r0.4 0.4 0.4" "r1.0 1.0 0.4"; do
    set -- $point; name=$1; r=$2; chi=$3
    for seed in $(seeds $r $chi); do
      for k in 0 1; do
        d=$out/$preset-$name-$seed-$k
        [ -f $d/metadata.toml ] || $S run assets/scenes/$preset.toml --duration 150 --seed $seed \
            --set size_ratio=$r --set chi=$chi --set arrest_skip=$k --out $d --quiet --force &
      done
      wait
      for k in 0 1; do
        d=$out/$preset-$name-$seed-$k
        grep -q "^$preset,$name,$seed,$k," $csv && continue
        st=$(awk -F' = ' '/^wall_time_settle_s/ {print $2}' $d/metadata.toml)
        di=$(awk -F' = ' '/^wall_time_discharge_s/ {print $2}' $d/metadata.toml)
        sk=$(awk -F' = ' '/^arrest_skipped_s/ {print $2}' $d/metadata.toml); sk=${sk:-0}
        ex=$(sed -n 2p $d/summary.csv | cut -d, -f7); cl=$(sed -n 2p $d/summary.csv | cut -d, -f17)
        echo "$preset,$name,$seed,$k,$st,$di,$(echo "$st + $di" | bc -l),$sk,$ex,$cl" >> $csv
      done
    done
  done
done
