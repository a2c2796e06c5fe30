#!/usr/bin/env bash
# build_is_current.sh BUILD_DIR — the CTest test build_is_current, the fixture every other test
# needs: it brings BUILD_DIR up to date (the labs, their shaders, the tests) before any test runs.
# Without it, a change that no longer compiles left the last good binaries and SPIR-V in place and
# the tests graded those: a broken shader passed them all. Now the build's errors are printed
# here, and CTest runs none of the tests that need it ("Not Run", failed dependency).
# -h / --help: the comment at the top of this file, nothing run.
set -uo pipefail
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
build="${1:?usage: build_is_current.sh BUILD_DIR}"
log="$build/build_is_current.log"
if cmake --build "$build" --parallel "$(nproc)" >"$log" 2>&1; then
  echo "build_is_current: $build is up to date"
  exit 0
fi
# The compiler's and glslang's own lines name the file, the line and the reason.
grep -E "error|ERROR|Error [0-9]" "$log" | grep -vE "^g?make(\[[0-9]+\])?: " | head -n 20
echo "build_is_current: the build failed (above; all of it in $log): no test runs until it builds," \
     "or the tests would grade the last binaries and shaders that did"
exit 1
