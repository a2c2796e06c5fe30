#!/usr/bin/env bash
# run.sh — set everything up, then run the newest lab with its default scene:
# in a window when a display is present, otherwise headless (prints the PNG's path).
# Extra arguments go to the lab, e.g.  bash scripts/run.sh --scene scenes/lab1_camera.json
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
build="${LAB_BUILD_DIR:-$root/build}"

lab=""
for candidate in lab1_camera lab2_lighting lab3_textures lab4_shadows; do
  [ -x "$build/$candidate/$candidate" ] && lab="$candidate"
done
[ -n "$lab" ] || { echo "run: no lab was built in $build" >&2; exit 1; }

if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec "$build/$lab/$lab" "$@"
else
  echo "run: no display found, rendering $lab headless"
  mkdir -p "$root/out"
  exec "$build/$lab/$lab" --headless --out "$root/out/$lab.png" "$@"
fi
