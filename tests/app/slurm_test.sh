#!/bin/bash
# Issue 16: a campaign through a real (one-node) SLURM cluster gives the same aggregates as the same campaign
# run locally; a task cancelled mid-run (scancel) is completed by resubmitting only what is missing.
# usage: slurm_test.sh SILOSCOPE   (ctest label "slurm"; exit 77 = skipped when no cluster can start here)
set -euo pipefail
bin=$(readlink -f "$1")
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d /tmp/siloscope_slurm.XXXXXX)
chmod 755 "$work"  # the munge and slurm daemons reach their files in it
cluster=$work/cluster
cleanup() { bash "$here/slurm_cluster.sh" stop "$cluster" >/dev/null 2>&1 || true; }
trap cleanup EXIT
if ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
  echo "SKIPPED: slurm-wlm and munge are not installed (.ci/bootstrap installs them)"; exit 77
fi
if ! conf=$(bash "$here/slurm_cluster.sh" start "$cluster"); then
  echo "SKIPPED: the one-node SLURM cluster did not start on this machine (see the logs above)"; exit 77
fi
export SLURM_CONF=$conf

cat > "$work/short.toml" <<TOML
settle_time = 2.0
TOML
cat > "$work/tiny.toml" <<TOML
name = "tiny"
scene = "short.toml"
seed = 16
realizations = 2
duration = 1.5
[grid]
size_ratio = [0.4, 1.0]
[[points]]
chi = 0.0
TOML

# 1. The same campaign locally and as a SLURM array.
"$bin" sweep "$work/tiny.toml" --quiet --results "$work/local"
"$bin" sweep "$work/tiny.toml" --emit-jobs --results "$work/cluster_run" > /dev/null
n=$(wc -l < "$work/cluster_run/jobs.txt")
[ "$n" -eq 6 ] || { echo "FAIL: expected 6 jobs, got $n"; exit 1; }
(cd "$work/cluster_run" && sbatch --wait --array=1-"$n" jobs.slurm > /dev/null)
"$bin" analyze "$work/cluster_run/runs" --out "$work/cluster_run/analysis" > /dev/null
if ! diff -q "$work/local/analysis/points.csv" "$work/cluster_run/analysis/points.csv"; then
  echo "FAIL: the SLURM aggregates differ from the local ones"; exit 1
fi
echo "ok: $n array tasks through sbatch give the local aggregates"

# 2. Cancel one task mid-run; the rest finish; resubmitting completes only what is missing.
sed -i 's/^duration = 1.5/duration = 30.0/' "$work/tiny.toml"
"$bin" sweep "$work/tiny.toml" --emit-jobs --results "$work/cancel" > /dev/null
job=$(cd "$work/cancel" && sbatch --parsable --array=1-6%2 jobs.slurm)
victim=""
for _ in $(seq 200); do
  victim=$(squeue -h -j "$job" -t RUNNING -o %i | head -n 1)
  [ -n "$victim" ] && break
  sleep 0.2
done
[ -n "$victim" ] || { echo "FAIL: no task of job $job started"; exit 1; }
sleep 2  # inside its simulation
scancel "$victim"
for _ in $(seq 600); do
  [ -z "$(squeue -h -j "$job" -o %i)" ] && break
  sleep 0.5
done
done_runs=$(find "$work/cancel/runs" -name metadata.toml | wc -l)
[ "$done_runs" -eq 5 ] || { echo "FAIL: expected 5 finished realizations after scancel, found $done_runs"; exit 1; }
"$bin" sweep "$work/tiny.toml" --emit-jobs --results "$work/cancel" > /dev/null
missing=$(wc -l < "$work/cancel/jobs.txt")
[ "$missing" -eq 1 ] || { echo "FAIL: expected 1 missing job, got $missing"; exit 1; }
(cd "$work/cancel" && sbatch --wait --array=1-"$missing" jobs.slurm > /dev/null)
done_runs=$(find "$work/cancel/runs" -name metadata.toml | wc -l)
[ "$done_runs" -eq 6 ] || { echo "FAIL: expected 6 realizations after resubmitting, found $done_runs"; exit 1; }
leftovers=$(find "$work/cancel/runs" -name '*.partial-*' | wc -l)
[ "$leftovers" -eq 0 ] || { echo "FAIL: $leftovers partial directories left"; exit 1; }
echo "ok: task $victim cancelled, 5 of 6 kept, the resubmission ran only the missing one"
rm -rf "$work/local" "$work/cluster_run" "$work/cancel"
