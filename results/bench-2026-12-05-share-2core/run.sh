#!/usr/bin/env bash
# The main job end to end with several builds side by side, interleaved rounds: wall, user and
# system seconds of each run (`/usr/bin/time`), the medians of wall. Usage (from the repository
# root):  results/bench-2026-12-05-share-2core/run.sh ROUNDS VARIANTS BINARY...
# VARIANTS is --variants (per point; 2500 = 20,000 flights of ballast_sweep.toml), or 0 for
# the scenario's own 500 (4,000 flights).
set -euo pipefail
rounds=$1; variants=$2; shift 2
tmp=$(mktemp -d)
args=(scenarios/ballast_sweep.toml --quiet)
[ "$variants" != 0 ] && args+=(--variants "$variants")
for r in $(seq "$rounds"); do
  for b in "$@"; do
    /usr/bin/time -f "%e %U %S" -o "$tmp/t" "$b" "${args[@]}" --out "$tmp/out" >/dev/null 2>&1
    echo "$b $(cat "$tmp/t")" | tee -a "$tmp/all"
  done
done
echo "== medians (wall s) over $rounds rounds, load $(cut -d' ' -f1-3 /proc/loadavg)"
for b in "$@"; do
  grep "^$b " "$tmp/all" | awk '{print $2}' | sort -g |
    awk -v b="$b" '{a[NR]=$1} END {m=(NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2); print b": "m" s"}'
done
rm -rf "$tmp"
