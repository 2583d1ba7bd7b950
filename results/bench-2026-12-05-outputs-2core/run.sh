#!/usr/bin/env bash
# The end-to-end bench of this log: the main job before and after, side by side, interleaved
# rounds; the 4,000-flight job; the 80,000- and 1,000,000-flight runs' wall, peak RSS and file
# count. Usage (from the repository root, after `cargo build --release`):
#   results/bench-2026-12-05-outputs-2core/run.sh BEFORE_BINARY AFTER_BINARY [ROUNDS]
set -euo pipefail
before=$1; after=$2; rounds=${3:-5}
tmp=$(mktemp -d)
wall() { # wall seconds of one run
  local t0 t1; t0=$(date +%s.%N); "$@" >/dev/null 2>&1 || [ $? -eq 1 ]; t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc -l
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
echo "== main job, --variants 2500 (20,000 flights), $rounds interleaved rounds"
: >"$tmp/b"; : >"$tmp/a"
for r in $(seq "$rounds"); do
  wall "$before" scenarios/ballast_sweep.toml --variants 2500 --quiet --out "$tmp/before" >>"$tmp/b"
  wall "$after" scenarios/ballast_sweep.toml --variants 2500 --quiet --out "$tmp/after" >>"$tmp/a"
done
b=$(median <"$tmp/b"); a=$(median <"$tmp/a")
echo "before: $(tr '\n' ' ' <"$tmp/b")-> median $b s, $(echo "20000 / $b" | bc) flights/s"
echo "after:  $(tr '\n' ' ' <"$tmp/a")-> median $a s, $(echo "20000 / $a" | bc) flights/s"
echo "ratio:  $(echo "$b / $a" | bc -l | cut -c1-5)"
echo "== main job as the README runs it (4,000 flights), $rounds interleaved rounds"
: >"$tmp/b"; : >"$tmp/a"
for r in $(seq "$rounds"); do
  wall "$before" scenarios/ballast_sweep.toml --quiet --out "$tmp/before" >>"$tmp/b"
  wall "$after" scenarios/ballast_sweep.toml --quiet --out "$tmp/after" >>"$tmp/a"
done
echo "before: median $(median <"$tmp/b") s; after: median $(median <"$tmp/a") s"
# Peak RSS, wall and the most files in the output directory while the run goes.
big() {
  local bin=$1 n=$2 extra=${3:-}
  local out="$tmp/big-$n"; rm -rf "$out"; mkdir -p "$out"
  ( most=0; while sleep 0.2; do
      c=$(find "$out" -type f 2>/dev/null | wc -l); [ "$c" -gt "$most" ] && most=$c && echo "$most" >"$tmp/most"
    done ) & local watcher=$!
  /usr/bin/time -v "$bin" scenarios/ballast_sweep.toml --variants "$n" --quiet $extra --out "$out" \
    >/dev/null 2>"$tmp/time" || [ $? -eq 1 ]
  kill "$watcher"
  echo "$(basename "$bin") --variants $n $extra: wall $(grep 'Elapsed (wall' "$tmp/time" | awk '{print $NF}'), peak RSS $(grep 'Maximum resident' "$tmp/time" | awk '{print $NF}') kB, at most $(cat "$tmp/most") files"
  rm -rf "$out"
}
echo "== 80,000 and 1,000,000 flights"
big "$before" 10000
big "$after" 10000
big "$after" 10000 --no-report
big "$after" 125000
big "$after" 125000 --no-report
rm -rf "$tmp"
