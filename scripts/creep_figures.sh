#!/bin/bash
# Does a surface lit only by the global map drift with progressive passes? The mean of
# the ceiling (indirect view) of an area-light room at 1, 2, 4, ..., 64 passes for two
# seeds, against fixed-k passes with ten times the photons (docs/photon-maps.md,
# "Progressive passes"). The room is scenes/cornell_physical.json with its point light
# replaced by a 0.5 m quad under the ceiling, which then sees no direct light.
#
#   scripts/creep_figures.sh build/penumbra [lookup: precomputed|exact] [global photons per pass]
set -euo pipefail
bin=$1
lookup=${2:-precomputed}
global=${3:-500000}
scene=$(dirname "$0")/../scenes/cornell_physical.json
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
room=(--set 'lights[0]={"type":"quad","corner":[-0.25,1.98,-0.25],"edge1":[0.5,0,0],"edge2":[0,0,0.5],"color":[1,1,1],"power":20}'
      --set camera.width=160 --set camera.height=160 --set photons.caustic=1000 --set photons.lookup="$lookup")
ceiling=100x18+30+0  # the ceiling in front of the light, clear of the walls

# Mean of the three channels over the ceiling.
mean() { oiiotool "$1" --cut "$ceiling" --printstats | awk '/Stats Avg/ {printf "%.5f", ($3 + $4 + $5) / 3}'; }

render() {  # render SEED PASSES OUT [more --set ...]
  local seed=$1 passes=$2 file=$3
  shift 3
  "$bin" render "$scene" -q -t 2 --aov indirect --seed "$seed" -o "$file" "${room[@]}" \
    --set photons.passes="$passes" "$@"
}

# The converged value: 8 fixed-k passes of ten times the photons, two other seeds.
sum=0
for seed in 11 12; do
  render "$seed" 8 "$out/ref.exr" --set photons.alpha=1 --set photons.global=$((global * 10)) --set photons.lookup=exact
  sum=$(awk -v a="$sum" -v b="$(mean "$out/ref.exr")" 'BEGIN {print a + b}')
done
ref=$(awk -v s="$sum" 'BEGIN {printf "%.5f", s / 2}')
echo "converged (fixed k, $((global * 10)) photons x 8 passes x 2 seeds): $ref"
echo "lookup $lookup, $global global photons per pass: ceiling mean (difference)"
for seed in 1 2; do
  line="seed $seed:"
  for passes in 1 2 4 8 16 32 64; do
    render "$seed" "$passes" "$out/p.exr" --set photons.global="$global"
    m=$(mean "$out/p.exr")
    line+=$(awk -v m="$m" -v r="$ref" -v p="$passes" 'BEGIN {printf "  %d: %.5f (%+.2f%%)", p, m, 100 * (m / r - 1)}')
  done
  echo "$line"
done
