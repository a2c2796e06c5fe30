#!/usr/bin/env bash
# lab3_samplers.sh — frame time of each sampler setting on the grazing floor (scenes/lab3_floor.json)
# at 1280x720, and lab 3 against lab 2 on lab 2's default scene, in one run.
# The error of each setting against the supersampled ground truth comes from the test
# Lab3Filtering.AnisotropyLowersTheErrorAgainstTheGroundTruth (build/test_output/lab3/sampler_errors.md).
#   bash bench/lab3_samplers.sh [frames] [rounds]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAB_BUILD_DIR:-$root/build}"
frames="${1:-60}"
rounds="${2:-3}"
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

median() { "$@" | sed -n 's/.*median_ms=\([0-9.]*\).*/\1/p'; }
settings=(
  'nearest|"filter": "nearest", "mipmaps": "none", "anisotropy": 1'
  'linear, no mipmaps|"filter": "linear", "mipmaps": "none", "anisotropy": 1'
  'trilinear|"filter": "linear", "mipmaps": "linear", "anisotropy": 1'
  'trilinear + aniso 2|"filter": "linear", "mipmaps": "linear", "anisotropy": 2'
  'trilinear + aniso 4|"filter": "linear", "mipmaps": "linear", "anisotropy": 4'
  'trilinear + aniso 8|"filter": "linear", "mipmaps": "linear", "anisotropy": 8'
  'trilinear + aniso 16|"filter": "linear", "mipmaps": "linear", "anisotropy": 16'
)
for i in "${!settings[@]}"; do
  IFS='|' read -r label sampler <<<"${settings[i]}"
  sed -e "s|\"textures/|\"$root/scenes/textures/|" \
      -e "s|\"sampler\": {[^}]*}|\"sampler\": { $sampler }|" "$root/scenes/lab3_floor.json" >"$tmp/floor_$i.json"
done
echo "median ms per frame at 1280x720, LP_NUM_THREADS=$LP_NUM_THREADS, $frames frames, $rounds rounds"
for ((r = 1; r <= rounds; r++)); do
  line="round $r:"
  line+="  lab2 on lab2_lighting.json $(median "$build/lab2_lighting/lab2_lighting" --benchmark "$frames" --scene "$root/scenes/lab2_lighting.json") |"
  line+="  lab3 on lab2_lighting.json $(median "$build/lab3_textures/lab3_textures" --benchmark "$frames" --scene "$root/scenes/lab2_lighting.json") |"
  line+="  lab3 default $(median "$build/lab3_textures/lab3_textures" --benchmark "$frames" --scene "$root/scenes/lab3_textures.json") |"
  for i in "${!settings[@]}"; do
    IFS='|' read -r label sampler <<<"${settings[i]}"
    line+="  floor $label $(median "$build/lab3_textures/lab3_textures" --benchmark "$frames" --scene "$tmp/floor_$i.json") |"
  done
  echo "$line"
done
