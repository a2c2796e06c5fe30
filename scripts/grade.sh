#!/usr/bin/env bash
# grade.sh — grade every submission of a lab: a score per exercise, the grader's messages and
# pictures, a class summary and the autograder JSON (docs/solutions.md, "Grading a class").
#
#   bash scripts/grade.sh LAB SUBMISSIONS [--out DIR] [--jobs N] [--cache DIR]
#
# Run in the instructors' repository (it has the solutions). SUBMISSIONS holds one entry per
# student: a folder (their copy of lab LAB) or a .tar.gz / .tgz / .zip of one; the student's name is
# the entry's name without its extension. DIR (default build/grades-labN/) gets grades.csv,
# index.html and, per student, students/NAME/results.json and report.html. Only the code inside the
# exercises' regions counts (a region that steps outside its exercise gets 0, flagged); each exercise
# is graded with the solution of every other one; student code runs only inside a bubblewrap sandbox
# (no network, its own copy, CPU/memory/process/wall limits), and no verdict comes from a process
# that runs it: a judge that runs none of it decides on the values it recorded (tests/probe.h).
# The pristine build is cached in --cache (default /tmp/vulkan-labs-grade-UID, $GRADE_CACHE), per lab and
# repository state. The implementation is scripts/grade/grade.py (Python 3 standard library).
set -euo pipefail
case "${1:-}" in -h | --help | "") awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
for tool in bwrap python3 prlimit; do
  command -v "$tool" >/dev/null || { echo "grade: $tool is missing (bash scripts/setup.sh installs it: bubblewrap, python3, util-linux)" >&2; exit 2; }
done
if [ "$(id -u)" -eq 0 ]; then command -v setpriv >/dev/null || { echo "grade: setpriv is missing (util-linux)" >&2; exit 2; }; fi
exec python3 "$here/grade/grade.py" "$@"
