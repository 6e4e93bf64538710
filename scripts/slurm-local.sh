#!/usr/bin/env bash
# A single-node Slurm on this machine, for `clothode sweep run --engine
# slurm` and its test (README "Sweeps"): Debian's slurm-wlm and munge,
# started directly (no systemd), with a generated slurm.conf that gives
# the one node this machine's cores and memory.
#
#   scripts/slurm-local.sh start [STATE_DIR]   start munged, slurmctld, slurmd
#   scripts/slurm-local.sh stop  [STATE_DIR]   stop them again
#   scripts/slurm-local.sh status [STATE_DIR]  whether the node takes jobs
#
# STATE_DIR (default /tmp/clothode-slurm) holds slurm.conf, the daemons'
# state, logs and pid files.  `start` prints the line to give the Slurm
# commands the configuration:  export SLURM_CONF=STATE_DIR/slurm.conf
# Needs root (the daemons run as root, SlurmUser=root).
set -euo pipefail
cmd=${1:-}
state=${2:-/tmp/clothode-slurm}
conf=$state/slurm.conf

fail() { echo "slurm-local: $*" >&2; exit 1; }

write_conf() {
    local host cpus mem
    host=$(hostname -s)
    cpus=$(nproc)
    # RealMemory in MB, a little below the total so that slurmd accepts it
    mem=$(awk '/^MemTotal:/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)
    mkdir -p "$state"/{ctld,d,log}
    cat > "$conf" <<EOF
ClusterName=clothode
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=${SLURM_LOCAL_PORT:-16817}
SlurmdPort=$(( ${SLURM_LOCAL_PORT:-16817} + 1 ))
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/d
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
MaxArraySize=100001
MaxJobCount=100000
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}

# munged, unless one already answers on the default socket
start_munge() {
    if munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
        return
    fi
    mkdir -p /run/munge /var/log/munge /var/lib/munge
    chown munge:munge /run/munge /var/log/munge /var/lib/munge
    [[ -r /etc/munge/munge.key ]] || fail "no /etc/munge/munge.key"
    runuser -u munge -- /usr/sbin/munged ||
        fail "munged did not start (see /var/log/munge/munged.log)"
    for _ in $(seq 50); do
        munge -n 2>/dev/null | unmunge >/dev/null 2>&1 && return
        sleep 0.1
    done
    fail "munged does not answer"
}

node_up() {
    SLURM_CONF=$conf sinfo -h -o %t 2>/dev/null | grep -Eq '^(idle|mix|alloc)'
}

start() {
    [[ $(id -u) -eq 0 ]] || fail "needs root"
    for p in slurmctld slurmd munged; do
        command -v "$p" >/dev/null || [[ -x /usr/sbin/$p ]] ||
            fail "$p not installed (apt-get install slurm-wlm munge)"
    done
    stop_daemons 2>/dev/null || true
    write_conf
    start_munge
    SLURM_CONF=$conf /usr/sbin/slurmctld -f "$conf" ||
        fail "slurmctld did not start ($state/log/slurmctld.log)"
    SLURM_CONF=$conf /usr/sbin/slurmd -f "$conf" ||
        fail "slurmd did not start ($state/log/slurmd.log)"
    for _ in $(seq 100); do
        if node_up; then
            echo "export SLURM_CONF=$conf"
            return
        fi
        sleep 0.2
    done
    SLURM_CONF=$conf scontrol update nodename="$(hostname -s)" \
        state=resume >/dev/null 2>&1 || true
    node_up || fail "the node did not come up ($state/log/)"
    echo "export SLURM_CONF=$conf"
}

# The daemons of this STATE_DIR, by their pid files (munged is left
# running: other Slurm or munge users may share it).
stop_daemons() {
    local pid
    for d in slurmd slurmctld; do
        [[ -f $state/$d.pid ]] || continue
        pid=$(cat "$state/$d.pid")
        kill "$pid" 2>/dev/null || continue
        for _ in $(seq 100); do
            kill -0 "$pid" 2>/dev/null || break
            sleep 0.1
        done
        kill -KILL "$pid" 2>/dev/null || true  # still there after 10 s
        rm -f "$state/$d.pid"
    done
}

case $cmd in
start) start ;;
stop) stop_daemons ;;
status) node_up && echo "up" || { echo "down"; exit 1; } ;;
*) fail "usage: scripts/slurm-local.sh start|stop|status [STATE_DIR]" ;;
esac
