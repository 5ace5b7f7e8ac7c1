#!/usr/bin/env bash
# slurm_test.sh BUNDLELAB OUTDIR: `bundlelab run --slurm` end to end on a real single-node Slurm
# cluster (scripts/local-slurm.sh: Debian's slurmctld, slurmd and munge, started here, no mock).
# The array runs, a second submission is refused while it is queued, one task is killed mid-run,
# --collect lists exactly that task, the same command resubmits exactly that task, nothing
# finished runs again, each reference is rendered once, and the merged results and report equal a
# local run's (times aside).
set -uo pipefail
bl=$1
out=$2/slurm
config=tests/experiments/slurm.toml
fail() { echo "FAIL: $*"; exit 1; }
for tool in munged slurmctld slurmd sbatch squeue scancel; do
    command -v "$tool" >/dev/null || { echo "SKIP: $tool not installed (scripts/install-deps.sh installs slurmctld slurmd slurm-client munge)"; exit 77; }
done
# slurmd starts each job as its user: a private cluster here runs as root (as CI does, since it
# installs packages); as another user it is skipped, saying why.
[[ $(id -u) -eq 0 ]] || { echo "SKIP: the private Slurm cluster of this test needs root (slurmd launches jobs as their user)"; exit 77; }
rm -rf "$out" && mkdir -p "$out"
cluster=$out/cluster
trap 'scripts/local-slurm.sh stop "$cluster"' EXIT
scripts/local-slurm.sh start "$cluster" >"$out/cluster.txt" 2>&1 || { cat "$out/cluster.txt"; fail "the local cluster did not start"; }
export SLURM_CONF=$cluster/slurm.conf
results=$out/results
queue_empty() { [[ -z $(squeue --noheader --format=%i --name="$1") ]]; }
wait_queue() {
    for _ in $(seq 1 240); do queue_empty "$1" && return 0; sleep 0.5; done
    squeue; fail "jobs still queued after 120 s"
}

"$bl" run "$config" --out "$results" --slurm --max-parallel 2 >"$out/submit1.txt" 2>&1 || { cat "$out/submit1.txt"; fail "first submission"; }
cat "$out/submit1.txt"
grep -q "submitted job [0-9]*, 6 of 6 tasks (array 0-5%2), after reference job" "$out/submit1.txt" || fail "expected an array of 6 after a reference job"
name=$(grep -o "'--job-name=[^']*'" "$results/slurm/submit-1.sbatch" | sed "s/'--job-name=//; s/'//")
[[ -n "$name" ]] || fail "no job name in the array script"

# While the array is in the queue, the same command submits nothing.
if "$bl" run "$config" --out "$results" --slurm >"$out/submit-busy.txt" 2>&1; then fail "a second submission was accepted while the first is queued"; fi
grep -q "still in the Slurm queue" "$out/submit-busy.txt" || { cat "$out/submit-busy.txt"; fail "no reason given for refusing"; }
[[ ! -e "$results/slurm/submit-2.sbatch" ]] || fail "the refused submission wrote a script"

# Kill the slow seed-0 task mid-run: once it has started (task.json) and before it is done.
victim=0004-cornell64-slow-s0
element=$(awk -F'\t' -v id="$victim" '$4 == id { print $1 "_" $2 }' "$results/slurm/submissions.tsv")
[[ -n "$element" ]] || fail "$victim not in submissions.tsv"
for _ in $(seq 1 240); do [[ -s "$results/tasks/$victim/task.json" ]] && break; sleep 0.25; done
[[ -s "$results/tasks/$victim/task.json" ]] || fail "$victim never started"
[[ ! -e "$results/tasks/$victim/done.json" ]] || fail "$victim finished before it could be killed (make it slower)"
scancel "$element" || fail "scancel $element"
wait_queue "$name"

if "$bl" run "$config" --out "$results" --collect >"$out/collect1.txt" 2>&1; then cat "$out/collect1.txt"; fail "--collect said all finished"; fi
cat "$out/collect1.txt"
grep -q "5 of 6 tasks finished" "$out/collect1.txt" || fail "expected 5 finished"
[[ $(grep -c "^  unfinished\|^  failed" "$out/collect1.txt") -eq 1 ]] || fail "expected exactly one unfinished task"
grep -q "unfinished $victim: .*log: .*/${element}.out" "$out/collect1.txt" || fail "the killed task and its log not named"
[[ $(wc -l <"$results/results.csv") -eq 6 ]] || fail "results.csv should hold the 5 finished tasks"
stamps() { stat -c '%n %Y %i' "$results"/tasks/*/done.json | grep -v "$victim"; }
stamps >"$out/stamps-before.txt"

# The same command again: exactly the killed task, no second reference job.
"$bl" run "$config" --out "$results" --slurm --max-parallel 2 >"$out/submit2.txt" 2>&1 || { cat "$out/submit2.txt"; fail "resubmission"; }
cat "$out/submit2.txt"
grep -q "submitted job [0-9]*, 1 of 6 tasks (array 0%2)$" "$out/submit2.txt" || fail "expected one task resubmitted, without a reference job"
grep -q "^tasks=(4)$" "$results/slurm/submit-2.sbatch" || fail "the resubmitted array is not task 4 alone"
wait_queue "$name"
"$bl" run "$config" --out "$results" --collect >"$out/collect2.txt" 2>&1 || { cat "$out/collect2.txt"; fail "--collect after the resubmission"; }
grep -q "6 of 6 tasks finished" "$out/collect2.txt" || fail "expected 6 finished"
stamps | diff "$out/stamps-before.txt" - || fail "a finished task ran again"
[[ $(cat "$results"/slurm/logs/*.out | grep -c "reference for scene '.*': rendering") -eq 2 ]] || fail "each of the 2 references must be rendered exactly once"

# The merged results equal a local run's in everything but time.
"$bl" run "$config" --out "$out/local" >"$out/local.txt" 2>&1 || { cat "$out/local.txt"; fail "local run"; }
content() { cut -d, -f1-8,12-21 "$1/results.csv"; }
diff <(content "$out/local") <(content "$results") || fail "the array's results differ from the local run's"
# And so do the reports, times masked (wall, time to relMSE, relMSE at equal time, speed-up).
for d in "$out/local" "$results"; do "$bl" report "$d" >"$d.report.txt" 2>&1 || { cat "$d.report.txt"; fail "report of $d"; }; done
untimed() { awk -F'|' 'NF > 10 { print $2 "|" $3 "|" $4 "|" $5 "|" $7 "|" $8; next } { print }' "$1/report.md"; }
diff <(untimed "$out/local") <(untimed "$results") || fail "the array's report differs from the local run's"
echo "PASS"
