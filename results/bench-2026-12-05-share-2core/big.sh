#!/usr/bin/env bash
# A large run's wall, peak RSS and the most files its output directory held at once.
# Usage (from the repository root): results/bench-2026-12-05-share-2core/big.sh BINARY VARIANTS
set -euo pipefail
bin=$1; n=$2
out=$(mktemp -d); tmp=$(mktemp -d)
echo 0 >"$tmp/most"
( most=0; while sleep 0.2; do
    c=$(find "$out" -type f 2>/dev/null | wc -l)
    if [ "$c" -gt "$most" ]; then most=$c; echo "$most" >"$tmp/most"; fi
  done ) & watcher=$!
/usr/bin/time -v "$bin" scenarios/ballast_sweep.toml --variants "$n" --quiet --timings --out "$out" \
  >"$tmp/stdout" 2>"$tmp/time" || [ $? -eq 1 ]
kill "$watcher"
echo "--variants $n: wall $(grep 'Elapsed (wall' "$tmp/time" | awk '{print $NF}'), user $(grep 'User time' "$tmp/time" | awk '{print $NF}') s, peak RSS $(grep 'Maximum resident' "$tmp/time" | awk '{print $NF}') KB, at most $(cat "$tmp/most") files"
grep -E "began where|flights/s end to end" "$tmp/stdout" || true
rm -rf "$out" "$tmp"
