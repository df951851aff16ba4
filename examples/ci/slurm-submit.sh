#!/bin/sh
# The gate on a Slurm cluster: its shards as an array job (slurm-gate.sbatch), then one job that merges their
# reports once every shard has ended, however it ended. Usage: slurm-submit.sh SHARDS; prints the merge's job id.
set -eu
shards=${1:-4}
here=$(cd "$(dirname "$0")" && pwd)
array=$(sbatch --parsable --array="1-${shards}" "${here}/slurm-gate.sbatch")
sbatch --parsable --dependency="afterany:${array}" --job-name=hpsf-gate-merge --output=merge.log \
  --wrap "\"${HPSF:-hpsf}\" check --merge shard-* --junit gate.xml --html gate.html"
