# slurm.sh - sourced: slurm_up starts a single-node Slurm cluster in $T/slurm (munged,
# slurmctld, slurmd on 127.0.0.1, each under `timeout "${SLURM_LIFE:-120}"`, their PIDs appended to $pids
# for the caller to stop); returns 0 when the node is idle, else 1 with the reason in
# $why. SLURMD_WRAP: a command slurmd runs under (the benchmark's tools/dev/bench/reaper.py).
# Used by tests/sweep/sweep.sh and tools/dev/bench/sweep_bench.sh.
slurm_up() {
    S=$T/slurm why=""
    for c in slurmctld slurmd munged munge sbatch; do
        command -v $c > /dev/null || { why="$c is not installed (sh tools/install-deps.sh)"; return 1; }
    done
    mkdir -p "$S/state" "$S/spool" && chmod 700 "$S"
    head -c 1024 /dev/urandom > "$S/munge.key" && chmod 400 "$S/munge.key"
    timeout "${SLURM_LIFE:-120}" munged -F -f -S "$S/munge.sock" --key-file="$S/munge.key" --log-file="$S/munged.log" \
        --pid-file="$S/munged.pid" --seed-file="$S/munged.seed" > "$S/munged.out" 2>&1 &
    pids="$pids $!"
    port=$((20000 + $$ % 20000))
    cat > "$S/slurm.conf" <<EOF
ClusterName=modrt
SlurmctldHost=localhost(127.0.0.1)
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$S/munge.sock
CredType=cred/munge
StateSaveLocation=$S/state
SlurmdSpoolDir=$S/spool
SlurmctldPidFile=$S/slurmctld.pid
SlurmdPidFile=$S/slurmd.pid
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SchedulerParameters=sched_min_interval=0
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SlurmctldLogFile=$S/slurmctld.log
SlurmdLogFile=$S/slurmd.log
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=sweep Nodes=localhost Default=YES MaxTime=10 State=UP
EOF
    export SLURM_CONF="$S/slurm.conf"
    i=0; while [ ! -S "$S/munge.sock" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
    [ -S "$S/munge.sock" ] || { why="munged did not start: $(tail -1 "$S/munged.out")"; return 1; }
    timeout "${SLURM_LIFE:-120}" slurmctld -D -f "$S/slurm.conf" > "$S/ctld.out" 2>&1 &
    pids="$pids $!"
    ${SLURMD_WRAP:-} timeout "${SLURM_LIFE:-120}" slurmd -D -f "$S/slurm.conf" -N localhost > "$S/d.out" 2>&1 &
    pids="$pids $!"
    i=0; while ! sinfo -h -o %t 2>/dev/null | grep -q idle && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
    sinfo -h -o %t 2>/dev/null | grep -q idle && return 0
    why="the node did not come up within 10 s: $(tail -1 "$S/ctld.out") / $(tail -1 "$S/d.out")"
    return 1
}

# slurm_run SCRIPT: submits an array job and waits until it has left the queue, at most
# SLURM_WAIT polls (default 600, about 60 s); sbatch --wait would poll at growing
# intervals of up to tens of seconds
slurm_run() {
    job=$(sbatch --parsable "$1" 2> "$S/sbatch.err") || { echo "sweep: sbatch: $(cat "$S/sbatch.err")"; return 1; }
    i=0; while [ -n "$(squeue -h -j "$job" 2>/dev/null)" ] && [ $i -lt "${SLURM_WAIT:-600}" ]; do
        sleep 0.1; i=$((i + 1)); done
}
