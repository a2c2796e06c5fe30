#!/usr/bin/env bash
# lab_figures.sh — the --benchmark figures quoted in the docs and closing notes, in one run.
# The machines are shared: compare figures from the same run (ratios), not across runs.
#   bash bench/lab_figures.sh [frames] [rounds]
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAB_BUILD_DIR:-$root/build}"
frames="${1:-100}"
rounds="${2:-3}"
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"  # repeatable lavapipe figures

cases=(
  "lab1_camera|scenes/lab1_camera.json|lab1 default"
  "lab2_lighting|scenes/lab2_ambient_only.json|lab2 ambient only"
  "lab2_lighting|scenes/lab2_one_light.json|lab2 1 light"
  "lab2_lighting|scenes/lab2_lighting.json|lab2 default (1+2+1 lights)"
  "lab2_lighting|scenes/lab2_many_lights.json|lab2 8+32+32 lights"
)
echo "median ms per frame at 1280x720, LP_NUM_THREADS=$LP_NUM_THREADS, $frames frames, $rounds rounds"
for ((r = 1; r <= rounds; r++)); do
  line="round $r:"
  for c in "${cases[@]}"; do
    IFS='|' read -r lab scene label <<<"$c"
    exe="$build/$lab/$lab"
    [ -x "$exe" ] || continue
    n=$frames
    [[ $scene == *many_lights* ]] && n=$(( frames / 10 > 5 ? frames / 10 : 5 ))  # ~0.3 s a frame
    ms=$("$exe" --benchmark "$n" --scene "$root/$scene" | sed -n 's/.*median_ms=\([0-9.]*\).*/\1/p')
    line+="  $label $ms |"
  done
  echo "$line"
done
