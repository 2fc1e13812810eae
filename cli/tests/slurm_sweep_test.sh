#!/usr/bin/env bash
# A sweep through a real one-node Slurm cluster (ci/slurm-cluster) gives the same table, cell for
# cell, as the same suite on the local backend. Skipped (exit 77) when not root: the cluster's
# daemons need it.
#   slurm_sweep_test.sh ISG REPO_ROOT
set -euo pipefail
isg=$1
root=$2
if [[ $(id -u) != 0 ]]; then
  echo "skipped: starting slurmctld and slurmd needs root (running as $(id -un))"
  exit 77
fi
work=$(mktemp -d /tmp/isg_slurm_test.XXXXXX)
cluster=$work/cluster
cleanup() {
  "$root/ci/slurm-cluster" stop "$cluster" > /dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
# Arrays of at most 5 tasks: the 8 cells go as two arrays, as a sweep larger than a site's
# MaxArraySize would (isg sweep reads it with scontrol).
"$root/ci/slurm-cluster" start "$cluster" --max-array-size 5
export SLURM_CONF=$cluster/slurm.conf

cd "$work"
cat > suite.json <<'JSON'
{
  "format": "isg.suite", "version": 1, "name": "slurm test",
  "worlds": ["builtin:d1", {"generate": {"family": "hotel", "rooms": 6, "seed": 2}}],
  "seeds": [1, 2],
  "methods": ["is-graphs", "odometry"],
  "run": {"duration": 40, "threads": 1},
  "slurm": {"cpus_per_task": 1, "time": "00:10:00", "mem": "2G"}
}
JSON
fail() { echo "FAIL: $*" >&2; exit 1; }
# A sweep folder and a suite name that sbatch's #SBATCH parser would split or cut short (a space,
# a '#') and a '%' that Slurm's --output pattern would read as a replacement symbol.
out="slurm run #1 (50%)"

"$isg" sweep suite.json -o "$out" --backend slurm --wait > slurm.out || fail "the Slurm sweep exited $?"
grep -q "as Slurm jobs [0-9]*, [0-9]* (8 array tasks in 2 arrays of at most 5 tasks)" slurm.out ||
  fail "not submitted as two arrays of 8 tasks in all: $(cat slurm.out)"
tasks=$(ls "$out"/logs/slurm-*_*.out | wc -l)
((tasks == 8)) || fail "expected 8 Slurm task logs in '$out/logs', found $tasks"
"$isg" sweep suite.json -o local --jobs 2 -q > local.out || fail "the local sweep exited $?"
cmp "$out/table.csv" local/table.csv || {
  diff "$out/table.csv" local/table.csv >&2
  fail "the Slurm and local tables differ"
}
# Every cell's numbers, not only the table's means: the run folders' APE agree.
for m in local/*/*/seed-*/metrics.json; do
  s=$out/${m#local/}
  a=$(grep -o '"rmse": [0-9.e+-]*' "$m")
  b=$(grep -o '"rmse": [0-9.e+-]*' "$s")
  [[ $a == "$b" ]] || fail "$m: $a, Slurm's $b"
done
# --collect on the Slurm folder gives the same table again.
"$isg" sweep --collect "$out" > /dev/null || fail "--collect exited $?"
cmp "$out/table.csv" local/table.csv || fail "--collect changed the table"
echo "ok: 8 cells through Slurm ($(grep -o 'jobs [0-9]*, [0-9]*' slurm.out)), table equal to the local backend's:"
cat local/table.csv
