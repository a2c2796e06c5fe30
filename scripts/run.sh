#!/usr/bin/env bash
# run.sh — set everything up, then run one lab with its own default scene
# (scenes/<lab>.json): in a window when a display is present, otherwise headless
# (writes out/<lab>.png and prints its path).
#
#   bash scripts/run.sh                     # the newest lab
#   bash scripts/run.sh lab1                # lab 1 (also: 1, lab1_camera)
#   bash scripts/run.sh 2 --scene scenes/lab2_one_light.json --validate
#   bash scripts/run.sh site [--student N] [OUT]   # the course site (scripts/make_site.sh) into OUT (build/site;
#                                           # --student N: lab N's student edition, build/site-student-labN)
#
# Everything after the lab goes to the lab unchanged (see `--help` of any lab).
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAB_BUILD_DIR:-$root/build}"

# The course site: packages and site/node_modules (no C++ build needed), the site, where to open it.
if [ "${1:-}" = site ]; then
  shift
  student=()
  if [ "${1:-}" = --student ]; then
    [ $# -ge 2 ] || { echo "run: site --student needs a lab (1..4)" >&2; exit 2; }
    student=(--student "$2")
    shift 2
  fi
  n="${student[1]:-}"
  n="${n#lab}"
  out="$(realpath -m -- "${1:-$root/build/site${n:+-student-lab${n%%_*}}}")"
  bash "$root/scripts/setup.sh" --no-build
  bash "$root/scripts/make_site.sh" "${student[@]}" "$out"
  echo "run: open file://$out/index.html in a browser (it needs no network),"
  echo "run: or serve it: python3 -m http.server --directory $out 8000   (then http://localhost:8000/)"
  exit 0
fi

# The labs of this checkout, in order: folders lab<N>_<name>/ with a CMakeLists.txt.
mapfile -t labs < <(cd "$root" && for d in lab[0-9]*_*; do [ -f "$d/CMakeLists.txt" ] && echo "$d"; done | sort -V)

# The first argument names a lab when it looks like one: 2, lab2, lab2_lighting.
lab=""
if (($#)) && [[ "$1" =~ ^(lab)?[0-9]+(_[A-Za-z0-9_]+)?$ ]]; then
  want="$1"
  shift
  [[ "$want" == lab* ]] || want="lab$want"
  for candidate in "${labs[@]}"; do
    if [ "$candidate" = "$want" ] || [ "${candidate%%_*}" = "$want" ]; then lab="$candidate"; fi
  done
  if [ -z "$lab" ]; then
    echo "run: no lab '$want' here; the labs are: ${labs[*]}" >&2
    exit 2
  fi
else
  lab="${labs[${#labs[@]} - 1]}"  # the newest
fi

bash "$root/scripts/setup.sh"
exe="$build/$lab/$lab"
[ -x "$exe" ] || { echo "run: $exe was not built" >&2; exit 1; }

if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec "$exe" "$@"
else
  extra=(--headless --out "$root/out/$lab.png")
  for arg in "$@"; do [ "$arg" = --out ] && extra=(--headless); done  # the caller names the PNG
  echo "run: no display found, rendering $lab headless"
  mkdir -p "$root/out"
  exec "$exe" "${extra[@]}" "$@"
fi
