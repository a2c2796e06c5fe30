#!/usr/bin/env bash
# with_exercise_hint.sh HINT_EXE TEST_NAME COMMAND… — runs COMMAND, a lab's test that is not a
# GoogleTest test (a smoke run, a window, a soak, the random scenes, a gallery); when it fails (an
# exit code other than 0 and 77, the skip), prints which exercise TEST_NAME needs the way a failing
# GoogleTest test does, as the output's last lines (HINT_EXE: exercise_hint, tests/exercise_hints.cpp,
# which reads the build's exercises manifest; tests/graded_exercises.txt's rows name CTest names
# too). Exits with COMMAND's exit code. tests/CMakeLists.txt wraps every labN test so.
set -uo pipefail
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
if [ $# -lt 3 ]; then
  echo "with_exercise_hint.sh: usage: with_exercise_hint.sh HINT_EXE TEST_NAME COMMAND…" >&2
  exit 2
fi
hint="$1" name="$2"
shift 2
code=0
"$@" || code=$?
if [ "$code" -ne 0 ] && [ "$code" -ne 77 ]; then "$hint" "$name" || true; fi
exit "$code"
