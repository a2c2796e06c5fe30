#!/usr/bin/env bash
# lab4_shadows.sh — what shadows cost, measured in ONE run (docs/performance.md, "Lab 4: what shadows cost"):
#   lab3      lab 3 on its default scene
#   lab4_on3  lab 4 on lab 3's default scene (no light casts shadows: must cost ≤ 1.10 × lab 3)
#   off       lab 4's default scene with every light's cast_shadows off (no pass, no lookup)
#   static    lab 4's default scene (maps rendered once, then only the lookups)
#   animated  the same with --dev-animate-lights (every map re-rendered every frame)
# Rounds interleave the five so that load from other processes hits all alike; each line is a
# --benchmark median (ms); the summary gives the median over rounds and the spread (min–max).
#   bash bench/lab4_shadows.sh [rounds] [frames]     (LP_NUM_THREADS=2 unless set)
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAB_BUILD_DIR:-$root/build}"
rounds="${1:-3}"
frames="${2:-40}"
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$root/scenes/lab4_shadows.json" "$tmp/off.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
for light in scene["lights"]:
    light["cast_shadows"] = False
json.dump(scene, open(sys.argv[2], "w"))
PY
# off.json lives in a temporary folder: its relative texture paths must still resolve.
sed -i "s#\"textures/#\"$root/scenes/textures/#g; s#\"models/#\"$root/scenes/models/#g" "$tmp/off.json"

median() {  # the median_ms of one --benchmark run
  "$@" --benchmark "$frames" 2>/dev/null | sed -n 's/.*median_ms=\([0-9.]*\).*/\1/p'
}
declare -A times
for ((r = 0; r < rounds; ++r)); do
  times[lab3]+=" $(median "$build/lab3_textures/lab3_textures")"
  times[lab4_on3]+=" $(median "$build/lab4_shadows/lab4_shadows" --scene "$root/scenes/lab3_textures.json")"
  times[off]+=" $(median "$build/lab4_shadows/lab4_shadows" --scene "$tmp/off.json")"
  times[static]+=" $(median "$build/lab4_shadows/lab4_shadows")"
  times[animated]+=" $(median "$build/lab4_shadows/lab4_shadows" --dev-animate-lights)"
done
echo "LP_NUM_THREADS=$LP_NUM_THREADS 1280x720, $rounds rounds of --benchmark $frames (median ms per round)"
python3 - "${times[lab3]}" "${times[lab4_on3]}" "${times[off]}" "${times[static]}" "${times[animated]}" <<'PY'
import statistics, sys
names = ["lab3", "lab4_on3", "off", "static", "animated"]
runs = {n: [float(x) for x in s.split()] for n, s in zip(names, sys.argv[1:])}
med = {n: statistics.median(v) for n, v in runs.items()}
for n in names:
    print(f"{n:9s} median {med[n]:7.2f} ms  (rounds: {', '.join(f'{x:.2f}' for x in runs[n])})")
print(f"lab4 on lab 3's scene / lab 3      = {med['lab4_on3'] / med['lab3']:.3f}")
print(f"default static / shadows off       = {med['static'] / med['off']:.3f}")
print(f"default animated / static          = {med['animated'] / med['static']:.3f}")
PY
