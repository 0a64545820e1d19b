#!/bin/sh
# SPDX-License-Identifier: MIT
# tools/cluster/slurm-local.sh: runs a command with a single-node Slurm of its
# own on loopback (Debian packages slurm-wlm and munge), to try the cluster
# recipes without a cluster; tests/cli/test_slurm.sh runs the README's Slurm
# example on it.
#
# usage: tools/cluster/slurm-local.sh COMMAND [ARG...]
#
# It starts munged (a fresh key), slurmctld and slurmd (node "hynode", one
# partition "hy" of this machine's CPUs), runs COMMAND with SLURM_CONF
# exported (sbatch, squeue, scancel, scontrol use this Slurm), then cancels
# what is left, stops the daemons and removes their directory: config, keys,
# sockets, state, spool and logs all live in one temporary directory under
# $TMPDIR (or /tmp).  Nothing of an installed Slurm or munge is used or
# touched (/etc/slurm, /etc/munge, their ports and sockets).
# As root it runs in new network, UTS and PID namespaces (unshare): only a
# loopback interface exists, so the daemons can be reached on 127.0.0.1 only
# (slurmctld has no bind-address setting of its own), any port is free, and
# when the command ends every process left in the namespace is killed.
# Otherwise it runs as the current user on free ports, and the daemons listen
# on every address of those ports (slurmctld has no bind-address setting;
# every request still needs this run's munge key).
# SLURM_LOCAL_KEEP=1 keeps the directory (its path printed) for a look at the logs.
#
# Exit status: COMMAND's; 1 if the daemons did not come up within their
# deadlines (their logs printed); 2 for a usage error.
set -u
me=$(cd "$(dirname "$0")" && pwd)/$(basename "$0")
say() { echo "slurm-local: $*" >&2; }

# ---- outer: the directory, the namespaces, the cleanup -----------------------
if [ "${1:-}" != --inner ]; then
    if [ $# -lt 1 ] || [ "$1" = -h ] || [ "$1" = --help ]; then
        sed -n '7p' "$0" | sed 's/^# //' >&2
        exit 2
    fi
    for p in munged slurmctld slurmd sbatch squeue scontrol; do
        command -v "$p" > /dev/null || PATH=$PATH:/usr/sbin:/sbin
        command -v "$p" > /dev/null || { say "$p not found: install slurm-wlm and munge (Debian: apt-get install slurm-wlm munge)"; exit 1; }
    done
    dir=$(mktemp -d "${TMPDIR:-/tmp}/hystviz-slurm.XXXXXX") || exit 1
    # munged's socket path must fit in sun_path (108 bytes)
    if [ ${#dir} -gt 80 ]; then
        rmdir "$dir"
        dir=$(mktemp -d /tmp/hystviz-slurm.XXXXXX) || exit 1
    fi
    cleanup() {
        if [ "${SLURM_LOCAL_KEEP:-0}" = 1 ]; then say "kept $dir"; else rm -rf "$dir"; fi
    }
    trap cleanup EXIT
    trap 'exit 130' INT
    trap 'exit 143' TERM
    chmod 755 "$dir"   # munged: its socket's directory must be searchable by all
    ns=
    if [ "$(id -u)" -eq 0 ] && command -v ip > /dev/null &&
        unshare --net --uts --pid --fork --mount-proc --kill-child true 2> /dev/null; then
        ns="unshare --net --uts --pid --fork --mount-proc --kill-child"
    else
        say "not root (or no unshare/ip): the daemons run in this machine's network; slurmctld listens on all addresses"
    fi
    # not exec: the trap removes the directory after the namespace is gone
    $ns sh "$me" --inner "$dir" "${ns:+ns}" "$@"
    exit $?
fi

# ---- inner: daemons up, the command, daemons down ----------------------------
dir=$2
inns=$3
shift 3
munged_pid= ctld_pid= slurmd_pid=
tail_logs() {
    for f in "$dir"/munged.log "$dir"/slurmctld.out "$dir"/slurmctld.log "$dir"/slurmd.out "$dir"/slurmd.log; do
        [ -s "$f" ] && { echo "---- $f (last 40 lines)"; tail -n 40 "$f"; }
    done >&2
}
alive() { [ -n "$1" ] && kill -0 "$1" 2> /dev/null; }
# every client call bounded: a dead controller would make it retry for long
cli() { timeout 10 "$@"; }
stop_all() {
    if alive "$ctld_pid" && alive "$slurmd_pid"; then
        cli scancel --quiet -u "$(id -un)" 2> /dev/null
        end=$(($(date +%s) + 15))   # the jobs' processes gone, then the daemons
        while [ "$(date +%s)" -lt $end ] && [ -n "$(cli squeue -h -o %i 2> /dev/null)" ]; do sleep 0.2; done
    fi
    for p in $slurmd_pid $ctld_pid $munged_pid; do kill "$p" 2> /dev/null; done
    end=$(($(date +%s) + 10))
    for p in $slurmd_pid $ctld_pid $munged_pid; do
        while alive "$p" && [ "$(date +%s)" -lt $end ]; do sleep 0.1; done
        kill -9 "$p" 2> /dev/null
        wait "$p" 2> /dev/null
    done
    munged_pid= ctld_pid= slurmd_pid=
}
trap 'stop_all' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
# wait_for WHAT SECONDS PID COMMAND...: polls COMMAND until it succeeds; when
# the daemon PID has died or the deadline has passed, prints the daemons'
# logs and exits 1
wait_for() {
    what=$1 end=$(($(date +%s) + $2)) pid=$3
    shift 3
    until "$@" > /dev/null 2>&1; do
        if ! alive "$pid"; then
            say "$what did not start (it exited); the daemons' logs:"
            tail_logs
            exit 1
        fi
        if [ "$(date +%s)" -ge $end ]; then
            say "$what did not come up within the deadline; the daemons' logs:"
            tail_logs
            exit 1
        fi
        sleep 0.2
    done
}

host=$(hostname -s 2> /dev/null || hostname)
if [ -n "$inns" ]; then
    # lo up; a second address on it: getaddrinfo(AI_ADDRCONFIG), which
    # slurmctld uses for its listening socket, finds no IPv4 with 127.0.0.1 alone
    ip link set lo up && ip addr add 10.254.254.1/32 dev lo ||
        { say "cannot set up the loopback interface of the network namespace"; exit 1; }
    # a host name of its own, resolved by an /etc/hosts of the namespace
    # (slurmd binds to what its host name resolves to: 127.0.0.1)
    host=hyslurm
    printf '127.0.0.1 localhost %s\n' "$host" > "$dir/hosts"
    hostname "$host" && mount --bind "$dir/hosts" /etc/hosts ||
        { say "cannot set the namespace's host name"; exit 1; }
    cport=6817 dport=6818
    # slurmd binds to what the host name resolves to (127.0.0.1), not to any address
    bind=CommunicationParameters=NoInAddrAny
else
    bind="# slurmd on every address: the host name may resolve to another one"
    # two free ports: bound by the kernel to port 0, then released
    ports=$(python3 -c 'import socket
s=[socket.socket() for _ in range(2)]
[x.bind(("127.0.0.1",0)) for x in s]
print(*[x.getsockname()[1] for x in s])' 2> /dev/null) || ports="$((20000 + $$ % 20000)) $((20001 + $$ % 20000))"
    cport=${ports% *} dport=${ports#* }
fi
user=$(id -un)
mkdir -p "$dir/state" "$dir/spool" "$dir/run"
# a munge key of this run only
dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 2> /dev/null && chmod 600 "$dir/munge.key" ||
    { say "cannot write the munge key"; exit 1; }
sock=$dir/run/munge.sock
munged -F --origin=127.0.0.1 --socket="$sock" --key-file="$dir/munge.key" --pid-file="$dir/run/munged.pid" \
    --seed-file="$dir/state/munged.seed" --log-file="$dir/munged.log" > "$dir/munged.log" 2>&1 &
munged_pid=$!
munge_ok() { munge -n -S "$sock" | unmunge -S "$sock"; }
wait_for munged 20 "$munged_pid" munge_ok

ncpu=$(nproc)
: > "$dir/plugstack.conf"
cat > "$dir/slurm.conf" << EOF
# written by tools/cluster/slurm-local.sh: a single node on loopback
ClusterName=hystviz-local
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$cport
SlurmdPort=$dport
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$sock
CredType=cred/munge
$bind
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
PlugStackConfig=$dir/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MailProg=/bin/true
ReturnToService=2
SlurmdParameters=config_overrides
KillWait=2
MessageTimeout=5
NodeName=hynode NodeHostname=localhost NodeAddr=127.0.0.1 CPUs=$ncpu State=UNKNOWN
PartitionName=hy Nodes=hynode Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -D -f "$SLURM_CONF" > "$dir/slurmctld.out" 2>&1 &
ctld_pid=$!
wait_for slurmctld 30 "$ctld_pid" cli scontrol ping
slurmd -D -N hynode -f "$SLURM_CONF" > "$dir/slurmd.out" 2>&1 &
slurmd_pid=$!
node_idle() { [ "$(cli sinfo -h -n hynode -o %T)" = idle ]; }
wait_for "slurmd (node hynode idle)" 30 "$slurmd_pid" node_idle

"$@"
rc=$?
stop_all
exit $rc
