#!/usr/bin/env bash
# make bench-farm: how evenly 4 shards split a jobs file, in CPU seconds (machines are shared).
# Each shard runs as its own process with --threads 1, one after another, then one process
# renders the whole file; printed: CPU per shard, max/mean (target <= 1.25) and the shards'
# sum against one process (target <= 1.05).
#
#   scripts/farm/bench_farm.sh [PENUMBRA]      (default build/penumbra)
#   FARM_TODAY=1   split by --shard I/N (no plan file); BENCH_KEEP=1 keeps the temp folder
#   FARM_MAPS=1    a --maps-only prepass builds each photon key once into a map folder the
#                  shards load (--map-dir); its CPU counts in the shards' sum
set -euo pipefail

REPO=$(cd "$(dirname "$0")/../.." && pwd)
PENUMBRA=$(realpath "${1:-$REPO/build/penumbra}")
FARM_TODAY=${FARM_TODAY:-0}
FARM_MAPS=${FARM_MAPS:-0}
SHARDS=4
JOBS_FILE=$REPO/scripts/farm/jobs_file.py
# The test's jobs file, larger (at the test's 64x48 a process's start-up outweighs its renders),
# and a mix: a 12-pass physical job, gate on/off/auto, a 64-frame orbit; each at a small
# size, where a process's fixed costs weigh, and at a farm's. Each: TEMPLATE [ARGS...] of
# jobs_file.py write.
BENCH_FILES=("$REPO/tests/farm/jobs.json.in camera.width=320 camera.height=240 camera.spp=8"
             "$REPO/tests/farm/jobs.json.in camera.width=640 camera.height=480 camera.spp=16"
             "$REPO/scripts/farm/bench_mix.json.in"
             "$REPO/scripts/farm/bench_mix.json.in --scale 2")
today() { [ "$FARM_TODAY" = 1 ]; }

# The arguments that select shard I (0-based) of SHARDS: the one place the split is chosen.
shard_args() {
  if today; then echo "--shard $(($1 + 1))/$SHARDS"; else echo "--shard-file shards.json --shard-index $1 --shard-count $SHARDS"; fi
  [ "$FARM_MAPS" = 1 ] && echo "--map-dir maps" || true
}

# Runs a command in folder DIR with its output in LOG; prints its CPU seconds (user + sys, children included).
cpu_seconds() {
  local dir=$1 log=$2; shift 2
  (cd "$dir" && python3 -c '
import resource, subprocess, sys
rc = subprocess.run(sys.argv[2:], stdout=open(sys.argv[1], "w"), stderr=subprocess.STDOUT).returncode
r = resource.getrusage(resource.RUSAGE_CHILDREN)
print(f"{r.ru_utime + r.ru_stime:.2f}")
sys.exit(rc)' "$log" "$@") || { echo "bench-farm: $* failed in $dir; see $log" >&2; exit 1; }
}

jobs_in() { sed -nE 's/^(shard [^:]*: )?([0-9]+) jobs: .*/\2/p' "$1"; }

bench_file() {
  local template=$1 name dir d i one plan="" maps=0 shard_cpu=() shard_jobs=()
  shift
  name=$(basename "$template" .json.in)
  dir=$(mktemp -d "$B/$name.XXXX")   # one file may be benched at several sizes
  mkdir -p "$dir/shards/out" "$dir/one/out"   # a binary before batch made its output folders
  local flags=()
  today && flags+=(--no-tiles)
  for d in shards one; do
    "$JOBS_FILE" write "$template" "$REPO/scenes" "${flags[@]}" "$@" > "$dir/$d/jobs.json"
  done
  if ! today; then
    plan=$(cpu_seconds "$dir/shards" "$dir/plan.log" "$PENUMBRA" batch jobs.json --plan-shards $SHARDS -o shards.json)
  fi
  if [ "$FARM_MAPS" = 1 ]; then
    maps=$(cpu_seconds "$dir/shards" "$dir/maps.log" "$PENUMBRA" batch jobs.json --threads 1 --maps-only --map-dir maps)
  fi
  for ((i = 0; i < SHARDS; i++)); do
    # shellcheck disable=SC2046
    shard_cpu+=("$(cpu_seconds "$dir/shards" "$dir/shard_$i.log" "$PENUMBRA" batch jobs.json --threads 1 $(shard_args $i))")
    shard_jobs+=("$(jobs_in "$dir/shard_$i.log")")
  done
  one=$(cpu_seconds "$dir/one" "$dir/one.log" "$PENUMBRA" batch jobs.json --threads 1)
  python3 - "${template#"$REPO"/} $*" "$one" "$plan" "${shard_cpu[*]}" "${shard_jobs[*]}" "$(jobs_in "$dir/one.log")" \
    "$START_CPU" "$maps" <<'EOF'
import sys
name, one, plan, cpus, jobs, total, start, maps = sys.argv[1:]
name = name.strip()
cpus = [float(c) for c in cpus.split()]
jobs = jobs.split()
mean = sum(cpus) / len(cpus)
print(f"{name}: {total} jobs")
for i, (c, j) in enumerate(zip(cpus, jobs)):
    print(f"  shard {i}  {j:>3} jobs  {c:7.2f} cpu s")
if float(maps) > 0:
    print(f"  maps prepass    {float(maps):7.2f} cpu s   (counted in the sum)")
print(f"  one process     {float(one):7.2f} cpu s" + (f"   (plan file: {float(plan):.2f} cpu s, once)" if plan else ""))
ratio, overhead = max(cpus) / mean, (sum(cpus) + float(maps)) / float(one)
print(f"  max/mean {ratio:.2f} (target <= 1.25: {'met' if ratio <= 1.25 else 'NOT met'})   "
      f"sum/one {overhead:.2f} (target <= 1.05: {'met' if overhead <= 1.05 else 'NOT met'}; "
      f"start-up alone: {1 + (len(cpus) - 1 + (float(maps) > 0)) * float(start) / float(one):.2f})")
EOF
}

B=$(mktemp -d /tmp/penumbra-bench-farm.XXXXXX)
[ "${BENCH_KEEP:-0}" = 1 ] && echo "bench-farm: keeping $B" || trap 'rm -rf "$B"' EXIT
echo "bench-farm: $SHARDS shards one after another, --threads 1, shard 0 by '$(shard_args 0)'; load $(cut -d' ' -f1 /proc/loadavg) at start"
# What every process pays before any job (its libraries' loading and initialisers).
START_CPU=$(cpu_seconds "$B" "$B/start.log" "$PENUMBRA" --version)
echo "bench-farm: a penumbra process starts in $START_CPU cpu s"
for f in "${BENCH_FILES[@]}"; do
  # shellcheck disable=SC2086
  bench_file $f
done
