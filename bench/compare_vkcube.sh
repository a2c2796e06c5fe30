#!/usr/bin/env bash
# compare_vkcube.sh — lab frame time against vkcube's on the same machine, same run.
#
# vkcube (Debian's vulkan-tools) runs in a window (Xvfb if no display) with
# present mode 0 (immediate); its frame time is (t(700 frames) − t(100 frames)) / 600,
# which removes start-up cost. The lab's figure is its --benchmark median.
#   bash bench/compare_vkcube.sh [lab] [frames]
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
lab="${1:-lab1_camera}"
frames="${2:-300}"
exe="${LAB_BUILD_DIR:-$root/build}/$lab/$lab"
command -v vkcube >/dev/null || { echo "vkcube missing: apt-get install vulkan-tools" >&2; exit 1; }

if [ -z "${DISPLAY:-}" ]; then
  # -noreset: each run below is the server's last client, and a reset as it leaves can refuse the next run.
  Xvfb :97 -screen 0 1600x900x24 -noreset >/dev/null 2>&1 &
  xvfb_pid=$!
  trap 'kill $xvfb_pid' EXIT
  export DISPLAY=:97
  sleep 1
fi

seconds() {  # wall time of a command, in seconds
  local start end
  start=$(date +%s.%N)
  "$@" >/dev/null 2>&1
  end=$(date +%s.%N)
  python3 -c "print($end - $start)"
}

for round in 1 2 3; do
  t100=$(seconds vkcube --width 1280 --height 720 --present_mode 0 --c 100)
  t700=$(seconds vkcube --width 1280 --height 720 --present_mode 0 --c 700)
  vkcube_ms=$(python3 -c "print(($t700 - $t100) * 1000 / 600)")
  line=$("$exe" --benchmark "$frames" --width 1280 --height 720)
  lab_ms=$(sed -n 's/.*median_ms=\([0-9.]*\).*/\1/p' <<<"$line")
  printf 'round %d: vkcube %.3f ms/frame, %s median %.3f ms/frame, ratio lab/vkcube %.2f\n' \
    "$round" "$vkcube_ms" "$lab" "$lab_ms" "$(python3 -c "print($lab_ms / $vkcube_ms)")"
done
