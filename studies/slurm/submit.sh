#!/usr/bin/env bash
# Submits a granasym study to Slurm: a job array of SHARDS shards
# (paper.sbatch) and the merge (merge.sbatch) that runs once all of them have
# ended, succeeded or not (afterany: it names the shards that did not
# finish and then exits 3). Prints both job ids.
#
#   [SHARDS=8] [SCALE=paper] [OUT=DIR] [PROGRAMME=FILE] [GRANASYM=PATH] \
#     studies/slurm/submit.sh [SBATCH_OPTION...]
#
# SBATCH_OPTIONs (--partition=..., --account=..., --time=..., --cpus-per-task=...)
# go to both sbatch calls and override the #SBATCH defaults of the scripts;
# the array size is SHARDS, not an option. Defaults: PROGRAMME
# studies/programmes/paper.toml and GRANASYM build/app/granasym of this
# repository (else granasym from PATH), SCALE paper, OUT study-paper-SCALE in
# the current directory, which must be on a file system every node sees. JOBS
# and THREADS are passed on to paper.sbatch (see there), REPORT (1: calibrate,
# figures and report after the merge; 0: only the state table) to merge.sbatch. Job logs
# (slurm-granasym-*.out) go to the current directory.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"

for option in "$@"; do
  case "$option" in
    --array* | -a*) echo "error: the array size is SHARDS=N, not $option" >&2; exit 2 ;;
  esac
done
shards="${SHARDS:-8}"
if ! [[ "$shards" =~ ^[1-9][0-9]*$ ]]; then
  echo "error: SHARDS=$shards is not a positive number of shards" >&2
  exit 2
fi
scale="${SCALE:-paper}"
case "$scale" in
  tiny | small | medium | paper) ;;
  *) echo "error: SCALE=$scale is not one of tiny, small, medium, paper" >&2; exit 2 ;;
esac
programme="$(realpath -m "${PROGRAMME:-$root/studies/programmes/paper.toml}")"
[ -f "$programme" ] || { echo "error: no programme file $programme (PROGRAMME)" >&2; exit 2; }
out="$(realpath -m "${OUT:-$PWD/study-paper-$scale}")"
granasym="${GRANASYM:-}"
if [ -z "$granasym" ]; then
  if [ -x "$root/build/app/granasym" ]; then
    granasym="$root/build/app/granasym"
  else
    granasym="$(command -v granasym || true)"
  fi
fi
[ -n "$granasym" ] || { echo "error: no granasym program: build it or set GRANASYM" >&2; exit 2; }
granasym="$(realpath -m "$granasym")"
[ -x "$granasym" ] || { echo "error: $granasym is not executable (GRANASYM)" >&2; exit 2; }
mkdir -p "$out"

export PROGRAMME="$programme" SCALE="$scale" OUT="$out" GRANASYM="$granasym" SHARDS="$shards"
# --parsable prints "ID" or "ID;CLUSTER".
shards_job="$(sbatch --parsable --export=ALL --array="0-$((shards - 1))" "$@" \
  "$here/paper.sbatch")"
shards_job="${shards_job%%;*}"
echo "shards job $shards_job: $shards array tasks of $programme, scale $scale, into $out"
merge_job="$(sbatch --parsable --export=ALL --dependency="afterany:$shards_job" "$@" \
  "$here/merge.sbatch")"
merge_job="${merge_job%%;*}"
echo "merge job $merge_job: after every task of job $shards_job has ended (it names the shards" \
     "that did not finish)"
