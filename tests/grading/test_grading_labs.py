#!/usr/bin/env python3
"""test_grading_labs.py — scripts/grade.sh on labs 2-4, two submissions each, made from a fresh
student copy of the lab (CTest: grading_shader_regions, label grading, runs lab 2's "mixed").

    python3 tests/grading/test_grading_labs.py [--mixed-only] [LAB…]      # default: 2 3 4

grading_lab1 (test_grading.py) holds the whole set of sandbox cases (attacks, archives, endless
loops, tampering, the regrade) on lab 1, whose regions are all C++ in one file. This test adds what
lab 1 cannot show: the same grader on a lab whose regions are shaders and C++ in several files:
  - "solved": every region the solution under a comment of the student's own, so no variant is the
    solution's text and each is built and run: every exercise 1;
  - "mixed", packed as a .zip with the copy inside one folder: the first exercise (a shader region
    in labs 2 and 4) does not compile, the rest are solved: 0 with "did not compile", then 1s. One
    broken region, even in a shader every picture compiles, costs only its own point.
--mixed-only grades "mixed" alone (CTest's run: its solved regions are graded as in "solved").
Checked for each lab: every grade cell, the notes, results.json, the report and the summary's link,
and that nothing outside the grader's output folder changed (a canary folder, the submissions).
Exit 77 (skip) where grading_lab1 would skip (no bubblewrap, or a student copy).
"""
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_grading as t  # noqa: E402  (region(), fill(), solution(), tree_hash(), the skip checks)

ROOT = t.ROOT


def exercises(lab):
    """The lab's exercises in its order, and each one's file (the course's model of an exercise)."""
    return [(e.name, e.file) for e in t.exercises.exercises_of(t.exercises.resolve_lab(lab))]


def grade_lab(tmp, lab, mixed_only):
    t0 = time.time()
    ex = exercises(lab)
    names = [n for n, _ in ex]
    for n, f in ex:
        t.FILE_OF[n] = f
    base = os.path.join(tmp, f"lab{lab}")
    copy, subs, canary = (os.path.join(base, d) for d in ("copy", "submissions", "canary"))
    subprocess.run(["bash", os.path.join(ROOT, "scripts/exercise.sh"), lab, "--out", copy], check=True, capture_output=True)
    os.makedirs(subs)
    os.makedirs(canary)
    open(os.path.join(canary, "keep.txt"), "w").write("the grader's machine: nothing may change this\n")

    if not mixed_only:
        solved = os.path.join(subs, "solved")
        shutil.copytree(copy, solved, symlinks=True)
        for n in names:
            t.fill(solved, n, [f"    // my own {n}\n"] + t.solution(n))
    mixed = os.path.join(base, "mixed-src", f"my-lab{lab}")
    shutil.copytree(copy, mixed, symlinks=True)
    for n in names[1:]:
        t.fill(mixed, n, [f"    // my own {n}\n"] + t.solution(n))
    t.fill(mixed, names[0], ["    float p = not_declared(1.0);\n"])  # an error in C++ and in GLSL alike
    with zipfile.ZipFile(os.path.join(subs, "mixed.zip"), "w") as z:
        for b, _, files in os.walk(mixed):
            for f in files:
                z.write(os.path.join(b, f), os.path.relpath(os.path.join(b, f), os.path.dirname(mixed)))
    expected = {} if mixed_only else {"solved": ([1] * len(names), [])}
    expected |= {"mixed": ([0] + [1] * (len(names) - 1), [f"did not compile: {names[0]}"])}

    before = (t.tree_hash(canary), t.tree_hash(subs))
    out = os.path.join(base, "out")
    t1 = time.time()
    r = subprocess.run(["bash", os.path.join(ROOT, "scripts/grade.sh"), lab, subs, "--out", out], capture_output=True, text=True)
    sys.stdout.write(r.stderr[-3000:])
    if r.returncode != 0:
        t.fail(f"lab {lab}: grade.sh exited {r.returncode}")
    problems = []
    if (t.tree_hash(canary), t.tree_hash(subs)) != before:
        problems.append("the canary or the submissions changed during grading")
    with open(os.path.join(out, "grades.csv"), newline="") as f:
        rows = list(csv.reader(f))
    if rows[0] != ["student"] + names + ["score", "notes"]:
        problems.append(f"grades.csv header {rows[0]} (expected the lab's order {names})")
    got = {row[0]: row for row in rows[1:]}
    for name, (grades, notes) in expected.items():
        row = got.get(name)
        if not row:
            problems.append(f"no row for {name}: {list(got)}")
            continue
        cells = [int(c) for c in row[1:1 + len(names)]]
        if cells != grades or int(row[-2]) != sum(grades):
            problems.append(f"{name}: grades {cells} score {row[-2]}, expected {grades}; notes: {row[-1]}")
        problems += [f"{name}: notes lack '{n}': {row[-1]}" for n in notes if n not in row[-1]]
        if "changed outside" in row[-1]:
            problems.append(f"{name}: notes say changed outside: {row[-1]}")
        res = json.load(open(os.path.join(out, "students", name, "results.json")))
        if res["score"] != sum(grades) or [x["score"] for x in res["tests"] if x["name"] in names] != grades:
            problems.append(f"{name}: results.json {json.dumps(res)[:300]}")
        problems += [f"{name}: the message for {x['name']} does not name it: {x['output'][:200]}"
                     for x in res["tests"] if x["name"] in names and not x["score"] and x["name"] not in x["output"]]
        if not os.path.isfile(os.path.join(out, "students", name, "report.html")):
            problems.append(f"{name}: no report.html")
        if f'href="students/{name}/report.html"' not in open(os.path.join(out, "index.html")).read():
            problems.append(f"index.html has no link to {name}'s report")
    for p in problems:
        print(f"FAIL lab {lab}: {p}")
    print(f"grading_shader_regions: lab {lab}: {'FAILED' if problems else 'every grade as expected, nothing outside changed'}"
          f" (grading {time.time() - t1:.0f} s, {time.time() - t0:.0f} s in all)")
    print(open(os.path.join(out, "grades.csv")).read())
    return not problems


def main():
    mixed_only = "--mixed-only" in sys.argv[1:]
    labs = [a for a in sys.argv[1:] if a != "--mixed-only"] or ["2", "3", "4"]
    t.skip_unless_gradable("grading_shader_regions")
    tmp = tempfile.mkdtemp(prefix="grade-labs-test-")
    os.chmod(tmp, 0o755)
    try:
        ok = [grade_lab(tmp, lab, mixed_only) for lab in labs]
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    sys.exit(0 if all(ok) else 1)


if __name__ == "__main__":
    main()
