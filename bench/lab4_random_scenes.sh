#!/usr/bin/env bash
# lab4_random_scenes.sh — the long run of lab 4's random-scene test (tests/lab4_random_scenes.cpp):
# N seeds (default 3000) against the ray-traced reference, split over the cores, one summary line
# per part and the failing seeds with their scenes. CTest runs seeds 0..299; this starts there too.
#   bash bench/lab4_random_scenes.sh [N] [BUILD_DIR] [-- OPTION...]
# Everything after `--` goes to every part's lab4_random_scenes as it is, e.g. the other kind of
# scene from the same seeds (2-4 translucent objects stacked, nested or intersecting):
#   bash bench/lab4_random_scenes.sh 3000 build -- --translucent-stacks
# or --huge-bias, --size WxH. (BUILD_DIR may be left out before `--`: $LAB_BUILD_DIR, else build/.)
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
positional=()
while (( $# > 0 )); do
  if [ "$1" = "--" ]; then shift; break; fi
  positional+=("$1"); shift
done
extra=("$@")  # after `--`: passed to every part
count="${positional[0]:-3000}"
build="${positional[1]:-${LAB_BUILD_DIR:-$root/build}}"
exe="$build/tests/lab4_random_scenes"
[ -x "$exe" ] || { echo "lab4_random_scenes.sh: $exe not built (bash scripts/setup.sh)" >&2; exit 2; }
parts="$(nproc)"
per=$(( (count + parts - 1) / parts ))
# One folder per set of options (a run with --translucent-stacks keeps the default run's logs).
logs="$build/test_output/lab4_random_long"
(( ${#extra[@]} == 0 )) || logs+="_$(printf '%s' "${extra[*]}" | tr -c 'A-Za-z0-9.=-' '_' | sed 's/^-*//')"
mkdir -p "$logs"
rm -f "$logs"/part*.log  # an earlier run's parts (more cores then) must not join this one's summary
echo "lab4_random_scenes.sh: $count seeds in $parts parts${extra[*]:+ (${extra[*]})}, CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), LP_NUM_THREADS=${LP_NUM_THREADS:-unset}"
start=$(date +%s)
pids=()
for ((p = 0; p < parts; ++p)); do
  first=$(( p * per ))
  n=$(( count - first < per ? count - first : per ))
  (( n > 0 )) || continue
  "$exe" --first "$first" --count "$n" ${extra[@]+"${extra[@]}"} > "$logs/part$p.log" 2>&1 & pids+=($!)
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
