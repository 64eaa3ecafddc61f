#!/usr/bin/env bash
# passim study precision --slurm on a real one-node Slurm cluster started on this machine
# (one-node.sh; docs/cluster.md): a partition that does not exist is refused; a small sweep
# submitted with --slurm, one of its shards killed while it runs, the study's status, resume;
# the merged files byte for byte against the one-machine run. The daemons are stopped at the
# end, whatever happens (trap).
# Usage: cluster_test.sh PASSIM WORK     (root; exit 77, "skipped", without root)
set -euo pipefail
passim=$(realpath "$1")
work=$(realpath -m "$2")
here=$(cd "$(dirname "$0")" && pwd)
[ "$(id -u)" -eq 0 ] || { echo "cluster_test: skipped: slurmd needs root"; exit 77; }
rm -rf "$work"
mkdir -p "$work"
cd "$work"
start=$SECONDS

fail() { echo "FAIL: $*" >&2; exit 1; }
run() {  # run CODE NAME COMMAND...: stdout and stderr to NAME.out/.err
  local want=$1 name=$2 got=0
  shift 2
  "$@" > "$name.out" 2> "$name.err" || got=$?
  [ "$got" -eq "$want" ] || { cat "$name.out" "$name.err" >&2; fail "$name: exit $got, expected $want"; }
}
has() { grep -qF -- "$2" "$1" || { cat "$1" >&2; fail "$1 does not say: $2"; }; }

# The cluster lives in a short temporary folder (a UNIX socket's path is at most 107 bytes).
cluster=$(mktemp -d /tmp/passim-slurm.XXXXXX)
stop_all() {
  local rc=$?
  if [ -n "${name:-}" ]; then scancel --name="$name-shards,$name-merge" 2>/dev/null || true; fi
  bash "$here/one-node.sh" stop "$cluster" || true
  if [ "$rc" -ne 0 ]; then  # what the daemons said, for the failure's report
    tail -n 15 "$cluster"/*.log >&2 2>/dev/null || true
  fi
  rm -rf "$cluster"
  exit "$rc"
}
trap stop_all EXIT
trap 'exit 1' INT TERM
bash "$here/one-node.sh" start "$cluster"
export SLURM_CONF=$cluster/slurm.conf
echo "  cluster up after $((SECONDS - start)) s"

# wait_gone NAME...: until no job of these names is in the queue (at most 180 s).
wait_gone() {
  local names
  names=$(IFS=,; echo "$*")
  for _ in $(seq 900); do
    [ -z "$(squeue --noheader --name="$names" --format=%i)" ] && return 0
    sleep 0.2
  done
  squeue >&2
  fail "jobs $names still queued after 180 s"
}

# 12 points in 4 shards of 3 (each task a second or two, so that one can be killed running).
study=(study precision --program pcf --filter 2x2 --scene paper --size 320x240 --bits 6,8,10,12 --bias 0,0.5,1 --figures png)

echo "== a partition that does not exist"
run 1 nopart "$passim" "${study[@]}" --slurm --partition nope --out nopart
has nopart.err "sbatch refused the shards' array job:"
has nopart.err "invalid partition specified: nope"
[ -f nopart/slurm/shards.sbatch ] && [ -f nopart/slurm/merge.sbatch ] || fail "the scripts are not left in place"

echo "== the one-machine run"
run 0 local "$passim" "${study[@]}" --jobs 2 -q --out local

echo "== the sweep through Slurm, one shard killed as it runs"
run 0 submit "$passim" "${study[@]}" --slurm --array-size 4 --time 5 --out s
has submit.out "submitted shards 1-4 of 4 as array job"
name=$(sed -n 's/.*"job_name": "\(.*\)".*/\1/p' s/slurm/jobs.json)
array=$(sed -n 's/.*as array job \([0-9]*\),.*/\1/p' submit.out)
killed=""
for _ in $(seq 1200); do  # at most 60 s
  running=$(squeue --noheader --array --name="$name-shards" --states=R --format=%K | head -n 1)
  if [ -n "$running" ]; then
    scancel "${array}_${running}"
    # Gone from the queue; killed if it left no result (else it had just finished: another one).
    while [ -n "$(squeue --noheader --array --name="$name-shards" --format=%K | grep -x "$running")" ]; do sleep 0.1; done
    if [ ! -e "s/shards/$running/study.json" ]; then killed=$running; break; fi
  fi
  [ -z "$(squeue --noheader --name="$name-shards" --format=%i)" ] && break
  sleep 0.05
done
[ -n "$killed" ] || fail "no shard could be killed while it ran (all finished first?)"
echo "  killed shard $killed"
has "s/slurm/logs/shard-$killed.out" "CANCELLED"
[ ! -e "s/shards/$killed" ] || fail "the killed shard left a result folder: s/shards/$killed"
wait_gone "$name-shards" "$name-merge"
run 0 status1 "$passim" study status s
has status1.out "points done: 9 of 12"
has status1.out "shards: 3 done, 0 running, 0 pending, 1 failed, 0 missing"
has status1.out "failed: $killed (slurm/logs/shard-$killed.out): "
has status1.out "merge: not run"   # Slurm dropped it: a shard it waited on failed
[ ! -e s/study.csv ] || fail "a merge ran without every shard"

echo "== resume"
run 0 resume "$passim" study resume s
has resume.out "failed: shards $killed"
has resume.out "submitted shards $killed of 4 as array job"
wait_gone "$name-shards" "$name-merge"
run 0 status2 "$passim" study status s
has status2.out "points done: 12 of 12"
has status2.out "shards: 4 done, 0 running, 0 pending, 0 failed, 0 missing"
has status2.out "merge: done"
ls -a s/shards | grep -q partial && fail "a partial folder is left in s/shards"
n=0
for f in local/*; do
  cmp -s "$f" "s/$(basename "$f")" || fail "s/$(basename "$f") differs from the one-machine run's"
  n=$((n + 1))
done
echo "  $n files identical to the one-machine run's ($(du -cb local/* | tail -n 1 | cut -f1) bytes)"
run 0 resume2 "$passim" study resume s
has resume2.out "nothing to resume: all 4 shards are done and merged"
echo "cluster_test: passed in $((SECONDS - start)) s"
