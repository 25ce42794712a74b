#!/usr/bin/env bash
# scripts/slurm-sweep.sh against a real single-node Slurm (Debian's slurmctld,
# slurmd and munge), started here in a scratch folder with its own ports and
# munge socket, and stopped when the test ends however it ends.
#
# A 4-shard sweep submitted as a job array with a dependent merge must equal
# the same sweep run on one machine, cell for cell: every error, step count and
# evaluation count (the times are measurements and differ). Prints both wall
# times. Needs root (the daemons run as root); without Slurm or root it skips
# (exit 77) saying why, unless GACOMPARE_REQUIRE_SLURM=1 (CI), where a skip is
# a failure: a check never passes on nothing.
#
#   tests/scripts/slurm_test.sh GACOMPARE_BIN SCENE
set -euo pipefail
bin=$(realpath "$1")
scene=$(realpath "$2")
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)

skip() {
  if [ "${GACOMPARE_REQUIRE_SLURM:-0}" = 1 ]; then echo "slurm_test: FAIL: $*" >&2; exit 1; fi
  echo "slurm_test: skipped: $*" >&2
  exit 77
}
for tool in slurmctld slurmd sbatch sinfo munged; do
  command -v "$tool" > /dev/null || [ -x "/usr/sbin/$tool" ] || skip "$tool not installed (scripts/install-deps.sh installs slurmctld, slurmd, slurm-client and munge)"
done
[ "$(id -u)" = 0 ] || skip "the test starts slurmctld, slurmd and munged as root; run it as root"
[ -r /etc/munge/munge.key ] || skip "no munge key (/etc/munge/munge.key; the munge package makes one)"

t=$(mktemp -d /tmp/gacompare_slurm.XXXXXX)
pids=()
cleanup() {
  status=$?
  SLURM_CONF="$t/slurm.conf" scancel --quiet --user=root 2> /dev/null || true
  for p in "${pids[@]}"; do kill "$p" 2> /dev/null || true; done
  for f in "$t"/*.pid; do [ -e "$f" ] && kill "$(cat "$f")" 2> /dev/null || true; done
  sleep 1
  for p in "${pids[@]}"; do kill -9 "$p" 2> /dev/null || true; done
  if [ $status -ne 0 ]; then
    for log in "$t"/*.log "$t"/cluster-shards/*.log; do
      [ -e "$log" ] && { echo "--- $log"; tail -20 "$log"; } >&2
    done
  fi
  rm -rf "$t"
  exit $status
}
trap cleanup EXIT INT TERM

# munged on a private socket, with the package's key.
/usr/sbin/munged --force --socket="$t/munge.sock" --pid-file="$t/munged.pid" --log-file="$t/munged.log" \
  --seed-file="$t/munge.seed" --key-file=/etc/munge/munge.key
host=$(hostname -s)
# Ports away from the defaults (6817/6818), so a Slurm already running here is left alone.
port=$((20000 + $$ % 20000))
node=$(/usr/sbin/slurmd -C | head -1 | sed -e "s/^NodeName=[^ ]*/NodeName=$host NodeAddr=127.0.0.1/" -e 's/ RealMemory=[0-9]*//')
mkdir -p "$t/state" "$t/spool"
cat > "$t/slurm.conf" <<EOF
ClusterName=gacompare
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$t/munge.sock
CredType=cred/munge
StateSaveLocation=$t/state
SlurmdSpoolDir=$t/spool
SlurmctldPidFile=$t/slurmctld.pid
SlurmdPidFile=$t/slurmd.pid
SlurmctldLogFile=$t/slurmctld.log
SlurmdLogFile=$t/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
$node State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP OverSubscribe=YES
EOF
export SLURM_CONF="$t/slurm.conf"
/usr/sbin/slurmctld -D -i > "$t/slurmctld.out" 2>&1 &
pids+=($!)
/usr/sbin/slurmd -D > "$t/slurmd.out" 2>&1 &
pids+=($!)
for _ in $(seq 60); do
  state=$(sinfo -h -o %T 2> /dev/null | head -1 || true)
  [ "$state" = idle ] && break
  sleep 0.5
done
[ "$state" = idle ] || { echo "slurm_test: the node did not come up (state '${state:-none}')" >&2; exit 1; }

# The same small sweep, one machine and four shards on Slurm.
opts=(--repeat 3)
start=$(date +%s%N)
"$bin" sweep "$scene" "${opts[@]}" --quiet --out "$t/single" > /dev/null 2> "$t/single.log"
single=$(( ($(date +%s%N) - start) / 1000000 ))
start=$(date +%s%N)
timeout 600 bash "$root/scripts/slurm-sweep.sh" --shards 4 --wait --gacompare "$bin" --out "$t/cluster" \
  "$scene" "${opts[@]}" > /dev/null 2> "$t/submit.log"
cluster=$(( ($(date +%s%N) - start) / 1000000 ))

python3 - "$t/single" "$t/cluster" <<'EOF'
import json, os, sys
a, b = sys.argv[1], sys.argv[2]
def cells(d):
    out = {}
    for f in sorted(os.listdir(os.path.join(d, "cells"))):
        if f.endswith(".json"):
            j = json.load(open(os.path.join(d, "cells", f)))
            for c in j["cells"]:
                c.pop("seconds", None)  # measured, not computed
            out[f] = j
    return out
x, y = cells(a), cells(b)
if not x:
    sys.exit("slurm_test: the single-machine sweep has no cells")
if sorted(x) != sorted(y):
    sys.exit(f"slurm_test: cells differ: {sorted(set(x) ^ set(y))}")
for f in x:
    if x[f] != y[f]:
        sys.exit(f"slurm_test: {f} differs between the machine and the cluster")
for name in ("sweep.md", "sweep.csv", "sweep.html"):
    if not os.path.exists(os.path.join(b, name)):
        sys.exit(f"slurm_test: the merged sweep has no {name}")
print(f"slurm_test: {len(x)} cells equal, cell for cell")
EOF
echo "slurm_test: one machine ${single} ms; 4 shards on Slurm, submission to merged report, ${cluster} ms"
