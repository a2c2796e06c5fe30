#!/usr/bin/env bash
# grade_class.sh — time scripts/grade.sh on a class of 10 submissions of a lab (issue 39's goals,
# on 2 cores after the first build: ≤ 15 s a lab 1 submission, ≤ 60 s a lab 3 or lab 4 one).
#
#   bash bench/grade_class.sh [LAB] [--keep DIR]      LAB: 1 (default) … 4
#
# The class is written from a fresh student copy of the lab. Every region of every student differs
# from the solution's text (a comment line of their own), as real students' code does, so no
# variant is the solution's and each submission costs what a real one costs: 5 isolated builds and
# runs, plus one run as handed in. The mix: 6 solved, 2 partial (the first two exercises; all but
# the last two), 1 not compiling in its third exercise's region, 1 left as handed out. Prints each submission's time, the mean and the worst, the CPU model, the
# cores and LP_NUM_THREADS. The pristine build (once per repository state) is timed apart.
set -euo pipefail
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
lab=1
case "${1:-}" in [1-9]) lab=$1; shift ;; esac
keep=""
[ "${1:-}" = --keep ] && keep="${2:?--keep needs a folder}"
goal=$([ "$lab" = 1 ] && echo 15 || echo 60)
tmp=$(mktemp -d /tmp/grade-bench-XXXXXX)
chmod 755 "$tmp"
trap '[ -n "$keep" ] && rm -rf "$keep" && cp -a "$tmp" "$keep"; rm -rf "$tmp"' EXIT
bash "$root/scripts/exercise.sh" "$lab" --out "$tmp/copy" >/dev/null
python3 - "$root" "$tmp" "$lab" <<'PY'
import os, shutil, sys
root, tmp, lab = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(root, "tests", "grading"))
sys.path.insert(0, os.path.join(root, "scripts", "grade"))
import model
import test_grading as t
# the lab's exercises and their files, in the lab's order (the course's model of an exercise)
ex = []
for e in model.exercises_of(model.resolve_lab(lab)):
    t.FILE_OF[e["name"]] = e["file"]
    ex.append(e["name"])
os.makedirs(os.path.join(tmp, "class"))
mix = {f"s{i:02d}": ex for i in range(1, 7)}
mix.update({"s07": ex[:2], "s08": ex[:-2], "s09": ex, "s10": []})
for name, solved in mix.items():
    d = os.path.join(tmp, "class", name)
    shutil.copytree(os.path.join(tmp, "copy"), d, symlinks=True)
    for e in solved:
        t.fill(d, e, [f"    // {name}'s own {e}\n"] + t.solution(e))
    if name == "s09":  # an undeclared function: an error in C++ and in GLSL alike
        t.fill(d, ex[2], ["    float p = not_declared(1.0);\n"])
PY
echo "grade_class: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'), $(nproc) cores, LP_NUM_THREADS=${LP_NUM_THREADS:-unset (lavapipe: one thread a core)}, load $(cut -d' ' -f1-3 /proc/loadavg)"
start=$(date +%s.%N)
# the pristine build and the solution's timing, apart (an empty class)
mkdir -p "$tmp/none/x" && bash "$root/scripts/grade.sh" "$lab" "$tmp/none" --out "$tmp/out0" 2>&1 | grep -E '^grade: (pristine|the solution)' || true
echo "grade_class: setup (pristine build or cache, the solution's timing): $(printf '%.0f' "$(echo "$(date +%s.%N) - $start" | bc)") s"
bash "$root/scripts/grade.sh" "$lab" "$tmp/class" --out "$tmp/out" 2>&1 | tee "$tmp/log" | grep -E '^    s[0-9]+: [0-9]+/|^grade: [0-9]+ submissions'
awk -v goal="$goal" '/^    s[0-9]+: [0-9]+\/[0-9]+ in / { for (i = 1; i <= NF; i++) if ($i == "in") { t = $(i + 1); sum += t; n++; if (t > max) max = t } }
     END { if (n) printf "grade_class: %d submissions, mean %.1f s, worst %.1f s a submission (goal: %d s)\n", n, sum / n, max, goal }' "$tmp/log"
cat "$tmp/out/grades.csv"
