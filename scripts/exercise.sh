#!/usr/bin/env bash
# exercise.sh — a student copy of the project, with a lab's exercises cut out and no answers in it;
# the labs' exercises listed, stubbed, checked. The command; scripts/exercise.py does the work, over
# scripts/course/exercises.py (the one reader of the exercise markers and tests/graded_exercises.txt).
#
#   bash scripts/exercise.sh LAB [NAME…] [--out DIR]   # write the copy
#   bash scripts/exercise.sh --help                     # every command
command -v python3 >/dev/null 2>&1 || { echo "exercise: python3 is missing (scripts/setup.sh installs it)" >&2; exit 2; }
exec python3 "$(dirname "${BASH_SOURCE[0]}")/exercise.py" "$@"  # every command, --help too
