#!/usr/bin/env bash
# A private single-node Slurm cluster for the tests: munged with its own key and socket, and
# slurmctld and slurmd with a slurm.conf of their own, all in DIR, no systemd, no accounting
# database. Clients find it through SLURM_CONF=DIR/slurm.conf.
# Usage: cluster.sh start DIR | stop DIR | env DIR (prints export SLURM_CONF=...)
#   start: exits 0 when `sinfo` sees the node idle; 77 when slurm-wlm or munge is not installed.
#   stop:  stops the daemons it started (by the PIDs it recorded) and leaves DIR's logs.
set -u
cmd=${1:-} dir=${2:-}
[ -n "$dir" ] || { echo "usage: cluster.sh start|stop|env DIR" >&2; exit 2; }
conf="$dir/slurm.conf"

stop() {
  for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munged.pid"; do
    [ -s "$pidfile" ] || continue
    pid=$(cat "$pidfile")
    kill "$pid" 2>/dev/null
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null
    rm -f "$pidfile"
  done
  [ -s "$dir/munge-dir" ] && [ "$(cat "$dir/munge-dir")" != "$dir/munge" ] && rm -rf "$(cat "$dir/munge-dir")"
  return 0
}

free_port() {  # a TCP port nothing listens on, from the kernel's range
  local p
  for _ in $(seq 50); do
    p=$((20000 + RANDOM % 20000))
    (exec 3<>/dev/tcp/127.0.0.1/$p) 2>/dev/null || { echo "$p"; return; }
  done
  echo 0
}

start() {
  for tool in munged mungekey slurmctld slurmd sinfo sbatch; do
    command -v "$tool" >/dev/null || [ -x "/usr/sbin/$tool" ] || { echo "SKIP: $tool is not installed (slurm-wlm, munge)"; exit 77; }
  done
  export PATH="$PATH:/usr/sbin"
  stop
  rm -rf "$dir" && mkdir -p "$dir"/{state,spool} || exit 1
  # munge's socket path must fit a Unix socket's 108 bytes: a short folder in /tmp when DIR is deep.
  local munge="$dir/munge"
  [ ${#munge} -gt 80 ] && munge=$(mktemp -d /tmp/relief-munge-XXXXXX)
  mkdir -p "$munge" && echo "$munge" > "$dir/munge-dir"
  chmod 0755 "$dir" "$munge"  # munged refuses a folder others cannot enter
  local host; host=$(hostname -s)
  local user; user=$(id -un)
  mungekey -c -k "$munge/munge.key" -b 1024 >/dev/null 2>&1 || dd if=/dev/urandom of="$munge/munge.key" bs=1024 count=1 2>/dev/null
  chmod 0400 "$munge/munge.key"
  munged --socket="$munge/munge.socket" --key-file="$munge/munge.key" --pid-file="$dir/munged.pid" \
         --log-file="$munge/munged.log" --seed-file="$munge/munged.seed" --force \
    || { echo "FAIL: munged did not start"; cat "$munge/munged.log" 2>/dev/null; exit 1; }
  cat > "$conf" <<EOF
ClusterName=relief-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerParameters=batch_sched_delay=0
DependencyParameters=kill_invalid_depend
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.txt
MpiDefault=none
ReturnToService=2
MinJobAge=300
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$conf"
  slurmctld || { echo "FAIL: slurmctld did not start"; tail -20 "$dir/slurmctld.log"; exit 1; }
  slurmd || { echo "FAIL: slurmd did not start"; tail -20 "$dir/slurmd.log"; exit 1; }
  # A deadline, not a count: sinfo waits out its own timeout when slurmctld does not answer.
  local deadline=$((SECONDS + 30)) state=
  while [ "$SECONDS" -lt "$deadline" ]; do
    state=$(timeout 5 sinfo -h -o %T 2>/dev/null | head -1)
    [ "$state" = idle ] && { echo "slurm: node $host idle (SLURM_CONF=$conf)"; exit 0; }
    sleep 0.1
  done
  echo "FAIL: the node is not idle after 30 s (state: ${state:-none})"
  for log in "$dir/slurmctld.log" "$dir/slurmd.log"; do echo "-- $log"; tail -n 10 "$log"; done
  stop; exit 1
}

case "$cmd" in
  start) start ;;
  stop) stop; echo "slurm: stopped" ;;
  env) echo "export SLURM_CONF=$conf" ;;
  *) echo "usage: cluster.sh start|stop|env DIR" >&2; exit 2 ;;
esac
