#!/usr/bin/env bash
# test.sh — set everything up, then run the whole test suite through CTest.
# Every headless render in the suite runs with the Khronos validation layers on.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
build="${LAB_BUILD_DIR:-$root/build}"
start=$(date +%s)
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" "$@"
echo "test: suite finished in $(( $(date +%s) - start )) s"
