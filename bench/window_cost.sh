#!/usr/bin/env bash
# window_cost.sh — what a window frame costs next to a headless frame and vkcube's.
#
# For each lab: wall time of --frames 100 and --frames 600, in a window and
# headless, and of vkcube (FIFO, same window size) — the per-frame cost is
# (T(600) − T(100)) / 500, which removes start-up and shutdown. Three rounds;
# compare the ratios within a round (the machine is shared, absolute numbers drift).
# Then the idle CPU of a lab window that nothing happens to (from /proc/PID/stat, 10 s).
#   bash bench/window_cost.sh [lab ...]        (default: every lab built)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAB_BUILD_DIR:-$root/build}"
labs=("$@")
if ((${#labs[@]} == 0)); then
  for d in "$build"/lab*/; do
    name=$(basename "$d"); [ -x "$d/$name" ] && labs+=("$name")
  done
fi
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
rounds="${ROUNDS:-3}"
tmp=$(mktemp -d)
if [ -z "${DISPLAY:-}" ]; then
  Xvfb :97 -screen 0 1600x900x24 >/dev/null 2>&1 &
  xvfb_pid=$!
  trap 'kill $xvfb_pid; rm -rf "$tmp"' EXIT
  export DISPLAY=:97
  sleep 1
else
  trap 'rm -rf "$tmp"' EXIT
fi

seconds() {  # wall time of a command, in seconds
  local start end
  start=$(date +%s.%N)
  "$@" >/dev/null 2>&1
  end=$(date +%s.%N)
  python3 -c "print($end - $start)"
}
per_frame() {  # ms per frame of "command --frames N" style runs: $1 = t100, $2 = t600
  python3 -c "print('%.2f' % (($2 - $1) * 1000 / 500))"
}

for round in $(seq "$rounds"); do
  line="round $round:"
  if command -v vkcube >/dev/null; then
    a=$(seconds vkcube --width 1280 --height 720 --present_mode 2 --c 100)
    b=$(seconds vkcube --width 1280 --height 720 --present_mode 2 --c 600)
    line+=" vkcube_fifo $(per_frame "$a" "$b")"
  fi
  for lab in "${labs[@]}"; do
    exe="$build/$lab/$lab"
    a=$(seconds "$exe" --frames 100); b=$(seconds "$exe" --frames 600)
    w=$(per_frame "$a" "$b")
    a=$(seconds "$exe" --frames 100 --out "$tmp/h.png"); b=$(seconds "$exe" --frames 600 --out "$tmp/h.png")
    h=$(per_frame "$a" "$b")
    line+=" | $lab window $w headless $h"
  done
  echo "$line ms/frame"
done

for lab in "${labs[@]}"; do
  "$build/$lab/$lab" >/dev/null 2>&1 &
  pid=$!
  sleep 3  # start-up and the first frames
  ticks() { awk '{print $14 + $15}' "/proc/$pid/stat"; }  # utime + stime, in clock ticks
  t0=$(ticks); sleep 10; t1=$(ticks)
  kill "$pid"; wait "$pid" 2>/dev/null || true
  echo "$lab idle window: $(python3 -c "print('%.1f' % (($t1 - $t0) * 100 / $(getconf CLK_TCK) / 10))") % of a core over 10 s"
done
