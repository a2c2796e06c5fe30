#!/usr/bin/env bash
# lab4_random_scenes.sh — the long run of lab 4's random-scene test (tests/lab4_random_scenes.cpp):
# N seeds (default 3000) against the ray-traced reference, split over the cores, one summary line
# per part and the failing seeds with their scenes. CTest runs seeds 0..299; this starts there too.
#   bash bench/lab4_random_scenes.sh [N] [BUILD_DIR]
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
count="${1:-3000}"
build="${2:-${LAB_BUILD_DIR:-$root/build}}"
exe="$build/tests/lab4_random_scenes"
[ -x "$exe" ] || { echo "lab4_random_scenes.sh: $exe not built (bash scripts/setup.sh)" >&2; exit 2; }
parts="$(nproc)"
per=$(( (count + parts - 1) / parts ))
logs="$build/test_output/lab4_random_long"
mkdir -p "$logs"
echo "lab4_random_scenes.sh: $count seeds in $parts parts, CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), LP_NUM_THREADS=${LP_NUM_THREADS:-unset}"
start=$(date +%s)
pids=()
for ((p = 0; p < parts; ++p)); do
  first=$(( p * per ))
  n=$(( count - first < per ? count - first : per ))
  (( n > 0 )) || continue
  "$exe" --first "$first" --count "$n" > "$logs/part$p.log" 2>&1 & pids+=($!)
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
grep -h '^lab4_random_scenes:' "$logs"/part*.log
grep -h -A3 '^FAIL seed' "$logs"/part*.log | grep -v '^  scene:' || true
# The worst scene over all parts (by wrong-side share).
grep -h '^seed ' "$logs"/part*.log | sed -E 's/^seed ([0-9]+): .*wrong_side_pct=([0-9.]+).*\[(.*)\]$/\2 \1 \3/' | sort -g | tail -1 |
  awk '{printf "worst: seed %s, %s %% wrong side (", $2, $1; for (i = 3; i <= NF; ++i) printf "%s%s", $i, (i < NF ? " " : ""); print ")"}'
echo "lab4_random_scenes.sh: $(cat "$logs"/part*.log | grep -c '^seed ') scenes judged in $(( $(date +%s) - start )) s; logs in $logs"
exit $status
