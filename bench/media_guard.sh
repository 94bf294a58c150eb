#!/bin/sh
# The media guard: every shipped scene without a medium renders the same pixels and
# the same --stats counts (rays, photons, operations) as a baseline binary.
# Usage: bench/media_guard.sh BASELINE_PENUMBRA NEW_PENUMBRA [OUTDIR]
set -eu
base=$1; new=$2; out=${3:-/tmp/${USER:-penumbra}-media-guard}
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out/base" "$out/new"
status=0
for scene in "$root"/scenes/*.json; do
  name=$(basename "$scene" .json)
  # The 1M-triangle benchmark scenes take minutes to tessellate; media scenes differ by design.
  case $name in teapot_1m|soft_shadows_dense) continue ;; esac
  grep -q '"media"' "$scene" && continue
  for side in base new; do
    bin=$base; [ $side = new ] && bin=$new
    # The baseline's outputs are kept: a second run against another build reuses them.
    [ $side = base ] && [ -s "$out/base/$name.json" ] && continue
    "$bin" render "$scene" -o "$out/$side/$name.exr" -t 2 -q -D camera.width=160 -D camera.height=100 \
      --stats "$out/$side/$name.json" >/dev/null 2>&1 || { echo "$name: $side render failed"; status=1; }
  done
  if ! oiiotool --diff "$out/base/$name.exr" "$out/new/$name.exr" >/dev/null 2>&1; then
    echo "$name: pixels differ"; status=1
  fi
  python3 - "$out/base/$name.json" "$out/new/$name.json" "$name" <<'PY' || status=1
import json, sys
# Counts only: times, CPU shares, memory and reasons may move between runs or builds.
KEYS = ["rays", "photons", "gate", "gather", "lookup", "numeric", "image", "passes", "media"]
def counts(path):
    j = json.load(open(path))
    return {k: j.get(k) for k in KEYS}
a, b = counts(sys.argv[1]), counts(sys.argv[2])
bad = [k for k in KEYS if a[k] != b[k]]
for k in bad:
    print(f"{sys.argv[3]}: --stats {k} differs: {a[k]} vs {b[k]}")
sys.exit(1 if bad else 0)
PY
done
[ $status = 0 ] && echo "media guard: every scene without a medium matches (pixels and counts)"
exit $status
