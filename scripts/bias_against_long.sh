#!/bin/bash
# The photon-map bias of a render against a longer one, measured over many seeds
# (docs/accuracy.md, "Against longer renders"): the mean M of N renders and the mean L
# of K longer renders of other seeds; per pixel (M - L)^2 less the variance of each
# mean (from the spread of its own images) has the squared bias difference as its
# mean. Prints that mean over the image's pixels and channels with its standard error,
# and with --cell (WxH+X+Y, as oiiotool --cut takes it) the part of it in that box.
#
#   scripts/bias_against_long.sh [--cell 32x64+160+192] RENDERS... -- REFERENCES...
set -euo pipefail
cell=
if [ "${1:-}" = --cell ]; then cell=$2; shift 2; fi
renders=() refs=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do renders+=("$1"); shift; done
[ $# -gt 0 ] && shift
refs=("$@")
if [ ${#renders[@]} -lt 2 ] || [ ${#refs[@]} -lt 2 ]; then
  echo "bias_against_long.sh: needs at least two renders and two references" >&2
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

mapfile -t m < <(meanAndVariance M "${renders[@]}")
mapfile -t l < <(meanAndVariance L "${refs[@]}")
excess=(M L --sub --dup --mul M_var --sub L_var --sub)
# Each pixel's excess has a variance of about 2 (M_var + L_var)^2 (a normal spread).
spread=(M_var L_var --add --dup --mul --mulc 2)
# average SCALE: the channels' mean that --printstats printed of an image scaled by
# SCALE (it prints six decimals).
average() { awk -v s="$1" '/Stats Avg/ {printf "%.6e", ($3 + $4 + $5) / (3 * s)}'; }
pixels() { oiiotool --info "$1" | sed -E 's/^[^:]*: *([0-9]+) x +([0-9]+).*/\1 \2/' | awk '{print $1 * $2}'; }

# figure ROI: the squared bias difference over ROI (the whole image: no --cut) as a
# share of the image's mean, and its standard error.
figure() {
  local cut=() n=$total
  if [ -n "${1:-}" ]; then cut=(--cut "$1"); n=$(awk -v c="$1" 'BEGIN {split(c, a, /[x+]/); print a[1] * a[2]}'); fi
  local e v
  e=$(oiiotool "${m[@]}" "${l[@]}" "${excess[@]}" "${cut[@]}" --mulc 1e6 --printstats | average 1e6)
  v=$(oiiotool "${m[@]}" "${l[@]}" "${spread[@]}" "${cut[@]}" --mulc 1e12 --printstats | average 1e12)
  awk -v e="$e" -v v="$v" -v n="$n" -v t="$total" \
    'BEGIN {printf "%.2e +- %.2e", e * n / t, sqrt(v * 3 * n) / (3 * t)}'
}

total=$(pixels "${renders[0]}")
whole=$(figure)
echo "${#renders[@]} renders, ${#refs[@]} references: mean squared bias difference over the image $whole" \
  "(RMSE $(awk -v v="${whole%% *}" 'BEGIN {printf "%.5f", (v > 0 ? sqrt(v) : 0)}'))"
[ -z "$cell" ] || echo "of which in $cell: $(figure "$cell")"
