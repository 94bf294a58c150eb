#!/usr/bin/env bash
# Times two bench_render binaries in turns (old, new, old, new, ...) on the scene and
# control rows, and prints each row's median real and CPU time with the change.
# Usage: scripts/bench_pair.sh OLD_BENCH_RENDER NEW_BENCH_RENDER [ROUNDS=3] [FILTER]
set -euo pipefail
old=$(realpath "$1") new=$(realpath "$2") rounds=${3:-3} filter=${4:-'BM_(Scene|Control)'}
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for r in $(seq "$rounds"); do
  for side in old new; do
    bin=$old; [ $side = new ] && bin=$new
    "$bin" --benchmark_filter="$filter" --benchmark_format=json > "$tmp/$side-$r.json" 2>/dev/null
  done
done
python3 - "$tmp" "$rounds" <<'PY'
import json, statistics, sys
tmp, rounds = sys.argv[1], int(sys.argv[2])
rows = {}
for side in ("old", "new"):
    for r in range(1, rounds + 1):
        for b in json.load(open(f"{tmp}/{side}-{r}.json"))["benchmarks"]:
            rows.setdefault(b["name"], {}).setdefault(side, []).append((b["real_time"], b["cpu_time"]))
print(f"{'row (median of %d, ms)' % rounds:56s} {'old real':>9s} {'new real':>9s} {'change':>7s} {'old cpu':>9s} {'new cpu':>9s} {'change':>7s}")
for name, sides in rows.items():
    med = lambda side, i: statistics.median(x[i] for x in sides[side])
    o, n, oc, nc = med("old", 0), med("new", 0), med("old", 1), med("new", 1)
    print(f"{name:56s} {o:9.1f} {n:9.1f} {100 * (n / o - 1):+6.1f}% {oc:9.1f} {nc:9.1f} {100 * (nc / oc - 1):+6.1f}%")
PY
