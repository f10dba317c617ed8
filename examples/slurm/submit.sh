#!/bin/bash
# Submits a bench sweep to Slurm: N shard tasks (a job array), then the merge, which starts only
# when every shard task succeeded. Run from the repository after `cargo build --release`:
#
#   examples/slurm/submit.sh --shards 16 --out sweep -- --request-limit 10000 --sharing none,pb,fb
#
# Everything after `--` is passed to every shard's `swarmplan bench` (any bench option but
# --shard, --out, --threads). Writes OUT/shards/shard-I (each shard's files), OUT/logs (Slurm's
# output), then OUT/merged (the files of one run of the whole). Run the same line again after a
# failure: shards already complete are not run again, the others are, then the merge.
#
# Resources per shard task, from the environment (defaults fit a 2-CPU node):
#   SWARMPLAN_CPUS (1), SWARMPLAN_MEM (1G), SWARMPLAN_TIME (02:00:00), SWARMPLAN_PARTITION (the
#   cluster's default), SWARMPLAN_BIN (target/release/swarmplan).
# Prints `array <job id> merge <job id>`.
set -euo pipefail
shards=4
out=bench-sweep
while [ $# -gt 0 ]; do
  case "$1" in
    --shards) shards=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --) shift; break ;;
    *) echo "usage: $0 [--shards N] [--out DIR] -- [bench options]" >&2; exit 2 ;;
  esac
done
case "$shards" in ''|*[!0-9]*|0) echo "--shards: give a number of shards >= 1" >&2; exit 2 ;; esac
here=$(cd "$(dirname "$0")" && pwd)
# Slurm opens the output files before the job starts: their folder must exist.
mkdir -p "$out/shards" "$out/logs"
export SWARMPLAN_BIN=${SWARMPLAN_BIN:-target/release/swarmplan}
if [ ! -x "$SWARMPLAN_BIN" ]; then
  echo "$SWARMPLAN_BIN not found: run cargo build --release first, or set SWARMPLAN_BIN" >&2
  exit 2
fi
resources=(--cpus-per-task="${SWARMPLAN_CPUS:-1}" --mem="${SWARMPLAN_MEM:-1G}" --time="${SWARMPLAN_TIME:-02:00:00}")
if [ -n "${SWARMPLAN_PARTITION:-}" ]; then resources+=(--partition="$SWARMPLAN_PARTITION"); fi
array=$(sbatch --parsable --export=ALL "${resources[@]}" --array="0-$((shards - 1))" \
  --output="$out/logs/shard-%a.out" "$here/bench.sbatch" "$out" "$@")
array=${array%%;*}
merge=$(sbatch --parsable --export=ALL "${resources[@]}" --dependency="afterok:$array" \
  --kill-on-invalid-dep=yes --output="$out/logs/merge.out" "$here/merge.sbatch" "$out" "$shards")
merge=${merge%%;*}
echo "array $array merge $merge"
