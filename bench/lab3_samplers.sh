#!/usr/bin/env bash
# lab3_samplers.sh — frame time of each sampler setting on the grazing floor (scenes/lab3_floor.json)
# at 1280x720 (the sampler's anisotropy and the shader's probes, "anisotropic": "probes"), and lab 3
# against lab 2 on lab 2's default scene, in one run. Two figures per case:
# the median wall-clock ms of --benchmark, and the CPU ms per frame (user + sys of a run of N + 5
# frames minus a run of 5: start-up and pipeline compilation cancel out). On a machine shared with
# other jobs the wall clock swings by 2x between runs; the CPU time hardly moves.
# The error of each setting against the supersampled ground truth comes from the test
# Lab3Filtering.AnisotropyLowersTheErrorAgainstTheGroundTruth (build/test_output/lab3/sampler_errors.md).
# The first line names the device (each device has its own best setting: a CPU rasterizer is not a
# GPU), from lab 3's --benchmark line; on a CPU device also the CPU model and LP_NUM_THREADS.
#   bash bench/lab3_samplers.sh [frames] [rounds]
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAB_BUILD_DIR:-$root/build}"
frames="${1:-60}"
rounds="${2:-3}"
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

median() { "$@" | sed -n 's/.*median_ms=\([0-9.]*\).*/\1/p'; }
# "NAME (TYPE[; CPU model, LP_NUM_THREADS=N])" of the device EXE runs on: its benchmark line, read
# as bench/tradeoff.py reads it (tradeoff_lib/device.py; it exits naming the problem when the line
# names no device).
device_of() {
  "$1" --benchmark 1 --width 64 --height 36 | grep '^benchmark ' | PYTHONPATH="$root/bench" python3 -c '
import os, sys
from tradeoff_lib import device
fields = dict(kv.split("=", 1) for kv in sys.stdin.read().split() if "=" in kv)
print(device.label(device.of_benchmark(fields, os.environ, device.read_cpu_model())))'
}
cpu_s() { /usr/bin/time -f "%U %S" "$@" 2>&1 >/dev/null | tail -1 | awk '{print $1 + $2}'; }
# "WALL_MS/CPU_MS" for: EXE SCENE
measure() {
  local wall short long
  wall=$(median "$1" --benchmark "$frames" --scene "$2")
  short=$(cpu_s "$1" --benchmark 5 --scene "$2")
  long=$(cpu_s "$1" --benchmark $((frames + 5)) --scene "$2")
  echo "$wall/$(awk -v a="$short" -v b="$long" -v n="$frames" 'BEGIN { printf "%.1f", (b - a) / n * 1000 }')"
}
settings=(
  'nearest|"filter": "nearest", "mipmaps": "none", "anisotropy": 1'
  'linear, no mipmaps|"filter": "linear", "mipmaps": "none", "anisotropy": 1'
  'trilinear|"filter": "linear", "mipmaps": "linear", "anisotropy": 1'
  'trilinear + aniso 2|"filter": "linear", "mipmaps": "linear", "anisotropy": 2'
  'trilinear + aniso 4|"filter": "linear", "mipmaps": "linear", "anisotropy": 4'
  'trilinear + aniso 8|"filter": "linear", "mipmaps": "linear", "anisotropy": 8'
  'trilinear + aniso 16|"filter": "linear", "mipmaps": "linear", "anisotropy": 16'
  'trilinear + probes 2|"filter": "linear", "mipmaps": "linear", "anisotropy": 2, "anisotropic": "probes"'
  'trilinear + probes 4|"filter": "linear", "mipmaps": "linear", "anisotropy": 4, "anisotropic": "probes"'
  'trilinear + probes 8|"filter": "linear", "mipmaps": "linear", "anisotropy": 8, "anisotropic": "probes"'
  'trilinear + probes 16|"filter": "linear", "mipmaps": "linear", "anisotropy": 16, "anisotropic": "probes"'
  'bilinear, nearest mipmaps + probes 4|"filter": "linear", "mipmaps": "nearest", "anisotropy": 4, "anisotropic": "probes"'
  'bilinear, nearest mipmaps + probes 8|"filter": "linear", "mipmaps": "nearest", "anisotropy": 8, "anisotropic": "probes"'
)
for i in "${!settings[@]}"; do
  IFS='|' read -r label sampler <<<"${settings[i]}"
  sed -e "s|\"textures/|\"$root/scenes/textures/|" \
      -e "s|\"sampler\": {[^}]*}|\"sampler\": { $sampler }|" "$root/scenes/lab3_floor.json" >"$tmp/floor_$i.json"
done
device=$(device_of "$build/lab3_textures/lab3_textures")  # an assignment: set -e ends the script if it fails
echo "device: $device"
echo "wall median ms / CPU ms per frame at 1280x720, LP_NUM_THREADS=$LP_NUM_THREADS, $frames frames, $rounds rounds"
for ((r = 1; r <= rounds; r++)); do
  line="round $r:"
  line+="  lab2 on lab2_lighting.json $(measure "$build/lab2_lighting/lab2_lighting" "$root/scenes/lab2_lighting.json") |"
  line+="  lab3 on lab2_lighting.json $(measure "$build/lab3_textures/lab3_textures" "$root/scenes/lab2_lighting.json") |"
  line+="  lab3 default $(measure "$build/lab3_textures/lab3_textures" "$root/scenes/lab3_textures.json") |"
  for i in "${!settings[@]}"; do
    IFS='|' read -r label sampler <<<"${settings[i]}"
    line+="  floor $label $(measure "$build/lab3_textures/lab3_textures" "$tmp/floor_$i.json") |"
  done
  echo "$line"
done
