# shellcheck shell=bash
# A private single-node Slurm cluster (munged, slurmctld, slurmd) for tests: sourced, not run.
# Everything it writes lives in one temp folder; it stops exactly the daemons it started, by PID.
#
#   source scripts/farm/slurm_cluster.sh
#   cluster_install            # Debian's slurm-wlm and munge, only when missing
#   cluster_start DIR          # writes DIR/slurm.conf, starts the daemons, waits for the node
#                              # (the munge user must be able to reach DIR: chmod 711 its parents)
#   ...sbatch/sinfo...         # SLURM_CONF points at DIR/slurm.conf
#   cluster_stop               # cancels our jobs, stops slurmd, slurmctld, munged (also from a trap)

CLUSTER_PKGS="slurm-wlm slurm-client munge"
CLUSTER_DIR=""
CLUSTER_NODE=""
CLUSTER_PIDS=()   # "name:pid", in start order; stopped in reverse

cluster_say() { echo "test-slurm: $*"; }
cluster_fail() { echo "test-slurm: FAIL: $*" >&2; exit 1; }

# 0 on Debian (where the packages come from), 1 elsewhere.
cluster_is_debian() { [ -r /etc/debian_version ] && command -v apt-get >/dev/null && command -v dpkg-query >/dev/null; }

# Installs those of CLUSTER_PKGS that are missing, as the Makefile's deps target does.
cluster_install() {
  local p missing=() sudo=""
  [ "$(id -u)" = 0 ] || sudo=sudo
  for p in $CLUSTER_PKGS; do
    dpkg-query -W -f='${Status}\n' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  cluster_say "installing missing packages: ${missing[*]}"
  # The packages try to start their services; without systemd policy-rc.d refuses, which is harmless.
  $sudo apt-get update -qq &&
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" ||
    cluster_fail "could not install ${missing[*]}"
}

# Two TCP ports free right now, so a cluster never meets another one on the default 6817/6818.
cluster_free_ports() {
  python3 -c 'import socket
s=[socket.socket() for _ in range(2)]
[x.bind(("", 0)) for x in s]
print(*[x.getsockname()[1] for x in s])'
}

cluster_write_conf() {
  local d=$1 node=$2 ctld_port=$3 slurmd_port=$4 node_line
  # slurmd -C measures the node (CPUs, sockets, memory); a node configured larger than it is gets drained.
  node_line=$(slurmd -C | sed -n 's/^NodeName=/NodeName=/p')
  [ -n "$node_line" ] || cluster_fail "slurmd -C printed no NodeName line"
  cat > "$d/slurm.conf" <<EOF
ClusterName=penumbra
SlurmctldHost=$node
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$d/munge/munge.socket
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/log/slurmctld.log
SlurmdLogFile=$d/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
DependencyParameters=kill_invalid_depend
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/filetxt
JobCompLoc=$d/log/jobcomp.log
SlurmctldTimeout=30
SlurmdTimeout=30
$node_line State=UNKNOWN
PartitionName=debug Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
}

# Starts one daemon in the foreground of a background job, so $! is the daemon itself.
cluster_spawn() {
  local name=$1; shift
  "$@" > "$CLUSTER_DIR/log/$name.out" 2>&1 < /dev/null &
  CLUSTER_PIDS+=("$name:$!")
}

cluster_pid() {
  local e
  for e in "${CLUSTER_PIDS[@]}"; do [ "${e%%:*}" = "$1" ] && echo "${e#*:}"; done
}

cluster_dead_daemon() {
  local e
  for e in "${CLUSTER_PIDS[@]}"; do
    kill -0 "${e#*:}" 2>/dev/null || { echo "${e%%:*}"; return 0; }
  done
  return 1
}

cluster_start() {
  CLUSTER_DIR=$1
  CLUSTER_NODE=$(hostname -s)
  local ports dead i state
  mkdir -p "$CLUSTER_DIR"/{munge,state,spool,log}
  chmod 711 "$CLUSTER_DIR"   # munged runs as munge and must reach its own folder
  setpriv --reuid=munge --regid=munge --init-groups test -x "$CLUSTER_DIR" ||
    cluster_fail "the munge user cannot reach $CLUSTER_DIR (chmod 711 its parent folders)"
  read -r -a ports <<< "$(cluster_free_ports)"
  cluster_write_conf "$CLUSTER_DIR" "$CLUSTER_NODE" "${ports[0]}" "${ports[1]}"
  export SLURM_CONF=$CLUSTER_DIR/slurm.conf

  # munged refuses a key or socket folder others may write; the key is this cluster's own.
  chown munge:munge "$CLUSTER_DIR/munge" && chmod 700 "$CLUSTER_DIR/munge" ||
    cluster_fail "cannot give $CLUSTER_DIR/munge to the munge user (run as root)"
  setpriv --reuid=munge --regid=munge --init-groups mungekey -c -k "$CLUSTER_DIR/munge/munge.key" ||
    cluster_fail "mungekey could not write $CLUSTER_DIR/munge/munge.key"
  chmod 711 "$CLUSTER_DIR/munge"   # clients (slurmctld, slurmd, jobs) reach the socket by name
  cluster_spawn munged setpriv --reuid=munge --regid=munge --init-groups /usr/sbin/munged -F \
    --socket="$CLUSTER_DIR/munge/munge.socket" --key-file="$CLUSTER_DIR/munge/munge.key" \
    --pid-file="$CLUSTER_DIR/munge/munged.pid" --log-file="$CLUSTER_DIR/munge/munged.log" \
    --seed-file="$CLUSTER_DIR/munge/munged.seed"
  for i in $(seq 50); do [ -S "$CLUSTER_DIR/munge/munge.socket" ] && break; cluster_dead_daemon >/dev/null && break; sleep 0.1; done
  [ -S "$CLUSTER_DIR/munge/munge.socket" ] ||
    cluster_fail "munged did not start; $(tail -n 3 "$CLUSTER_DIR/munge/munged.log" "$CLUSTER_DIR/log/munged.out" 2>/dev/null)"

  cluster_spawn slurmctld /usr/sbin/slurmctld -D -i -f "$SLURM_CONF"
  cluster_spawn slurmd /usr/sbin/slurmd -D -f "$SLURM_CONF"
  # The node is usable once it reports idle; a daemon that exits meanwhile is a failure, not a skip.
  for i in $(seq 120); do
    if dead=$(cluster_dead_daemon); then
      cluster_fail "$dead exited at start; last lines of $CLUSTER_DIR/log/$dead.log:
$(tail -n 15 "$CLUSTER_DIR/log/$dead.log" "$CLUSTER_DIR/log/$dead.out" 2>/dev/null)"
    fi
    state=$(sinfo -h -n "$CLUSTER_NODE" -o %T 2>/dev/null) && [ "$state" = idle ] && break
    sleep 0.5
  done
  [ "$state" = idle ] || cluster_fail "node $CLUSTER_NODE is '${state:-unreachable}' after 60 s, not idle; see $CLUSTER_DIR/log"
  cluster_say "cluster up: node $CLUSTER_NODE, ports ${ports[*]}, pids ${CLUSTER_PIDS[*]}, folder $CLUSTER_DIR"
}

# Cancels this cluster's jobs, then stops its daemons (slurmd, slurmctld, munged) by PID.
cluster_stop() {
  local i e name pid ids=""
  [ ${#CLUSTER_PIDS[@]} -eq 0 ] && return 0
  # Only this cluster's controller is asked (SLURM_CONF), and only while it runs.
  kill -0 "$(cluster_pid slurmctld)" 2>/dev/null && ids=$(timeout 10 squeue -h -o %A 2>/dev/null | sort -u)
  if [ -n "$ids" ]; then
    timeout 10 scancel $ids 2>/dev/null
    for _ in $(seq 20); do [ -z "$(timeout 10 squeue -h -o %A 2>/dev/null)" ] && break; sleep 0.5; done
  fi
  for ((i = ${#CLUSTER_PIDS[@]} - 1; i >= 0; i--)); do
    e=${CLUSTER_PIDS[i]}; name=${e%%:*}; pid=${e#*:}
    kill -0 "$pid" 2>/dev/null || continue
    kill -TERM "$pid" 2>/dev/null
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -0 "$pid" 2>/dev/null && { echo "test-slurm: $name (pid $pid) ignored SIGTERM, killing it" >&2; kill -KILL "$pid" 2>/dev/null; }
    wait "$pid" 2>/dev/null
  done
  cluster_say "stopped ${CLUSTER_PIDS[*]}"
  CLUSTER_PIDS=()
}
