#!/usr/bin/env bash
# window_cost.sh — what a window frame costs next to a headless frame and vkcube's.
#
# For each lab: wall time and CPU time (user + system, all threads) of --frames 100 and
# --frames 600, in a window and headless, and of vkcube (FIFO, same window size) — the
# per-frame cost is (T(600) − T(100)) / 500, which removes start-up and shutdown. Each figure
# is printed as wall/cpu in ms per frame. Three rounds; compare the ratios within a round (the
# machine is shared: wall time drifts with the load, CPU time much less).
# Then the idle CPU of a lab window that nothing happens to (from /proc/PID/stat, 10 s).
#   bash bench/window_cost.sh [lab ...]        (default: every lab built)
#   ROUNDS=2 IDLE=0 SHORT=50 LONG=250 bash bench/window_cost.sh lab2_lighting
#        (2 rounds, skip the idle measurement, (T(250) − T(50)) / 200 for a slow lab)
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
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
short="${SHORT:-100}" long="${LONG:-600}"  # frame counts of the two runs per figure
tmp=$(mktemp -d)
if [ -z "${DISPLAY:-}" ]; then
  # -noreset: each run below is the server's last client, and a reset as it leaves can refuse the next run.
  Xvfb :97 -screen 0 1600x900x24 -noreset >/dev/null 2>&1 &
  xvfb_pid=$!
  trap 'kill $xvfb_pid; rm -rf "$tmp"' EXIT
  export DISPLAY=:97
  sleep 1
else
  trap 'rm -rf "$tmp"' EXIT
fi

seconds() {  # "wall cpu" of a command, in seconds (cpu: user + system of all its threads)
  python3 - "$@" <<'PY'
import os, subprocess, sys, time
start = time.monotonic()
child = subprocess.Popen(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
_, _, usage = os.wait4(child.pid, 0)
print(time.monotonic() - start, usage.ru_utime + usage.ru_stime)
PY
}
per_frame() {  # "wall/cpu" ms per frame of "command --frames N" style runs: $1 = T(short), $2 = T(long)
  python3 -c "a = '$1'.split(); b = '$2'.split(); print('%.2f/%.2f' % tuple((float(b[i]) - float(a[i])) * 1000 / ($long - $short) for i in (0, 1)))"
}

for round in $(seq "$rounds"); do
  line="round $round:"
  if command -v vkcube >/dev/null; then
    a=$(seconds vkcube --width 1280 --height 720 --present_mode 2 --c "$short")
    b=$(seconds vkcube --width 1280 --height 720 --present_mode 2 --c "$long")
    line+=" vkcube_fifo $(per_frame "$a" "$b")"
  fi
  for lab in "${labs[@]}"; do
    exe="$build/$lab/$lab"
    a=$(seconds "$exe" --frames "$short"); b=$(seconds "$exe" --frames "$long")
    w=$(per_frame "$a" "$b")
    a=$(seconds "$exe" --frames "$short" --out "$tmp/h.png"); b=$(seconds "$exe" --frames "$long" --out "$tmp/h.png")
    h=$(per_frame "$a" "$b")
    line+=" | $lab window $w headless $h"
  done
  echo "$line (wall/cpu ms/frame)"
done

[ "${IDLE:-1}" = 0 ] && exit 0  # IDLE=0: frame costs only
for lab in "${labs[@]}"; do
  rm -f "$tmp/status"
  "$build/$lab/$lab" --dev-status-file "$tmp/status" >/dev/null 2>&1 &
  pid=$!
  # Start-up (lab 4 compiles its shader variants at the first frame: seconds on lavapipe), then 3 s
  # for the frames after it (ImGui settling) before the idle window is measured.
  for _ in $(seq 600); do grep -q '^frame=' "$tmp/status" 2>/dev/null && break; sleep 0.1; done
  sleep 3
  ticks() { awk '{print $14 + $15}' "/proc/$pid/stat"; }  # utime + stime, in clock ticks
  t0=$(ticks); sleep 10; t1=$(ticks)
  kill "$pid"; wait "$pid" 2>/dev/null || true
  echo "$lab idle window: $(python3 -c "print('%.1f' % (($t1 - $t0) * 100 / $(getconf CLK_TCK) / 10))") % of a core over 10 s"
done
