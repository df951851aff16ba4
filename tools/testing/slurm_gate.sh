#!/usr/bin/env bash
# examples/ci/slurm-submit.sh on a real one-node Slurm (Debian's slurm-wlm and munge), started here and stopped on
# exit: the gate's shards run as an array job, the merge as a job that depends on it, and the merged JUnit report
# equals the unsharded run's, times aside. The daemons run as root (slurmd must), so does this test.
# Usage: slurm_gate.sh HPSF SOURCE OUT
set -euo pipefail
hpsf=$1 source=$2 out=$3
for tool in munged slurmctld slurmd sbatch squeue sinfo; do
  command -v "$tool" > /dev/null || { echo "slurm_gate: $tool is missing (scripts/install-deps.sh installs it)" >&2; exit 1; }
done
[[ $(id -u) -eq 0 ]] || { echo "slurm_gate: slurmd runs as root; run this test as root" >&2; exit 1; }

rm -rf "$out" && mkdir -p "$out"/{state,spool,log,run}
cleanup() {
  for pid in "$out"/slurmd.pid "$out"/slurmctld.pid "$out"/munged.pid; do
    [[ -f $pid ]] && kill "$(cat "$pid")" 2> /dev/null || true
  done
}
trap cleanup EXIT

munged --force --socket="$out/munge.socket" --key-file=/etc/munge/munge.key --pid-file="$out/munged.pid" \
  --log-file="$out/log/munged.log" --seed-file="$out/munged.seed"
host=$(hostname -s)
port=$((20000 + RANDOM % 20000))
cat > "$out/slurm.conf" << CONF
ClusterName=hpsf-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$out/munge.socket
CredType=cred/munge
StateSaveLocation=$out/state
SlurmdSpoolDir=$out/spool
SlurmctldPidFile=$out/slurmctld.pid
SlurmdPidFile=$out/slurmd.pid
SlurmctldLogFile=$out/log/slurmctld.log
SlurmdLogFile=$out/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=hpsf Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$out/slurm.conf
slurmctld -c -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 60); do
  sinfo -h -o %t 2> /dev/null | grep -q idle && break
  sleep 0.5
done
sinfo -h -o %t | grep -q idle || { echo "slurm_gate: the node never came up" >&2; cat "$out"/log/*.log >&2; exit 1; }

# A small gate: five cases over three shards.
cat > "$out/run/gate.json" << 'GATE'
{
  "hpsf_gate": 1,
  "name": "slurm",
  "crosscheck": {
    "scenes": ["cornell"], "size": "16x16", "spp": 1, "seeds": [1, 2],
    "configs": {"roomy": {}, "crowded": {"capacity": 256, "probe-limit": 4, "fingerprint-bits": 8}},
    "backends": {"emulated": {"backend": "emulated"}}
  },
  "statistics": {"scenes": ["cornell"], "size": "16x16", "spp": 1}
}
GATE
cd "$out/run"
export HPSF=$hpsf GATE=$out/run/gate.json
merge=$("$source/examples/ci/slurm-submit.sh" 3)
for _ in $(seq 240); do
  [[ -z $(squeue -h) ]] && break
  sleep 0.5
done
[[ -z $(squeue -h) ]] || { echo "slurm_gate: jobs still queued after 120 s" >&2; squeue >&2; exit 1; }
for shard in 1 2 3; do
  [[ -f shard-$shard/check.json ]] || { echo "slurm_gate: shard $shard left no report" >&2; cat gate-*.log >&2; exit 1; }
done
[[ -f gate.xml ]] || { echo "slurm_gate: merge job $merge left no report" >&2; cat merge.log >&2; exit 1; }

# The same gate unsharded: its JUnit report equals the merged one but for the times.
"$hpsf" check "$GATE" --out whole --junit whole.xml > whole.log
untimed() { sed -E 's/ time="[0-9.]+"//g' "$1"; }
if ! diff <(untimed gate.xml) <(untimed whole.xml); then
  echo "slurm_gate: the merged JUnit report differs from the unsharded one" >&2
  exit 1
fi
grep -q 'tests="5"' gate.xml || { echo "slurm_gate: the merged JUnit report does not hold 5 cases" >&2; exit 1; }
echo "slurm_gate: 3 shards as array job $((merge - 1)), merged by job $merge: the unsharded report, case for case"
