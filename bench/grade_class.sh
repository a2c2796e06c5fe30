#!/usr/bin/env bash
# grade_class.sh — time scripts/grade.sh on a class of 10 lab 1 submissions (issue: ≤ 15 s a
# submission on 2 cores after the first build).
#
#   bash bench/grade_class.sh [--keep DIR]
#
# The class is written from a fresh student copy of lab 1. Every region of every student differs
# from the solution's text (a comment line of their own), as real students' code does, so no
# variant is the solution's and each submission costs what a real one costs: 5 isolated builds and
# runs, plus one run as handed in. The mix: 6 solved, 2 partial, 1 not compiling in one region, 1
# left as handed out. Prints each submission's time, the mean and the worst, the CPU model, the
# cores and LP_NUM_THREADS. The pristine build (once per repository state) is timed apart.
set -euo pipefail
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
keep=""
[ "${1:-}" = --keep ] && keep="${2:?--keep needs a folder}"
tmp=$(mktemp -d /tmp/grade-bench-XXXXXX)
chmod 755 "$tmp"
trap '[ -n "$keep" ] && rm -rf "$keep" && cp -a "$tmp" "$keep"; rm -rf "$tmp"' EXIT
bash "$root/scripts/exercise.sh" 1 --out "$tmp/copy" >/dev/null
python3 - "$root" "$tmp" <<'PY'
import os, shutil, sys
root, tmp = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(root, "tests", "grading"))
import test_grading as t
os.makedirs(os.path.join(tmp, "class"))
mix = {f"s{i:02d}": t.EXERCISES for i in range(1, 7)}
mix.update({"s07": ["look_at", "projection"], "s08": ["look_at", "transform", "mode_switch"], "s09": t.EXERCISES, "s10": []})
for name, solved in mix.items():
    d = os.path.join(tmp, "class", name)
    shutil.copytree(os.path.join(tmp, "copy"), d, symlinks=True)
    for e in solved:
        t.fill(d, e, [f"    // {name}'s own {e}\n"] + t.solution(e))
    if name == "s09":
        t.fill(d, "projection", ["    glm::dmat4 p = not_declared(1.0);\n"])
PY
echo "grade_class: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'), $(nproc) cores, LP_NUM_THREADS=${LP_NUM_THREADS:-unset (lavapipe: one thread a core)}, load $(cut -d' ' -f1-3 /proc/loadavg)"
start=$(date +%s.%N)
# the pristine build and the solution's timing, apart (an empty class)
mkdir -p "$tmp/none/x" && bash "$root/scripts/grade.sh" 1 "$tmp/none" --out "$tmp/out0" 2>&1 | grep -E '^grade: (pristine|the solution)' || true
echo "grade_class: setup (pristine build or cache, the solution's timing): $(printf '%.0f' "$(echo "$(date +%s.%N) - $start" | bc)") s"
bash "$root/scripts/grade.sh" 1 "$tmp/class" --out "$tmp/out" 2>&1 | tee "$tmp/log" | grep -E '^    s[0-9]+: [0-9]/|^grade: [0-9]+ submissions'
awk '/^    s[0-9]+: [0-9]\/[0-9] in / { for (i = 1; i <= NF; i++) if ($i == "in") { t = $(i + 1); sum += t; n++; if (t > max) max = t } }
     END { if (n) printf "grade_class: %d submissions, mean %.1f s, worst %.1f s a submission (goal: 15 s)\n", n, sum / n, max }' "$tmp/log"
cat "$tmp/out/grades.csv"
