#!/usr/bin/env bash
# test.sh — set everything up, then run the whole test suite through CTest.
# Every headless render in the suite runs with the Khronos validation layers on.
#
#   bash scripts/test.sh [CTEST_ARGS…]     e.g. -L lab2, -R Camera (docs/testing.md); LAB_BUILD_DIR picks the build
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
build="${LAB_BUILD_DIR:-$root/build}"
start=$(date +%s)
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" "$@"
echo "test: suite finished in $(( $(date +%s) - start )) s"
