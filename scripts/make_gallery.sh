#!/usr/bin/env bash
# make_gallery.sh — each lab's expected pictures: docs/images/<lab>/*.png, shown on the lab's
# gallery page docs/images/<lab>/README.md.
#
#   bash scripts/make_gallery.sh [LAB…]           # render them (needs a build; LAB_BUILD_DIR or build/)
#   bash scripts/make_gallery.sh --check [LAB…]   # exit 1 when a committed picture no longer matches
#                                                 # what the lab renders (CTest: gallery_labN)
#
# A picture is a scene: docs/images/<lab>/scenes/NAME.json gives NAME.png, and default.png is the
# lab's own default scene (scenes/<lab>.json). Each is rendered headless at 480×270 with
# validation on, with the shaders of the build it is given (--dev-shader-dir $build/shaders/<lab>,
# not the folder compiled into the binary). A picture that needs more than its scene (lab 4's
# shadow-map view is a developer flag, not a scene key) has a NAME.args next to NAME.json: extra
# command-line arguments, split at spaces and newlines (no quoting), lines starting with '#'
# ignored; e.g. `--dev-shadow-view 0`.
#
# A picture of the truth a lab approximates comes from the CPU reference instead of the lab: a
# NAME.reference next to NAME.json (instead of a NAME.args) holds tests/tools/lab_reference's
# arguments, read the same way, and the picture is `lab_reference --lab <lab> --scene NAME.json
# --width 480 --height 270 ARGUMENTS`; e.g. `--supersample 16` for lab 3's filtering ground truth
# (16×16 rays per pixel, as tests/test_lab3_render.cpp takes it). The reference is deterministic, so
# --check compares it like the others; it needs `lab_reference` built as well.
#
# --check renders again and compares with tests/tools/lab_compare: like the render tests, at most
# 0.5 % of the pixels may differ by more than 2/255 (a real GPU rasterizes a few edge pixels
# differently; lavapipe gives the same bytes). It also checks that the gallery page
# shows every picture and names no missing one. A failed check leaves the new picture and a
# heatmap of the difference in build/test_output/gallery/<lab>/.
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
build="${LAB_BUILD_DIR:-$root/build}"
width=480 height=270
max_over_2_percent=0.5

check=0
if [ "${1:-}" = --check ]; then check=1; shift; fi
mapfile -t labs < <(for d in lab[0-9]*_*; do [ -f "$d/CMakeLists.txt" ] && echo "$d"; done | sort -V)
if (($#)); then
  wanted=()
  for w in "$@"; do
    [[ "$w" == lab* ]] || w="lab$w"
    for l in "${labs[@]}"; do [ "$l" = "$w" ] || [ "${l%%_*}" = "$w" ] && wanted+=("$l"); done
  done
  labs=("${wanted[@]}")
fi

failures=0
for lab in "${labs[@]}"; do
  dir="docs/images/$lab"
  [ -d "$dir/scenes" ] || { echo "gallery: $lab has no $dir/scenes (no pictures)"; continue; }
  exe="$build/$lab/$lab"
  [ -x "$exe" ] || { echo "gallery: $exe is not built" >&2; exit 2; }
  shaders="$build/shaders/$lab"
  [ -d "$shaders" ] || { echo "gallery: $shaders is not built" >&2; exit 2; }
  out="$build/test_output/gallery/$lab"
  mkdir -p "$out"
  pictures=("default:scenes/$lab.json")
  for s in "$dir"/scenes/*.json; do pictures+=("$(basename "$s" .json):$s"); done
  for p in "${pictures[@]}"; do
    name="${p%%:*}" scene="${p#*:}"
    extra=() renderer=lab
    if [ -f "$dir/scenes/$name.args" ] && [ -f "$dir/scenes/$name.reference" ]; then
      echo "FAIL $lab/$name: $dir/scenes/ has both $name.args (for the lab) and $name.reference (for lab_reference)"
      failures=$((failures + 1))
      continue
    fi
    arguments="$dir/scenes/$name.args"
    if [ -f "$dir/scenes/$name.reference" ]; then arguments="$dir/scenes/$name.reference" renderer=reference; fi
    if [ -f "$arguments" ]; then
      read -r -d '' -a extra < <(grep -v '^[[:space:]]*#' "$arguments") || true
    fi
    if [ $renderer = reference ]; then
      reference="$build/tests/lab_reference"
      [ -x "$reference" ] || { echo "gallery: $reference is not built (needed for $dir/scenes/$name.reference)" >&2; exit 2; }
      if ! "$reference" --lab "$lab" --scene "$scene" --width $width --height $height "${extra[@]}" \
           --out "$out/$name.png" >"$out/$name.log" 2>&1; then
        echo "FAIL $lab/$name: lab_reference failed on $scene: $(tail -n 1 "$out/$name.log")"
        failures=$((failures + 1))
        continue
      fi
    elif ! "$exe" --dev-shader-dir "$shaders" --scene "$scene" --headless --validate \
         --width $width --height $height "${extra[@]}" --out "$out/$name.png" >"$out/$name.log" 2>&1; then
      echo "FAIL $lab/$name: the lab failed on $scene: $(tail -n 1 "$out/$name.log")"
      failures=$((failures + 1))
      continue
    fi
    if ((check == 0)); then
      cp "$out/$name.png" "$dir/$name.png"
      echo "gallery: $dir/$name.png"
      continue
    fi
    if [ ! -f "$dir/$name.png" ]; then
      echo "FAIL $lab/$name: $dir/$name.png is missing (run bash scripts/make_gallery.sh $lab)"
      failures=$((failures + 1))
      continue
    fi
    if ! figures=$("$build/tests/lab_compare" "$dir/$name.png" "$out/$name.png" --heatmap "$out/${name}_heatmap.png" 2>&1); then
      echo "FAIL $lab/$name: $figures"
      failures=$((failures + 1))
      continue
    fi
    over=$(sed -nE 's/.*over_2=([0-9.]+)%.*/\1/p' <<<"$figures")
    if [ -z "$over" ] || awk -v o="$over" -v m="$max_over_2_percent" 'BEGIN { exit !(o > m) }'; then
      echo "FAIL $lab/$name: $dir/$name.png no longer matches the lab ($figures); new picture and heatmap in $out/"
      failures=$((failures + 1))
    else
      echo "ok   $lab/$name ($figures)"
    fi
  done
  if ((check)); then
    # The page shows every picture, and only pictures that exist.
    page="$dir/README.md"
    if [ ! -f "$page" ]; then
      echo "FAIL $lab: no gallery page $page"
      failures=$((failures + 1))
    else
      for p in "${pictures[@]}"; do
        name="${p%%:*}"
        grep -q "($name\.png)" "$page" || { echo "FAIL $lab: $page does not show $name.png"; failures=$((failures + 1)); }
      done
      for shown in $(grep -oE '\([a-z0-9_]+\.png\)' "$page" | tr -d '()' | sort -u); do
        [ -f "$dir/$shown" ] || { echo "FAIL $lab: $page shows $shown, which does not exist"; failures=$((failures + 1)); }
      done
    fi
  fi
done
if ((failures)); then
  echo "gallery: $failures problem(s)"
  exit 1
fi
