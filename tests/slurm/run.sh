#!/usr/bin/env bash
# The Slurm path on a real one-node cluster (tests/slurm/cluster.sh): the README's submit line
# over 4 shards, its merge against one local run byte for byte, then a sweep with one shard's
# job killed (the merge does not run, the shard is not marked complete) and the same submit line
# again, which reruns only that shard and merges.
#
#   tests/slurm/run.sh        # after cargo build --release; exit 3 when Slurm cannot be set up
set -euo pipefail
cd "$(dirname "$0")/../.."

bin=target/release/swarmplan
[ -x "$bin" ] || { echo "build first: cargo build --release" >&2; exit 2; }
status=0
tests/slurm/cluster.sh up || status=$?
[ "$status" = 0 ] || exit "$status"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
options=(--limit 24 --exact-limit 2 --joint)
files=(config.json requests.csv hops.csv stops.csv joint.csv)

# Waits until the jobs given have left the queue (at most 15 minutes).
wait_jobs() {
  for _ in $(seq 1 900); do
    if [ -z "$(squeue -h -j "$1" 2>/dev/null)" ]; then return 0; fi
    sleep 1
  done
  echo "jobs $1 still queued after 15 minutes" >&2
  squeue >&2
  return 1
}

same_as_local() {
  for f in "${files[@]}"; do
    cmp "$1/$f" "$work/local/$f" || { echo "$1/$f differs from one local run" >&2; return 1; }
  done
  echo "$1: ${files[*]} equal one local run, byte for byte"
}

"$bin" bench "${options[@]}" --out "$work/local" >/dev/null 2>&1

# 1. The sweep as the README submits it.
read -r _ array _ merge < <(examples/slurm/submit.sh --shards 4 --out "$work/sweep" -- "${options[@]}")
wait_jobs "$array,$merge"
same_as_local "$work/sweep/merged"

# 2. One shard's job killed before it runs: no merge, no completion mark for that shard.
read -r _ array _ merge < <(SBATCH_HOLD=1 examples/slurm/submit.sh --shards 4 --out "$work/killed" -- "${options[@]}")
scancel "${array}_2"
scontrol release "$array" "$merge" >/dev/null 2>&1 || true
wait_jobs "$array,$merge"
if [ -e "$work/killed/merged/complete" ]; then
  echo "the merge ran although shard 2 was killed" >&2
  exit 1
fi
if [ -e "$work/killed/shards/shard-2/complete" ]; then
  echo "the killed shard 2 is marked complete" >&2
  exit 1
fi
for i in 0 1 3; do
  [ -e "$work/killed/shards/shard-$i/complete" ] || { echo "shard $i did not complete" >&2; exit 1; }
done
# A merge by hand refuses the unfinished shard, naming it.
if "$bin" bench merge "$work"/killed/shards/shard-{0,1,2,3} --out "$work/by-hand" 2>"$work/err"; then
  echo "bench merge accepted an unfinished shard" >&2
  exit 1
fi
grep -q "E7007" "$work/err" && grep -q "shard-2" "$work/err" ||
  { echo "bench merge did not name the unfinished shard 2 with E7007: $(cat "$work/err")" >&2; exit 1; }
echo "killed shard 2: no merge, and bench merge refuses it: $(head -c 200 "$work/err" | tr '\n' ' ')"

# 3. The same submit line again: only shard 2 runs, then the merge.
read -r _ array _ merge < <(examples/slurm/submit.sh --shards 4 --out "$work/killed" -- "${options[@]}")
wait_jobs "$array,$merge"
for i in 0 1 3; do
  grep -q "is complete" "$work/killed/logs/shard-$i.out" ||
    { echo "shard $i ran again" >&2; exit 1; }
done
same_as_local "$work/killed/merged"
echo "Slurm sweep: merge equals one run; a killed shard reruns alone on resubmission"
