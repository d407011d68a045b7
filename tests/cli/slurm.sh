#!/usr/bin/env bash
# tessera farm slurm on a real Slurm cluster of one node, started here: munged, slurmctld and slurmd from Debian with a
# generated slurm.conf on 127.0.0.1 (their own key, socket, ports and state in the scratch folder; the machine's own
# Slurm or MUNGE, if any, are not touched). The job array renders tiles of an animated scene, the dependent job
# stitches them and encodes a GIF, and every frame must equal a local render byte for byte; a resubmission finds
# everything done. Exits 77 (skipped) only when Slurm cannot run here: not installed, or not root; a daemon that is
# installed but does not start fails the test.
set -euo pipefail
tessera="$1"
scratch="$2"
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"
scratch=$(pwd)
skip() { echo "SKIP: $*"; exit 77; }
fail() {
  echo "FAIL: $*"
  for log in cluster/log/*.log out/slurm/logs/*.log; do [ -f "$log" ] && { echo "== $log"; tail -n 20 "$log"; }; done
  exit 1
}

for tool in munged mungekey slurmctld slurmd sbatch squeue scontrol; do
  command -v "$tool" > /dev/null || skip "$tool is not installed (Debian: slurm-wlm munge)"
done
[ "$(id -u)" = 0 ] || skip "slurmd starts jobs as their users, so it runs as root; this test is not root"

# --- a one-node cluster -----------------------------------------------------------------------------------------
mkdir -p cluster/state cluster/spool cluster/log
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2> /dev/null || true; done
  for pidfile in cluster/slurmctld.pid cluster/slurmd.pid cluster/munged.pid; do
    [ -f "$pidfile" ] && kill "$(cat "$pidfile")" 2> /dev/null || true
  done
}
trap cleanup EXIT
mungekey -c -k "$scratch/cluster/munge.key"
munged -f -S "$scratch/cluster/munge.sock" --key-file="$scratch/cluster/munge.key" \
  --log-file="$scratch/cluster/log/munged.log" --pid-file="$scratch/cluster/munged.pid" \
  --seed-file="$scratch/cluster/munged.seed" || fail "munged does not start"
host=$(hostname -s)
port=$((20000 + RANDOM % 20000))
cat > cluster/slurm.conf <<CONF
ClusterName=tessera-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$scratch/cluster/munge.sock
StateSaveLocation=$scratch/cluster/state
SlurmdSpoolDir=$scratch/cluster/spool
SlurmctldPidFile=$scratch/cluster/slurmctld.pid
SlurmdPidFile=$scratch/cluster/slurmd.pid
SlurmctldLogFile=$scratch/cluster/log/slurmctld.log
SlurmdLogFile=$scratch/cluster/log/slurmd.log
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
ReturnToService=2
MpiDefault=none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
MinJobAge=600
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=tessera Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$scratch/cluster/slurm.conf"
slurmctld -c -f "$SLURM_CONF" || fail "slurmctld does not start"
slurmd -f "$SLURM_CONF" || fail "slurmd does not start"
for ((i = 0; i < 60; i++)); do
  sinfo -h -o %T 2> /dev/null | grep -q idle && break
  sleep 1
done
sinfo -h -o %T | grep -q idle || fail "the node never became idle: $(sinfo 2>&1)"

# Waits until the jobs given leave the queue (at most 5 minutes), then checks that each completed.
wait_jobs() {
  for ((i = 0; i < 300; i++)); do
    [ -z "$(squeue -h -j "$(IFS=,; echo "$*")" 2> /dev/null)" ] && break
    sleep 1
  done
  for job in "$@"; do
    state=$(scontrol show job "$job" | grep -o 'JobState=[A-Z]*' | sort -u)
    [ "$state" = "JobState=COMPLETED" ] || fail "job $job ended as: $state"
  done
}

# --- frames 0..5 of the moving Whitted scene, two tiles each, stitched and encoded by the follow-up job -------------
"$tessera" farm slurm whitted-moving --frames 0:5 --tiles 2 -o out/f_%04d.png --size 64x48 --spp 2 \
  --movie out/movie.gif --cpus-per-task 1 --partition tessera --time 00:10:00 --submit --stats > submit.txt
grep -q '^tasks=12$' submit.txt || fail "$(cat submit.txt)"
render_job=$(sed -n 's/^render_job=//p' submit.txt)
assemble_job=$(sed -n 's/^assemble_job=//p' submit.txt)
[ -n "$render_job" ] && [ -n "$assemble_job" ] || fail "no job ids: $(cat submit.txt)"
wait_jobs "$render_job" "$assemble_job"

"$tessera" render whitted-moving --frames 0:5 -o local/f_%04d.png --size 64x48 --spp 2 --quiet
for f in 0 1 2 3 4 5; do
  cmp "out/f_000$f.png" "local/f_000$f.png" || fail "frame $f from the cluster differs from the local render"
done
/usr/bin/python3 -c "
from PIL import Image; im = Image.open('out/movie.gif'); n = 1
while True:
    try: im.seek(im.tell() + 1); n += 1
    except EOFError: break
assert n == 6, n"
"$tessera" farm status out/f_%04d.png --frames 0:5 --tiles 2 --stats > status.txt
grep -q '^done=12$' status.txt && grep -q '^missing=0$' status.txt || fail "status: $(cat status.txt)"

# --- a resubmission skips everything; a lost tile is rendered again and the frame re-stitched ----------------------
rm out/f_0003.tile-1-of-2.png out/f_0003.png
"$tessera" farm status out/f_%04d.png --frames 0:5 --tiles 2 --stats | grep -q '^missing=1$' || fail "status misses a tile"
"$tessera" farm slurm whitted-moving --frames 0:5 --tiles 2 -o out/f_%04d.png --size 64x48 --spp 2 --cpus-per-task 1 \
  --submit --stats > resubmit.txt
wait_jobs "$(sed -n 's/^render_job=//p' resubmit.txt)" "$(sed -n 's/^assemble_job=//p' resubmit.txt)"
cmp out/f_0003.png local/f_0003.png || fail "the re-rendered frame differs"
skipped=$(cat out/slurm/logs/render-"$(sed -n 's/^render_job=//p' resubmit.txt)"_*.log | grep -c -- '-> ' || true)
[ "$skipped" = 1 ] || fail "the resubmission rendered $skipped parts, expected 1"

# --- whole frames, three per task --------------------------------------------------------------------------------
"$tessera" farm slurm whitted-moving --frames 0:7 --frames-per-task 3 -o runs/f_%04d.png --size 64x48 --spp 2 \
  --submit --stats > runs.txt
grep -q '^tasks=3$' runs.txt || fail "$(cat runs.txt)"
wait_jobs "$(sed -n 's/^render_job=//p' runs.txt)"
for f in 0 1 2 3 4 5; do cmp "runs/f_000$f.png" "local/f_000$f.png" || fail "runs: frame $f differs"; done
test -s runs/f_0007.png && test ! -e runs/f_0008.png
echo "slurm: ok"
