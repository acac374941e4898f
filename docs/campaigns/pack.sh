#!/bin/bash
# Pack a finished campaign's results for the repository: what `analyze` needs and nothing more.
#   docs/campaigns/pack.sh RESULTS DEST      e.g. docs/campaigns/pack.sh results/obstacle docs/campaigns/obstacle
# DEST gets campaign.toml, runs/runs.tar.xz (each realization's metadata.toml, exits.csv, clogs.csv, arches.csv,
# and trajectory.sstraj when the campaign kept trajectories (trajectory_fps), and any *.refused.toml) and analysis/ (points, realizations, survival, avalanches, clog survival, species, metadata). The test suite
# re-analyses every pack and compares.
set -euo pipefail
src=${1:?usage: pack.sh RESULTS DEST}
dest=${2:?usage: pack.sh RESULTS DEST}
[ -f "$src/campaign.toml" ] && [ -d "$src/runs" ] && [ -f "$src/analysis/points.csv" ] || {
  echo "pack.sh: $src is not a finished campaign's results (campaign.toml, runs/, analysis/points.csv)" >&2
  exit 2
}
mkdir -p "$dest/runs" "$dest/analysis"
list=$(mktemp)
cp "$src/campaign.toml" "$dest/"
# A campaign that kept trajectories (trajectory_fps) is analysed from them too (column.csv); analyze then checks
# them (manifests are not packed: pack.sh rewrites each metadata.toml's command line, and takes out the line
# that declares a manifest, which a reader would otherwise miss).
traj=()
grep -q '^trajectory_fps' "$src/campaign.toml" && traj=(-o -name trajectory.sstraj)
(cd "$src" && find runs \( -name metadata.toml -o -name exits.csv -o -name clogs.csv -o -name arches.csv \
  -o -name '*.refused.toml' "${traj[@]}" \) | LC_ALL=C sort > "$list")
# Staged, so that each realization's command line names the program, not where this machine keeps it.
stage=$(mktemp -d)
(cd "$src" && cp --parents $(cat "$list") "$stage/")
find "$stage" -name metadata.toml -exec sed -i -E -e 's#^command = "[^" ]*/(siloscope[^" ]*) #command = "siloscope #' \
  -e '/^manifest = "manifest.toml"$/d' {} +
tar -C "$stage" -cf - --owner=0 --group=0 --numeric-owner --mtime=2026-01-01 -T "$list" \
  | xz -9e > "$dest/runs/runs.tar.xz.partial"
rm -rf "$list" "$stage"
mv "$dest/runs/runs.tar.xz.partial" "$dest/runs/runs.tar.xz"
for f in points.csv realizations.csv survival.csv avalanches.csv clog_survival.csv species.csv metadata.toml; do
  cp "$src/analysis/$f" "$dest/analysis/"
done
[ -f "$src/analysis/drain.csv" ] && cp "$src/analysis/drain.csv" "$dest/analysis/"  # a drain campaign's J
[ -f "$src/analysis/column.csv" ] && cp "$src/analysis/column.csv" "$dest/analysis/"  # from kept trajectories
# No path of this machine in the pack: realizations are named relative to the pack (runs/p000/r000).
abs=$(cd "$src" && pwd)
sed -i "s#,$abs/runs/#,runs/#" "$dest/analysis/realizations.csv"
# ... and the analysis' own command line names the program and a results folder, not this machine's paths.
sed -i -E -e '/^manifest = "manifest.toml"$/d' \
  -e "s#^command = \"[^\" ]*/(siloscope[^\" ]*) #command = \"siloscope #; s#$abs#results/$(basename "$dest")#g" \
  "$dest/analysis/metadata.toml"
echo "packed $(tar -tJf "$dest/runs/runs.tar.xz" | grep -c metadata.toml) realizations into $dest ($(du -sh "$dest" | cut -f1))"
