#!/usr/bin/env python3
"""exercise_tools_agree.py — every tool of the course sees the same exercises.

    python3 tests/exercise_tools_agree.py [--no-copies]

The exercises are read in one place, scripts/course/exercises.py; this test holds each tool that
uses them to what `bash scripts/exercise.sh --list --json` says, lab by lab (names, files, marker
lines, hints, tests):
  - scripts/check_answers.py's list of exercises and their labs;
  - scripts/comment_answers.py's input (solution_code of the lab alone: each row inside its
    exercise's region, every exercise there);
  - the manifest the C++ hints and the grader read (`exercise.sh --manifest OUT`): each lab's own
    exercises, complete and solved in this project, and its "!order" names, the lab's exercises;
  - the course site's exercise table (`node site/build.mjs --exercises LAB`);
  - the solution lines the answer checks search for (`--solution-lines --json` and the text form:
    the same rows, each inside one of the lab's or a later lab's exercises);
  - the student copy (`exercise.sh LAB --out DIR`, one per lab): its markers are the lab's exercises
    as TODOs in the same files, each file is stub_text() of the project's, each region holds the
    exercise's stub lines, its .exercise-stubs holds each stub, and its manifest sees every
    exercise of the lab as a stub still to do.
Then it proves it can fail: a copy with a marker renamed, a copy with a stub changed in
.exercise-stubs, and each tool's view above with one exercise renamed or moved must each be
reported. --no-copies leaves the copies out (seconds instead of a minute), self-check included.

Prints one line per disagreement; exit 0 when all agree, 1 when one does not (or the check could
not fail), 77 in a student copy (the copies are written from the complete project).
"""
import copy
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from course import exercises as ex  # noqa: E402
import check_answers  # noqa: E402
import comment_answers  # noqa: E402,F401 (it must import: exercise.sh --check-copy runs it)

EXERCISE_PY = os.path.join(ROOT, "scripts", "exercise.py")


def cli(*args):
    """The stdout of `exercise.py ARGS` (exit status 0 required)."""
    return subprocess.run([sys.executable, EXERCISE_PY, *args], cwd=ROOT, check=True, capture_output=True,
                          text=True).stdout


def rows(listing):
    """(name, file, line, hint, tests) of each exercise of a --list --json style list."""
    return [(e["name"], e["file"], int(e["line"]), e["hint"], tuple(e["tests"])) for e in listing]


def differ(what, lab, got, want):
    """The problem lines when lists got and want differ (the first difference named)."""
    if got == want:
        return []
    for i, (g, w) in enumerate(zip(got, want)):
        if g != w:
            return [f"FAIL {what}, {lab}: exercise {i + 1} is {g!r}, the listing's is {w!r}"]
    return [f"FAIL {what}, {lab}: {len(got)} exercises, the listing has {len(want)} "
            f"({', '.join(str(r[0]) for r in (got[len(want):] or want[len(got):]))} too many or missing)"]


# ---------------------------------------------------------------- the views of each tool
def views(labs):
    """lab → each tool's view of the lab's exercises, as comparable lists; "listing" is the
    reference."""
    v = {"listing": {}, "module": {}, "check_answers": {}, "comment_answers": {}, "manifest": {},
         "solution_lines": {}, "site": {}}
    every = rows(json.loads(cli("--list", "--json")))
    tmp = tempfile.mkdtemp(prefix="exercise-manifest-")
    try:
        out = os.path.join(tmp, "manifest.json")
        cli("--manifest", out)
        with open(out, encoding="utf-8") as f:
            manifest = json.load(f)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    listed = check_answers.listed_exercises()
    first_lab = {}
    for m in manifest["exercises"]:
        first_lab.setdefault(m["name"], m["lab"])
    v["listing-all"], v["manifest-entries"] = every, manifest
    site = shutil.which("node") and os.path.isdir(os.path.join(ROOT, "site", "node_modules"))
    for lab in labs:
        n = ex.lab_number(lab)
        v["listing"][lab] = rows(json.loads(cli("--list", "--json", lab)))
        v["module"][lab] = [(e.name, e.file, e.line, e.hint, e.tests) for e in ex.exercises_of(lab)]
        v["check_answers"][lab] = sorted(name for name, k in listed.items() if k == n)
        seen = []
        for name, _, where, _ in ex.solution_code(lab, only=True):
            file = where.rsplit(":", 1)[0]
            if (name, file) not in seen:
                seen.append((name, file))
        v["comment_answers"][lab] = seen
        v["manifest"][lab] = [(m["name"], m["file"], m["line"], m["hint"], tuple(m["tests"]))
                              for m in manifest["exercises"] if m["lab"] == n and first_lab[m["name"]] == n]
        v["solution_lines"][lab] = (json.loads(cli("--solution-lines", "--json", lab)), cli("--solution-lines", lab))
        if site:
            listing = subprocess.run(["node", os.path.join(ROOT, "site", "build.mjs"), "--exercises", lab], cwd=ROOT,
                                     check=True, capture_output=True, text=True).stdout
            v["site"][lab] = rows(json.loads(listing))
    if not site:
        print("SKIPPED the course site's view: node or site/node_modules is missing (scripts/setup.sh installs them)")
        del v["site"]
    return v


def check_views(v, labs):
    """The problems of the views against the listing."""
    problems = []
    ref = v["listing"]
    if v["listing-all"] != [r for lab in labs for r in ref[lab]]:
        problems.append("FAIL --list --json without LAB is not every lab's --list --json LAB in turn")
    table = ex.graded_table()
    regions = {}  # name → (file, marker line, END line) of the own exercises of every lab
    for lab in labs:
        for e in ex.exercises_of(lab):
            regions[e.name] = (e.file, e.line, e.end)
    for lab in labs:
        want = ref[lab]
        problems += differ("the module (exercises_of)", lab, v["module"][lab], want)
        problems += differ("check_answers.py's exercises", lab, v["check_answers"][lab], sorted(r[0] for r in want))
        problems += differ("comment_answers.py's input (solution_code)", lab, v["comment_answers"][lab],
                           [(r[0], r[1]) for r in want])
        for name, _, where, _ in ex.solution_code(lab, only=True):
            file, line = where.rsplit(":", 1)
            reg = regions.get(name)
            if not reg or reg[0] != file or not reg[1] < int(line) < (reg[2] or 10 ** 9):
                problems.append(f"FAIL solution_code, {lab}: {where} is not inside exercise {name}'s region")
        problems += differ("the manifest", lab, v["manifest"][lab], want)
        if "site" in v:
            problems += differ("the course site's table (build.mjs --exercises)", lab, v["site"][lab],
                               [(n, f, k, h.strip(), t) for n, f, k, h, t in want])
        order = list(table.order.get(lab.split("_", 1)[0], ()))
        names = [r[0] for r in want]
        if names[:len(order)] != order:
            problems.append(f"FAIL tests/graded_exercises.txt's !order for {lab} ({' '.join(order)}) is not the "
                            f"first of its exercises in the listing ({' '.join(names)})")
        as_json, as_text = v["solution_lines"][lab]
        if ex.join_lines("\037".join((r["name"], r["where"], r["code"])) for r in as_json) != as_text:
            problems.append(f"FAIL --solution-lines {lab}: the text form and --json differ")
        later = {e.name for k in ex.labs_from(lab) for e in ex.exercises_of(k)}
        for r in as_json:
            file, line = r["where"].rsplit(":", 1)
            reg = regions.get(r["name"])
            if r["name"] not in later or not reg or reg[0] != file or not reg[1] < int(line) < (reg[2] or 10 ** 9):
                problems.append(f"FAIL --solution-lines {lab}: {r['where']} is not inside exercise {r['name']}'s region")
        if not as_json:
            problems.append(f"FAIL --solution-lines {lab}: no line to look for")
    for m in v["manifest-entries"]["exercises"]:
        if not m["todo"] and (not m["complete"] or m["code"] == m["stub"]):
            problems.append(f"FAIL the manifest: {m['file']}:{m['line']} ({m['name']}) is not a complete, solved "
                            "exercise in the complete project")
    return problems


# ---------------------------------------------------------------- the student copies
def check_copy(copy, lab):
    """The problems of copy (written by exercise.py LAB) against the project's markers."""
    problems = []
    mine = ex.exercises_of(lab)
    theirs = ex.exercises_of(lab, copy)
    if [(e.name, e.file) for e in theirs] != [(e.name, e.file) for e in mine]:
        problems.append(f"FAIL the copy of {lab}: its exercises are {[e.name for e in theirs]}, "
                        f"the project's {[e.name for e in mine]}")
    for e in theirs:
        if not e.todo:
            problems.append(f"FAIL the copy of {lab}: {e.file}:{e.line} ({e.name}) is not a TODO marker")
    by_file = {}
    for e in mine:
        by_file.setdefault(e.file, []).append(e.name)
    for file, names in by_file.items():
        copied = ex.read_text(os.path.join(copy, file))
        if ex.stub_text(ex.read_text(os.path.join(ROOT, file)), names) != copied:
            problems.append(f"FAIL the copy of {lab}: {file} is not stub_text() of the project's")
        lines = ex.split_lines(copied)
        for name in names:
            e = next(x for x in mine if x.name == name)
            region = ex.find_region(lines, name)
            if region is None:
                problems.append(f"FAIL the copy of {lab}: {file} has no region of exercise {name}")
                continue
            if tuple(lines[region[0] + 1:region[1]]) != e.stub:
                problems.append(f"FAIL the copy of {lab}: exercise {name}'s region in {file} is not its stub")
            if not lines[region[0]].endswith(f"// TODO EXERCISE {name}: {e.hint}" +
                                             (f" Checked by {', '.join(e.tests)}." if e.tests else "")):
                problems.append(f"FAIL the copy of {lab}: exercise {name}'s marker in {file} is not the project's hint")
    want = {f"{e.file} {e.name}": "".join(ex.bare(c) for _, c in e.stub_code) for e in mine if e.stub_code}
    if ex.copy_stubs(copy) != want:
        problems.append(f"FAIL the copy of {lab}: its .exercise-stubs is not the stubs of its exercises")
    n = ex.lab_number(lab)
    for m in ex.manifest(copy)["exercises"]:
        own = m["name"] in by_file.get(m["file"], ())
        if m["lab"] == n and own and not (m["todo"] and m["complete"] and m["code"] == m["stub"]):
            problems.append(f"FAIL the copy of {lab}: its manifest does not see {m['name']} as a stub to do")
        if m["lab"] < n and m["todo"]:
            problems.append(f"FAIL the copy of {lab}: {m['file']}:{m['line']} of an earlier lab is a TODO")
    return problems


def write_copy(lab, out):
    subprocess.run([sys.executable, EXERCISE_PY, lab, "--out", out], cwd=ROOT, check=True, stdout=subprocess.DEVNULL)


# ---------------------------------------------------------------- the check can fail
def self_check(v, labs, copy_of):
    """Problems where a corrupted input goes unreported."""
    problems = []

    def must_fail(what, found):
        if not found:
            problems.append(f"FAIL self-check: {what} is not reported: the check cannot fail")
        else:
            print(f"self-check: {what}: reported ({found[0][:100]}…)")

    lab = labs[0]
    for tool in [t for t in ("module", "check_answers", "comment_answers", "manifest", "site") if t in v]:
        broken = copy.deepcopy(v)
        first = broken[tool][lab][0]
        if isinstance(first, str):  # check_answers: a name
            changed = first + "_renamed"
        elif len(first) == 5:  # the marker one line lower
            changed = first[:2] + (first[2] + 1,) + first[3:]
        else:  # comment_answers: (name, file), another name
            changed = (first[0] + "_renamed",) + first[1:]
        broken[tool][lab][0] = changed
        must_fail(f"{tool}'s view with {lab}'s first exercise changed", check_views(broken, labs))
    if copy_of:
        lab = next(iter(copy_of))
        e = ex.exercises_of(lab)[0]
        bad = copy_of[lab] + "-renamed"
        shutil.copytree(copy_of[lab], bad, symlinks=True)
        path = os.path.join(bad, e.file)
        text = ex.read_text(path)
        with open(path, "w", encoding="utf-8", errors="surrogateescape", newline="") as f:
            f.write(text.replace(f"// TODO EXERCISE {e.name}: ", f"// TODO EXERCISE {e.name}_renamed: ", 1))
        must_fail(f"a copy of {lab} with the marker of {e.name} renamed", check_copy(bad, lab))
        shutil.rmtree(bad)
        shutil.copytree(copy_of[lab], bad, symlinks=True)
        stubs = ex.read_text(os.path.join(bad, ex.STUBS))
        with open(os.path.join(bad, ex.STUBS), "w", encoding="utf-8", newline="") as f:
            f.write(re.sub(rf"^({re.escape(e.file)} {e.name}) (.*)$", r"\1 1 + \2", stubs, count=1, flags=re.M))
        must_fail(f"a copy of {lab} with the stub of {e.name} changed in .exercise-stubs", check_copy(bad, lab))
        shutil.rmtree(bad)
    return problems


def main(argv):
    if argv[:1] in (["-h"], ["--help"]):
        print(__doc__.strip())
        return 0
    if argv not in ([], ["--no-copies"]):
        print("exercise_tools_agree: usage: exercise_tools_agree.py [--no-copies]", file=sys.stderr)
        return 2
    if os.path.exists(os.path.join(ROOT, ".student-copy")):
        print("exercise_tools_agree: this is a student copy: the tools are checked in the complete project (skipped)")
        return 77
    labs = [lab for lab in ex.labs() if ex.exercises_of(lab)]
    if not labs:
        print("FAIL no lab has exercises: nothing to compare")
        return 1
    v = views(labs)
    problems = check_views(v, labs)
    print(f"exercise_tools_agree: {sum(len(v['listing'][lab]) for lab in labs)} exercises of {len(labs)} labs: "
          f"{', '.join(t for t in v if t not in ('listing', 'listing-all', 'manifest-entries'))} against --list --json")
    copy_of = {}
    tmp = tempfile.mkdtemp(prefix="exercise-tools-agree-")
    try:
        if "--no-copies" not in argv:
            for lab in labs:
                copy_of[lab] = os.path.join(tmp, lab)
                write_copy(lab, copy_of[lab])
                found = check_copy(copy_of[lab], lab)
                problems += found
                print(f"the copy of {lab}: {len(ex.exercises_of(lab))} exercises, {len(found)} problem(s)")
        problems += self_check(v, labs, copy_of)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    for p in problems:
        print(p)
    if problems:
        print(f"exercise_tools_agree: FAILED ({len(problems)} problem(s))")
        return 1
    print("exercise_tools_agree: passed (every tool sees the same exercises; each disagreement tried is reported)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
