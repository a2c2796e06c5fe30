#!/usr/bin/env bash
# fuzz_scenes.sh — the big scene-file fuzz run, under AddressSanitizer + UndefinedBehaviorSanitizer.
#
#   bash bench/fuzz_scenes.sh [CASES] [SEED]     default: 5000 cases, seed 1
#
# Builds the sanitizer build (build-asan, LAB_SANITIZE=ON; LAB_ASAN_BUILD_DIR overrides) if needed,
# then runs tests/scene_fuzz.cpp: CASES mutants of every scene in scenes/ and tests/scenes/ through
# lab::load_scene (each must load, or be rejected with one line naming the file: exit code 2 in a
# lab), one case in 100 also through the newest lab binary; a tenth as many through each older lab;
# then the cases in tests/fuzz/regressions.txt. A sanitizer report stops the run (halt_on_error).
# A failing case prints "FAILED <case seed> <scene file>": append that line to
# tests/fuzz/regressions.txt (with a comment: what it found, what fixed it) so that every test run
# replays it. Same CASES and SEED = the same cases.
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAB_ASAN_BUILD_DIR:-$root/build-asan}"
cases="${1:-5000}"
seed="${2:-1}"
[[ "$cases" =~ ^[0-9]+$ && "$seed" =~ ^[0-9]+$ ]] || { echo "usage: bench/fuzz_scenes.sh [CASES] [SEED]" >&2; exit 2; }

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLAB_SANITIZE=ON >/dev/null
labs=()
for lab in lab4_shadows lab3_textures lab2_lighting lab1_camera; do
  [[ -f "$root/$lab/CMakeLists.txt" ]] && labs+=("$lab")
done
cmake --build "$build" -j2 --target scene_fuzz "${labs[@]}"

# Leak checking stays off: lavapipe leaks 240 bytes at exit from inside the driver (docs/testing.md).
export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
cd "$root"
fuzz="$build/tests/scene_fuzz"
start=$(date +%s)
result=0
"$fuzz" --seed "$seed" --cases "$cases" --lab "$build/${labs[0]}/${labs[0]}" --lab-cases $((cases / 100)) \
  scenes tests/scenes || result=1
for lab in "${labs[@]:1}"; do
  "$fuzz" --seed "$((seed + 1000))" --cases $((cases / 10)) --lab "$build/$lab/$lab" --lab-cases $((cases / 1000 + 1)) \
    scenes tests/scenes || result=1
done
"$fuzz" --replay tests/fuzz/regressions.txt --lab "$build/${labs[0]}/${labs[0]}" || result=1
echo "fuzz_scenes: $(( $(date +%s) - start )) s under ASan/UBSan, seed $seed: $([[ $result == 0 ]] && echo PASS || echo FAILED)"
exit "$result"
