#!/usr/bin/env bash
# passim study precision --slurm without a cluster (docs/cluster.md):
#  1. the scripts run by hand, one shard after another, then the merge: the same bytes as the
#     one-machine run; status from the shard files alone;
#  2. bad input: no sbatch on the PATH, a refused submission, options passim sets itself;
#  3. status and resume against stand-ins for sbatch, squeue, sacct and scancel that print what
#     a cluster would and log what they are asked: which shards go again, after which jobs.
# The real thing, a one-node cluster on this machine, is cluster_test.sh.
# Usage: scripts_test.sh PASSIM WORK
set -euo pipefail
passim=$(realpath "$1")
work=$(realpath -m "$2")
rm -rf "$work"
mkdir -p "$work"
cd "$work"

fail() { echo "FAIL: $*" >&2; exit 1; }
# run CODE NAME ARGS...: passim ARGS must exit with CODE; its stdout and stderr go to NAME.out/.err.
run() {
  local want=$1 name=$2 got=0
  shift 2
  "$@" > "$name.out" 2> "$name.err" || got=$?
  [ "$got" -eq "$want" ] || { cat "$name.out" "$name.err" >&2; fail "$name: exit $got, expected $want"; }
}
has() { grep -qF -- "$2" "$1" || { cat "$1" >&2; fail "$1 does not say: $2"; }; }
same_files() {  # every file of the one-machine run, byte for byte
  local f n=0
  for f in "$1"/*; do
    cmp -s "$f" "$2/$(basename "$f")" || fail "$2/$(basename "$f") differs from the one-machine run's"
    n=$((n + 1))
  done
  echo "  $n files identical to the one-machine run's"
}

study=(study precision --program pcf --filter 2x2 --scene edges --size 160x120 --bits 6,8,12 --bias 0,1 --figures png)
run 0 local "$passim" "${study[@]}" -q --out local

echo "== the scripts by hand"
run 0 write "$passim" "${study[@]}" --slurm --no-submit --array-size 3 --partition short --time 5 --mem 1G \
    --slurm-extra="--account=lab --qos short" --out byhand
has write.out "6 points in 3 shards"
s=byhand/slurm/shards.sbatch
for line in '#SBATCH --array=1-3' '#SBATCH --partition=short' '#SBATCH --time=5' '#SBATCH --mem=1G' \
            '#SBATCH --account=lab' '#SBATCH --qos short' '#SBATCH --cpus-per-task=1' '--shard "$SHARD/3"'; do
  has "$s" "$line"
done
has byhand/slurm/merge.sbatch '#SBATCH --partition=short'
has byhand/slurm/merge.sbatch 'for ((i = 1; i <= 3; i++))'
nosq=$work/nobin  # a PATH without Slurm's commands
mkdir -p "$nosq"
SLURM_ARRAY_TASK_ID=1 bash "$s" > /dev/null
SLURM_ARRAY_TASK_ID=3 bash "$s" > /dev/null
run 0 status1 env PATH="$nosq" "$passim" study status byhand
has status1.out "points done: 4 of 6"
has status1.out "shards: 2 done, 0 running, 0 pending, 0 failed, 1 missing"
has status1.out "missing: 2"
has status1.out "Slurm not reachable (squeue is not on the PATH)"
SLURM_ARRAY_TASK_ID=2 bash "$s" > /dev/null
bash byhand/slurm/merge.sbatch > /dev/null
run 0 status2 env PATH="$nosq" "$passim" study status byhand --json
has status2.out '"merge": "done"'
has status2.out '"points_done": 6'
same_files local byhand

echo "== bad input"
run 1 toomany "$passim" "${study[@]}" --slurm --array-size 7 --out bad
has toomany.err "--array-size 7: 1 to the sweep's 6 points"
run 2 needs "$passim" "${study[@]}" --partition short --out bad
run 2 excludes "$passim" "${study[@]}" --slurm --shard 1/2 --out bad
run 1 own "$passim" "${study[@]}" --slurm --slurm-extra="--output=x.log" --out bad
has own.err "--output=x.log is set by passim"
[ ! -e bad ] || fail "refused options wrote files"
run 1 nosbatch env PATH="$nosq" "$passim" "${study[@]}" --slurm --out nosbatch
has nosbatch.err "sbatch is not on the PATH"
has nosbatch.err "sbatch $work/nosbatch/slurm/shards.sbatch"
[ -f nosbatch/slurm/shards.sbatch ] && [ -f nosbatch/slurm/merge.sbatch ] || fail "the scripts are not left in place"
run 1 status3 env PATH="$nosq" "$passim" study status nothing-here
has status3.err "not a Slurm study"

# Stand-ins: sbatch logs its arguments and prints the next job id (or refuses, as told by a
# file); squeue prints $fake/queue (or cannot reach the controller); sacct prints $fake/acct.
fake=$work/fake
mkdir -p "$fake/bin"
echo 100 > "$fake/next_id"
cat > "$fake/bin/sbatch" <<EOF
#!/bin/sh
echo "\$*" >> $fake/sbatch.log
case "\$*" in *merge.sbatch) [ -f $fake/refuse_merge ] && { echo "sbatch: error: QOSMaxSubmitJobPerUserLimit" >&2; exit 1; } ;; esac
[ -f $fake/refuse ] && { echo "sbatch: error: Batch job submission failed: Invalid account or account/partition combination specified" >&2; exit 1; }
n=\$(cat $fake/next_id); echo \$((n + 1)) > $fake/next_id; echo "\$n"
EOF
cat > "$fake/bin/squeue" <<EOF
#!/bin/sh
[ -f $fake/down ] && { echo "squeue: error: Unable to contact slurm controller (connect failure)" >&2; exit 1; }
cat $fake/queue 2>/dev/null; exit 0
EOF
printf '#!/bin/sh\ncat %s/acct 2>/dev/null\n' "$fake" > "$fake/bin/sacct"
printf '#!/bin/sh\necho "$*" >> %s/scancel.log\n' "$fake" > "$fake/bin/scancel"
chmod +x "$fake/bin/"*
fpath="$fake/bin:$PATH"  # the stand-ins come first

echo "== a refused submission"
touch "$fake/refuse"
run 1 refused env PATH="$fpath" "$passim" "${study[@]}" --slurm --out refused
has refused.err "sbatch refused the shards' array job:"
has refused.err "Invalid account or account/partition combination specified"
has refused.err "passim study resume $work/refused"
has refused/slurm/jobs.json '"submissions": []'
rm "$fake/refuse"
touch "$fake/refuse_merge"
run 1 refused_merge env PATH="$fpath" "$passim" "${study[@]}" --slurm --out refused_merge
has refused_merge.err "shards 1-6 are submitted as array job 100, but sbatch refused the merge job:"
has refused_merge.err "QOSMaxSubmitJobPerUserLimit"
rm "$fake/refuse_merge" "$fake/sbatch.log"
echo 102 > "$fake/next_id"

echo "== submission, status and resume against the stand-ins"
run 0 submit env PATH="$fpath" "$passim" "${study[@]}" --slurm --array-size 4 --out fk
has submit.out "submitted shards 1-4 of 4 as array job 102, and the merge as job 103 after them"
has "$fake/sbatch.log" "--parsable $work/fk/slurm/shards.sbatch"
has "$fake/sbatch.log" "--parsable --kill-on-invalid-dep=yes --dependency=afterok:102 $work/fk/slurm/merge.sbatch"
run 1 again env PATH="$fpath" "$passim" "${study[@]}" --slurm --array-size 4 --out fk
has again.err "holds a Slurm study already submitted"
name=$(sed -n 's/.*"job_name": "\(.*\)".*/\1/p' fk/slurm/jobs.json)
# Shard 1 done; 2 ran and died (its log, no result, a leftover partial folder); 3 is missing;
# 4 still runs; the merge was dropped by Slurm when shard 2 failed.
SLURM_ARRAY_TASK_ID=1 bash fk/slurm/shards.sbatch > /dev/null
echo "slurmstepd: error: *** JOB 104 ON node7 CANCELLED AT 2026-12-02T10:00:00 DUE TO TIME LIMIT ***" > fk/slurm/logs/shard-2.out
mkdir -p fk/shards/.2.partial-node7-99 fk/shards/.4.partial-node7-98
echo "102|4|R|None|$name-shards" > "$fake/queue"
printf '102_2|TIMEOUT\n102_3|CANCELLED by 0\n' > "$fake/acct"
run 0 fstatus env PATH="$fpath" "$passim" study status fk
has fstatus.out "points done: 2 of 6"
has fstatus.out "shards: 1 done, 1 running, 0 pending, 1 failed, 1 missing"
has fstatus.out "failed: 2 (slurm/logs/shard-2.out): TIMEOUT: slurmstepd: error: *** JOB 104 ON node7 CANCELLED AT 2026-12-02T10:00:00 DUE TO TIME LIMIT ***"
has fstatus.out "missing: 3"
has fstatus.out "merge: not run"
touch "$fake/down"
run 1 fdown env PATH="$fpath" "$passim" study resume fk
has fdown.err "Slurm is not reachable (squeue: error: Unable to contact slurm controller (connect failure))"
rm "$fake/down"
: > "$fake/sbatch.log"
run 0 fresume env PATH="$fpath" "$passim" study resume fk
has fresume.out "failed: shards 2"
has fresume.out "missing: shards 3"
has fresume.out "submitted shards 2-3 of 4 as array job 104, and the merge as job 105 after them"
has "$fake/sbatch.log" "--parsable --array=2-3 $work/fk/slurm/shards.sbatch"
has "$fake/sbatch.log" "--dependency=afterok:104,afterany:102 $work/fk/slurm/merge.sbatch"
[ ! -e fk/shards/.2.partial-node7-99 ] || fail "resume left the killed shard's partial folder"
[ -e fk/shards/.4.partial-node7-98 ] || fail "resume removed a running shard's partial folder"
# A merge queued: nothing to do; a queued merge when shards go again is cancelled first.
printf '104|2|PD|None|%s-shards\n105|N/A|PD|Dependency|%s-merge\n' "$name" "$name" > "$fake/queue"
run 0 fqueued env PATH="$fpath" "$passim" study status fk
has fqueued.out "merge: queued (job 105, waiting: Dependency)"
rm fk/slurm/logs/shard-2.out
printf '105|N/A|PD|Dependency|%s-merge\n' "$name" > "$fake/queue"
run 0 fresume2 env PATH="$fpath" "$passim" study resume fk
has "$fake/scancel.log" "105"
has fresume2.out "submitted shards 2-4 of 4 as array job 106"
echo "scripts_test: passed"
