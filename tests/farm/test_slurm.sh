#!/usr/bin/env bash
# make test-slurm: a jobs file rendered on a real single-node Slurm cluster (a maps prepass, a
# 4-task array, a dependent tile merge) against one `penumbra batch` process, byte for byte.
#
#   tests/farm/test_slurm.sh [PENUMBRA]       (default build/penumbra)
#   FARM_TODAY=1   a binary before the plan file: shards by `--shard I/N` only (no maps prepass, tiles, merge or --status)
#   FARM_KEEP=1    keep the temp folder (it is kept anyway when an assertion fails)
set -uo pipefail

REPO=$(cd "$(dirname "$0")/../.." && pwd)
PENUMBRA=$(realpath "${1:-$REPO/build/penumbra}")
FARM_TODAY=${FARM_TODAY:-0}
SHARDS=4
WAIT_SECONDS=300          # per sbatch --wait: Slurm polls, so allow for 30 s after the last task
TEMPLATE=$REPO/tests/farm/jobs.json.in
JOBS_FILE=$REPO/scripts/farm/jobs_file.py
APPENDED=$REPO/scenes/fig07_glass_in_box.json   # a scene no other job renders
TILE_JOB=tiled            # the jobs file's "tiles": 4 job
# The parts of the tile job (out/NAME.tileIofN.exr), expanded by the merge task's shell.
TILE_PARTS="out/${TILE_JOB}.tile*of4.exr"
MERGED=merged/$TILE_JOB.png

source "$REPO/scripts/farm/slurm_cluster.sh"

PASSED=0 FAILED=0 SKIPPED=0
ok() { echo "test-slurm: ok: $*"; PASSED=$((PASSED + 1)); }
bad() { echo "test-slurm: FAIL: $*"; FAILED=$((FAILED + 1)); }
skip() { echo "test-slurm: skipped: $*"; SKIPPED=$((SKIPPED + 1)); }
today() { [ "$FARM_TODAY" = 1 ]; }

# ---- the jobs files

# Writes DIR/jobs.json from the template: shipped scenes by absolute path, outputs relative to DIR,
# so the reference and the farm write the same stamps into different folders.
write_jobs() {
  local dir=$1
  mkdir -p "$dir/merged"   # batch makes the jobs file's out/; merge writes into an existing folder
  local flags=()
  today && flags+=(--no-tiles)
  "$JOBS_FILE" write "$TEMPLATE" "$REPO/scenes" "${flags[@]}" > "$dir/jobs.json"
}

# ---- Slurm submissions (every task runs in the farm folder; its log is logs/LABEL_TASK.out)

# The command one array task runs: the shard selection in one place.
shard_command() {
  if today; then
    echo "$PENUMBRA batch jobs.json --threads 1 --shard \$((SLURM_ARRAY_TASK_ID + 1))/$SHARDS"
  else
    echo "$PENUMBRA batch jobs.json --threads 1 --shard-file shards.json --shard-index env --shard-count $SHARDS --map-dir $MAPS"
  fi
}

# LABEL SBATCH-ARGS...: sets JOB_ID. sbatch runs in the background and is waited for, so Ctrl-C
# or SIGTERM reaches the trap at once (bash defers a trap until a foreground command ends).
submit() {
  local label=$1 rc; shift
  timeout --foreground "$WAIT_SECONDS" sbatch --parsable --job-name="$label" --chdir="$FARM" --time=15 \
    --output="$T/logs/${label}_%a.out" "$@" > "$T/logs/$label.id" &
  SUBMIT_PID=$!
  wait "$SUBMIT_PID"; rc=$?
  SUBMIT_PID=""
  JOB_ID=$(cat "$T/logs/$label.id")
  return "$rc"
}

# Sums over every log of LABEL the number sed expression EXPR takes from its last matching line.
sum_logs() {
  local label=$1 expr=$2 f n total=0
  for f in "$T/logs/${label}"_*.out; do
    n=$(sed -nE "$expr" "$f" | tail -n 1)
    [ -n "$n" ] || { echo "no summary line in $f" >&2; echo "?"; return 1; }
    total=$((total + n))
  done
  echo "$total"
}
# The batch summary's totals line (src/cli/batch_command.cpp: batchSummary).
rendered_in() { sum_logs "$1" 's/^(shard [^:]*: )?[0-9]+ jobs: ([0-9]+) rendered.*/\2/p'; }
maps_built_in() { sum_logs "$1" 's/.*photon maps built ([0-9]+).*/\1/p'; }

# Every task Slurm finished (the jobcomp file) completed with exit code 0; else names the
# others, with the last lines of the logs of those that failed (not merely cancelled).
all_tasks_completed() {
  local failed name
  failed=$(grep -v 'JobState=COMPLETED .*ExitCode=0:0' "$T/cluster/log/jobcomp.log" || true)
  [ -z "$failed" ] && return 0
  echo "$failed" | sed -E 's/.*(JobId=[^ ]+) .*(Name=[^ ]+) (JobState=[^ ]+).* (ExitCode=[^ ]+).*/  \1 \2 \3 \4/'
  for name in $(echo "$failed" | grep -v 'JobState=CANCELLED' | sed -E 's/.* Name=([^ ]+) .*/\1/' | sort -u); do
    tail -n 3 "$T/logs/${name}"_*.out 2>/dev/null
  done
  return 1
}

# ---- the runs

reference_run() {
  (cd "$REF" && "$PENUMBRA" batch jobs.json > "$T/logs/reference_0.out" 2>&1) ||
    cluster_fail "the one-process batch failed: $(tail -n 5 "$T/logs/reference_0.out")"
  REF_MAPS=$(maps_built_in reference)
}

# The submit host plans the split; a maps prepass, the array after it, the merge after the array.
farm_run() {
  local prepass array
  if today; then
    submit shards --array=0-$((SHARDS - 1)) --wait --wrap "$(shard_command)"
  else
    (cd "$FARM" && "$PENUMBRA" batch jobs.json --plan-shards $SHARDS -o shards.json > "$T/logs/plan.out" 2>&1) ||
      cluster_fail "--plan-shards failed: $(tail -n 3 "$T/logs/plan.out")"
    submit maps --wrap "$PENUMBRA batch jobs.json --threads 1 --maps-only --map-dir $MAPS" ||
      cluster_fail "sbatch refused the maps prepass"
    prepass=$JOB_ID
    submit shards --array=0-$((SHARDS - 1)) --dependency=afterok:"$prepass" --wrap "$(shard_command)" ||
      cluster_fail "sbatch refused the array"
    array=$JOB_ID
    submit merge --dependency=afterok:"$array" --wait --wrap "$PENUMBRA merge $TILE_PARTS -o $MERGED"
  fi
  local why
  why=$(all_tasks_completed) || cluster_fail "tasks did not complete:
$why
logs: $T/logs"
}

# ---- the assertions

# Byte for byte; an EXR (the tile parts) but for the DateTime OpenImageIO stamps on every
# write: the same pixels (idiff) and every other header field.
same_file() {
  cmp -s "$1" "$2" && return 0
  case $1 in *.exr) ;; *) return 1 ;; esac
  idiff -fail 0 -warn 0 "$1" "$2" > /dev/null 2>&1 &&
    diff <(iinfo -v "$1" | grep -v -e DateTime -e "^$1") <(iinfo -v "$2" | grep -v -e DateTime -e "^$2") > /dev/null
}

assert_outputs_equal() {
  local listed f n=0 differ=()
  listed=$(diff <(cd "$REF/out" && find . -type f | sort) <(cd "$FARM/out" && find . -type f | sort))
  [ -z "$listed" ] || { bad "the farm and one process wrote different files:
$listed"; return; }
  while read -r f; do
    n=$((n + 1))
    same_file "$REF/out/$f" "$FARM/out/$f" || differ+=("$f")
  done < <(cd "$REF/out" && find . -type f | sort)
  if [ ${#differ[@]} -eq 0 ] && [ "$n" -ge 12 ]; then
    ok "$n outputs byte-identical to one process"
  else
    bad "$n outputs, differing from one process: ${differ[*]:-none} (at least 12 expected)"
  fi
}

assert_maps_built_once() {
  local prepass shards farm
  shards=$(maps_built_in shards)
  if today; then
    skip "photon maps: $shards built across the shards against $REF_MAPS in one process (no --map-dir yet)"
    return
  fi
  prepass=$(maps_built_in maps) && [ "$shards" != "?" ] || { bad "photon maps: a prepass or shard log has no summary"; return; }
  farm=$((prepass + shards))
  [ "$farm" = "$REF_MAPS" ] && ok "photon maps built across the farm: $farm, as in one process" ||
    bad "photon maps built across the farm: $farm (prepass + shards), one process: $REF_MAPS"
}

# penumbra batch --status in the farm folder; sets STATUS_RC and STATUS_OUT.
run_status() {
  STATUS_OUT=$(cd "$FARM" && "$PENUMBRA" batch jobs.json --status --shard-file shards.json 2>&1)
  STATUS_RC=$?
}

assert_status_clean() {
  if today; then skip "--status (FARM_TODAY=1: a binary before the plan file)"; return; fi
  run_status
  [ "$STATUS_RC" = 0 ] && ok "--status exits 0 after the farm run" ||
    bad "--status exits $STATUS_RC after the farm run:
$STATUS_OUT"
}

# The jobs (every name of the expanded jobs file, from --list-shard 1/1) whose line in
# STATUS_OUT says missing; totals lines name no job, so they do not count.
missing_jobs() {
  local name
  (cd "$FARM" && "$PENUMBRA" batch jobs.json --list-shard 1/1 | cut -f1) | while read -r name; do
    grep -w -- "$name" <<< "$STATUS_OUT" | grep -qw missing && echo "$name"
  done
}

# One appended job: --status lists it alone as missing, and a second array renders it alone.
assert_append_renders_one() {
  local missing rendered
  if today; then
    # Without per-job stamps a newer jobs file makes every output stale: keep its time.
    touch -r "$FARM/jobs.json" "$T/jobs.mtime"
    "$JOBS_FILE" append "$FARM/jobs.json" "$APPENDED"
    touch -r "$T/jobs.mtime" "$FARM/jobs.json"
    skip "--status after appending a job (FARM_TODAY=1: a binary before the plan file)"
  else
    # The split is kept: a job the shard file does not name goes to its least-loaded shard.
    "$JOBS_FILE" append "$FARM/jobs.json" "$APPENDED"
    run_status
    missing=$(missing_jobs)
    if [ "$missing" = "$(basename "$APPENDED" .json)" ] && [ "$STATUS_RC" != 0 ] && [ "$STATUS_RC" != 2 ]; then
      ok "--status after appending a job: 1 missing ($missing), exit $STATUS_RC"
    else
      bad "--status after appending a job: missing '${missing//$'\n'/ }', exit $STATUS_RC (want the appended job alone, and an exit code neither 0 nor 2):
$STATUS_OUT"
    fi
  fi
  submit again --array=0-$((SHARDS - 1)) --wait --wrap "$(shard_command)"
  local why
  why=$(all_tasks_completed) || { bad "the second array's tasks did not complete:
$why"; return; }
  rendered=$(rendered_in again)
  [ "$rendered" = 1 ] && ok "a second array after appending a job renders exactly 1 job" ||
    bad "a second array after appending a job rendered $rendered jobs, not 1 (logs: $T/logs/again_*.out)"
}

# The merged tile frame equals the whole frame rendered by one process.
assert_tiles_merge_whole() {
  if today; then skip "tiles and merge (FARM_TODAY=1: a binary before the plan file)"; return; fi
  # The same job untiled, by one process, into the same relative output: the same stamp.
  mkdir -p "$T/whole"
  "$JOBS_FILE" untile "$FARM/jobs.json" "$TILE_JOB" > "$T/whole/jobs.json"
  (cd "$T/whole" && "$PENUMBRA" batch jobs.json -q) || { bad "the whole-frame batch of $TILE_JOB failed"; return; }
  local whole=$T/whole/out/$TILE_JOB.png
  if cmp -s "$whole" "$FARM/$MERGED"; then
    ok "4 tiles merged by a dependent task equal the whole frame"
  else
    # Say whether the pixels or only the metadata differ (idiff: openimageio-tools, make deps).
    local pixels="the pixels differ too"
    idiff -fail 0 "$whole" "$FARM/$MERGED" > /dev/null 2>&1 && pixels="same pixels, other metadata"
    bad "the merged $MERGED differs from the whole frame $whole ($pixels)"
  fi
}

# ---- main

# Stops the daemons, then prints the closing count (a run cut short by an error counts as a failure).
cleanup() {
  local rc=$?
  [ -n "${SUBMIT_PID:-}" ] && kill "$SUBMIT_PID" 2>/dev/null
  cluster_stop
  [ "$rc" != 0 ] && [ "$FAILED" = 0 ] && FAILED=1
  if [ "$FAILED" = 0 ] && [ "${FARM_KEEP:-0}" != 1 ]; then rm -rf "$T"; else echo "test-slurm: kept $T"; fi
  echo "test-slurm: $((SECONDS - START)) s"
  echo "test-slurm: $PASSED passed, $FAILED failed, $SKIPPED skipped"
  [ "$FAILED" = 0 ] || exit 1
}

main() {
  if ! cluster_is_debian; then
    echo "test-slurm: skipped: not a Debian machine (it needs Debian's slurm-wlm and munge packages)"
    exit 0
  fi
  [ -x "$PENUMBRA" ] || cluster_fail "no penumbra binary at $PENUMBRA (make renderer)"
  START=$SECONDS
  T=$(mktemp -d /tmp/penumbra-slurm.XXXXXX) && chmod 711 "$T"
  REF=$T/reference FARM=$T/farm MAPS=$T/maps
  mkdir -p "$T/logs" "$MAPS"
  trap cleanup EXIT
  trap 'FAILED=$((FAILED + 1)); exit 130' INT TERM HUP
  today && echo "test-slurm: FARM_TODAY=1: shards by --shard I/$SHARDS"
  cluster_install
  cluster_start "$T/cluster"
  write_jobs "$REF"
  write_jobs "$FARM"
  reference_run
  farm_run
  assert_outputs_equal
  assert_maps_built_once
  assert_status_clean
  assert_tiles_merge_whole
  assert_append_renders_one
  [ "$FAILED" = 0 ]
}

main "$@"
