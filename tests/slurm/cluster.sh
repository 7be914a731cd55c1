#!/usr/bin/env bash
# A private Slurm cluster of several nodes on this host for the tests: munged with its own key and
# socket, slurmctld, and one slurmd a node (n1..nN, each its own port, spool, log and PID file:
# Debian's slurmd runs several nodes on one host, `slurmd -N NAME`), with a slurm.conf of their
# own, all in DIR, no systemd, no accounting database. Tasks are spread over the nodes (CR_LLN:
# the least loaded first), so that a job array runs on several. Clients find it through
# SLURM_CONF=DIR/slurm.conf; a task knows its node by $SLURMD_NODENAME.
# Usage: cluster.sh start DIR [NODES] | stop DIR | env DIR (prints export SLURM_CONF=...)
#   start: NODES nodes (default 3); exits 0 when `sinfo` sees every node idle; 77 when slurm-wlm
#          or munge is not installed.
#   stop:  stops the daemons it started (by the PIDs it recorded) and leaves DIR's logs.
set -u
cmd=${1:-} dir=${2:-} nodes=${3:-3}
[ -n "$dir" ] || { echo "usage: cluster.sh start DIR [NODES] | stop DIR | env DIR" >&2; exit 2; }
case "$nodes" in [1-9]) ;; *) echo "cluster.sh: NODES is 1 to 9, not $nodes" >&2; exit 2 ;; esac
conf="$dir/slurm.conf"

stop() {
  for pidfile in "$dir"/run/slurmd-*.pid "$dir/slurmctld.pid" "$dir/munged.pid"; do
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

taken=" "  # the ports given out so far: each daemon its own, though none listens yet
free_port() {  # sets port: a TCP port nothing listens on and not given out, from 20000-39999
  port=0
  local p
  for _ in $(seq 50); do
    p=$((20000 + RANDOM % 20000))
    [[ "$taken" == *" $p "* ]] && continue
    (exec 3<>/dev/tcp/127.0.0.1/$p) 2>/dev/null || { taken+="$p "; port=$p; return; }
  done
}

start() {
  for tool in munged mungekey slurmctld slurmd sinfo sbatch; do
    command -v "$tool" >/dev/null || [ -x "/usr/sbin/$tool" ] || { echo "SKIP: $tool is not installed (slurm-wlm, munge)"; exit 77; }
  done
  export PATH="$PATH:/usr/sbin"
  stop
  rm -rf "$dir" && mkdir -p "$dir"/{state,run,log} || exit 1
  local k names=()
  for k in $(seq "$nodes"); do names+=("n$k"); mkdir -p "$dir/spool/n$k" || exit 1; done
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
  free_port; local controller=$port
  cat > "$conf" <<EOF
ClusterName=relief-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$controller
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool/%n
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd-%n.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/log/slurmd-%n.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU,CR_LLN
SchedulerParameters=batch_sched_delay=0
DependencyParameters=kill_invalid_depend
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.txt
MpiDefault=none
ReturnToService=2
MinJobAge=300
EOF
  for k in "${names[@]}"; do
    free_port
    echo "NodeName=$k NodeAddr=127.0.0.1 NodeHostname=localhost Port=$port CPUs=$(nproc) State=UNKNOWN" >> "$conf"
  done
  echo "PartitionName=test Nodes=n[1-$nodes] Default=YES MaxTime=INFINITE State=UP" >> "$conf"
  export SLURM_CONF="$conf"
  slurmctld || { echo "FAIL: slurmctld did not start"; tail -20 "$dir/slurmctld.log"; exit 1; }
  for k in "${names[@]}"; do
    slurmd -N "$k" || { echo "FAIL: slurmd -N $k did not start"; tail -20 "$dir/log/slurmd-$k.log"; stop; exit 1; }
  done
  # A deadline, not a count: sinfo waits out its own timeout when slurmctld does not answer.
  local deadline=$((SECONDS + 30)) state=
  while [ "$SECONDS" -lt "$deadline" ]; do
    state=$(timeout 5 sinfo -h -N -o '%N %T' 2>/dev/null | sort | tr '\n' ' ')
    [ "$(xargs -n 2 <<< "$state" | awk '$2 == "idle"' | wc -l)" = "$nodes" ] &&
      { echo "slurm: nodes ${names[*]} idle on $host (SLURM_CONF=$conf)"; exit 0; }
    sleep 0.1
  done
  echo "FAIL: the nodes are not all idle after 30 s (${state:-no answer})"
  for log in "$dir/slurmctld.log" "$dir"/log/slurmd-*.log; do echo "-- $log"; tail -n 10 "$log"; done
  stop; exit 1
}

case "$cmd" in
  start) start ;;
  stop) stop; echo "slurm: stopped" ;;
  env) echo "export SLURM_CONF=$conf" ;;
  *) echo "usage: cluster.sh start|stop|env DIR" >&2; exit 2 ;;
esac
