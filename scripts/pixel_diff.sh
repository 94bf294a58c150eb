#!/usr/bin/env bash
# Renders every scene in scenes/ with two penumbra binaries and compares the pixels
# with OIIO's idiff (not cmp: EXR headers carry metadata that may differ): each
# scene at 160x100 in every view of its model, and at its own size.
# Usage: scripts/pixel_diff.sh OLD_BINARY NEW_BINARY OUT_DIR   (exit 1 on any difference)
set -uo pipefail
old=$1 new=$2 out=$3
cd "$(dirname "$0")/.."
mkdir -p "$out/old" "$out/new"
status=0
for scene in scenes/*.json; do
  name=$(basename "$scene" .json)
  model=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1])).get('render', {}).get('model', 'classic'))" "$scene")
  views="beauty depth normal indirect"
  [ "$model" = physical ] && views="$views direct caustic"
  runs=()
  for v in $views; do runs+=("${name}_${v}.exr|--aov $v --set camera.width=160 --set camera.height=100"); done
  runs+=("${name}_full.exr|")
  for run in "${runs[@]}"; do
    file=${run%%|*} args=${run#*|}
    for side in old new; do
      bin=$old; [ $side = new ] && bin=$new
      # shellcheck disable=SC2086
      "$bin" render "$scene" -o "$out/$side/$file" -q -t 2 $args || { echo "FAILED: $side $file"; status=1; }
    done
    if ! idiff -fail 0 -warn 0 "$out/old/$file" "$out/new/$file" > /dev/null 2>&1; then
      echo "DIFFERS: $file"; status=1
    fi
  done
done
[ $status = 0 ] && echo "pixel_diff: every image identical ($(ls "$out/new" | wc -l) images)"
exit $status
