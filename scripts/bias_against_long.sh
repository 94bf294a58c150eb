#!/bin/bash
# The photon-map bias of a render against a longer one, measured over many seeds
# (docs/accuracy.md, "Against longer renders"): per pixel (M - L)^2 less each mean's
# variance, where M is the mean of the renders and L of the longer ones (other seeds).
#
#   scripts/bias_against_long.sh [--cell 32x64+160+192] [--groups 8] RENDERS... -- REFERENCES...
#
# Prints the mean of that over the image's pixels and channels (the squared bias
# difference as an image's mean), and with --cell (WxH+X+Y, as oiiotool --cut takes
# it) the part inside that box and the part outside, each with a jackknife standard
# error: over groups of the renders and over the references one at a time, since
# neighbouring pixels share photons and are not independent.
set -euo pipefail
cell='' groups=8
while [ $# -gt 0 ]; do
  case $1 in
    --cell) cell=$2; shift 2 ;;
    --groups) groups=$2; shift 2 ;;
    *) break ;;
  esac
done
renders=() refs=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do renders+=("$1"); shift; done
[ $# -gt 0 ] && shift
refs=("$@")
if [ ${#renders[@]} -lt $((2 * groups)) ] || [ ${#refs[@]} -lt 3 ]; then
  echo "bias_against_long.sh: needs at least $((2 * groups)) renders and three references" >&2
  exit 2
fi

# oiiotool arguments that leave on the stack the mean of the files (labelled $1) and
# the variance of that mean ($1_var).
meanAndVariance() {
  local label=$1
  shift
  local n=$# args=() first=1
  for f in "$@"; do
    args+=("$f" --ch "R,G,B")
    [ $first = 1 ] || args+=(--add)
    first=0
  done
  args+=(--divc "$n" --label "$label")
  first=1
  for f in "$@"; do
    args+=("$f" --ch "R,G,B" --dup --mul)
    [ $first = 1 ] || args+=(--add)
    first=0
  done
  # var(mean) = (mean of squares - square of mean) / (n - 1)
  args+=(--divc "$n" "$label" "$label" --mul --sub --divc $((n - 1)) --label "${label}_var")
  printf '%s\n' "${args[@]}"
}

pixels() { oiiotool --info "$1" | sed -E 's/^[^:]*: *([0-9]+) x +([0-9]+).*/\1 \2/' | awk '{print $1 * $2}'; }
total=$(pixels "${renders[0]}")
cellShare=0
[ -z "$cell" ] || cellShare=$(awk -v c="$cell" -v t="$total" 'BEGIN {split(c, a, /[x+]/); print a[1] * a[2] / t}')

# estimate RENDERS... -- REFERENCES...: "whole inside outside", each as a share of the
# image's mean (--printstats prints six decimals, so the image is scaled by 1e6).
estimate() {
  local r=() l=()
  while [ "$1" != -- ]; do r+=("$1"); shift; done
  shift
  l=("$@")
  local mArgs lArgs cut=()
  mapfile -t mArgs < <(meanAndVariance M "${r[@]}")
  mapfile -t lArgs < <(meanAndVariance L "${l[@]}")
  [ -z "$cell" ] || cut=(--cut "$cell" --printstats)
  oiiotool "${mArgs[@]}" "${lArgs[@]}" M L --sub --dup --mul M_var --sub L_var --sub --mulc 1e6 --printstats "${cut[@]}" |
    awk -v s="$cellShare" '/Stats Avg/ {v[n++] = ($3 + $4 + $5) / 3e6}
      END {inside = n > 1 ? v[1] * s : 0; printf "%.6e %.6e %.6e\n", v[0], inside, v[0] - inside}'
}

full=$(estimate "${renders[@]}" -- "${refs[@]}")
replicates=()
for ((g = 0; g < groups; ++g)); do
  kept=()
  for i in "${!renders[@]}"; do ((i % groups == g)) || kept+=("${renders[$i]}"); done
  replicates+=("R $(estimate "${kept[@]}" -- "${refs[@]}")")
done
for i in "${!refs[@]}"; do
  kept=("${refs[@]:0:i}" "${refs[@]:i+1}")
  replicates+=("L $(estimate "${renders[@]}" -- "${kept[@]}")")
done

# Jackknife: (n - 1) / n times the sum of squared deviations from the replicates' mean,
# for the renders' groups and the references' in turn, added.
printf '%s\n' "${replicates[@]}" | awk -v full="$full" -v g="$groups" -v k="${#refs[@]}" \
  -v nr="${#renders[@]}" -v hasCell="${cell:+1}" -v cell="$cell" '
  { for (j = 2; j <= 4; ++j) { sum[$1, j] += $j; sq[$1, j] += $j * $j }; count[$1]++ }
  END {
    split(full, f, " ")
    names[2] = "over the image"; names[3] = "inside " cell; names[4] = "outside it"
    printf "%d renders, %d references: squared bias difference as the image'"'"'s mean\n", nr, k
    for (j = 2; j <= (hasCell ? 4 : 2); ++j) {
      var = 0
      for (s in count) {
        n = count[s]; m = sum[s, j] / n
        var += (n - 1) / n * (sq[s, j] - n * m * m)
      }
      v = f[j - 1]
      printf "  %-28s %10.2e +- %.2e  (RMSE %.5f)\n", names[j], v, sqrt(var > 0 ? var : 0), (v > 0 ? sqrt(v) : 0)
    }
  }'
