#!/usr/bin/env bash
# Renders every scene in scenes/ with two penumbra binaries and compares the pixels
# with OIIO's idiff (not cmp: EXR headers carry metadata that may differ): each
# scene at 160x100 in every view of its model, and at its own size; the plan of
# every scene and view (`plan --json`, byte for byte); a small sweep (its rows
# without the time columns, and each run's image); and a two-job batch.
# Usage: scripts/pixel_diff.sh OLD_BINARY NEW_BINARY OUT_DIR   (exit 1 on any difference)
# PIXEL_DIFF_FULL=0 leaves out the renders at each scene's own size; PIXEL_DIFF_REUSE_OLD=1
# keeps the old binary's outputs already in OUT_DIR/old (the same baseline checked again).
set -uo pipefail
old=$(realpath "$1") new=$(realpath "$2") out=$3
full=${PIXEL_DIFF_FULL:-1}
reuse=${PIXEL_DIFF_REUSE_OLD:-0}
cd "$(dirname "$0")/.."
mkdir -p "$out/old" "$out/new"
out=$(realpath "$out")
small="--set camera.width=160 --set camera.height=100"
status=0
images=0
same_image() {  # same_image FILE: the old and new renders of FILE hold the same pixels
  images=$((images + 1))
  if ! idiff -fail 0 -warn 0 "$out/old/$1" "$out/new/$1" > /dev/null 2>&1; then
    echo "DIFFERS: $1"; status=1
  fi
}
bin_of() { if [ "$1" = new ]; then echo "$new"; else echo "$old"; fi; }

for scene in scenes/*.json; do
  name=$(basename "$scene" .json)
  model=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1])).get('render', {}).get('model', 'classic'))" "$scene")
  views="beauty depth normal indirect error"
  [ "$model" = physical ] && views="$views direct caustic"
  runs=()
  for v in $views; do runs+=("${name}_${v}.exr|--aov $v $small"); done
  [ "$full" = 1 ] && runs+=("${name}_full.exr|")
  for run in "${runs[@]}"; do
    file=${run%%|*} args=${run#*|}
    for side in old new; do
      [ $side = old ] && [ "$reuse" = 1 ] && [ -s "$out/old/$file" ] && [ -s "$out/old/${file%.exr}.plan.json" ] && continue
      # shellcheck disable=SC2086
      "$(bin_of $side)" render "$scene" -o "$out/$side/$file" -q -t 2 $args || { echo "FAILED: $side $file"; status=1; }
      # The plan decides the passes before any pixel: a changed decision shows here first.
      # shellcheck disable=SC2086
      "$(bin_of $side)" plan --json "$scene" $args > "$out/$side/${file%.exr}.plan.json" 2>&1 ||
        { echo "FAILED: $side plan ${file%.exr}"; status=1; }
    done
    same_image "$file"
    cmp -s "$out/old/${file%.exr}.plan.json" "$out/new/${file%.exr}.plan.json" ||
      { echo "DIFFERS: plan of ${file%.exr}"; status=1; }
  done
done

# A sweep: four runs sharing one emission; its rows must agree but for the clock.
for side in old new; do
  [ $side = old ] && [ "$reuse" = 1 ] && [ -s "$out/old/sweep_rows.csv" ] && continue
  rm -rf "$out/$side/sweep"
  # shellcheck disable=SC2086
  "$(bin_of $side)" sweep scenes/soft_shadows.json -o "$out/$side/sweep" $small --photons 1e4,2e4 --k 20,50 -q -t 2 ||
    { echo "FAILED: $side sweep"; status=1; }
  python3 - "$out/$side/sweep/results.csv" > "$out/$side/sweep_rows.csv" <<'EOF'
import csv, sys
timed = lambda c: c.endswith("_s") or c in ("cpu_share", "load_avg_1m")
rows = list(csv.reader(open(sys.argv[1])))
keep = [i for i, c in enumerate(rows[0]) if not timed(c)]
for r in rows:
    print(",".join(r[i] for i in keep))
EOF
done
cmp -s "$out/old/sweep_rows.csv" "$out/new/sweep_rows.csv" || { echo "DIFFERS: sweep results.csv"; status=1; }
for f in "$out"/new/sweep/runs/*.exr "$out"/new/sweep/reference.exr; do
  same_image "sweep/${f#"$out"/new/sweep/}"
done

# A batch of two jobs: a physical scene's layered views and a gated classic one.
for side in old new; do
  [ $side = old ] && [ "$reuse" = 1 ] && [ -s "$out/old/batch/gate.exr" ] && continue
  mkdir -p "$out/$side/batch"
  cat > "$out/$side/batch/jobs.json" <<EOF
{"set": ["camera.width=160", "camera.height=100"],
 "jobs": [{"scene": "$PWD/scenes/cornell_physical.json", "views": ["beauty", "caustic", "depth"], "output": "cornell.exr"},
          {"scene": "$PWD/scenes/fig11_gate_shadows.json", "output": "gate.exr"}]}
EOF
  "$(bin_of $side)" batch "$out/$side/batch/jobs.json" --force -q -t 2 || { echo "FAILED: $side batch"; status=1; }
done
same_image batch/cornell.exr
same_image batch/gate.exr

[ $status = 0 ] && echo "pixel_diff: every image ($images) and plan identical"
exit $status
