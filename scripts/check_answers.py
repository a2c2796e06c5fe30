#!/usr/bin/env python3
"""check_answers.py — the exercises' declared answers, kept out of everything a student holds.

    python3 scripts/check_answers.py DIR N              # DIR (a student copy of lab N, or its student
                                                        # site) holds no answer of lab N or a later lab
    python3 scripts/check_answers.py --must-find DIR N  # the same search must find answers in DIR (the
                                                        # instructors' edition): the check can fail
    python3 scripts/check_answers.py --rewrite DIR N    # the student text: every answer span of the
                                                        # Markdown files in DIR becomes its question
    python3 scripts/check_answers.py --prove [COMMIT]   # the check can fail (CTest answers_check_can_fail):
                                                        # for every lab N it finds N's answers in this
                                                        # tree, in a copy of N whose Markdown keeps the
                                                        # answer spans, and in the copy COMMIT's
                                                        # exercise.sh writes (a tree before this check)
    python3 scripts/check_answers.py --prove-leaks COMMIT NAME…
                                                        # each exercise NAME's answer is found in the copy
                                                        # of its lab that COMMIT writes (a tree that still
                                                        # stated it: CTest answers_check_finds_old_leaks)

The answers are declared in docs/solutions/answers.json (instructors only: copies leave
docs/solutions/ out, `exercise.sh --left-out`): for each exercise, its lab and the forms its answer
takes in prose, comments and tests (a formula as the docs write it, an enum, a phrase, an expected
value). Every exercise `exercise.sh --list` names must be declared.

The search reads every text file under DIR (code, comments, Markdown, HTML, JS, test sources; a
file with a NUL byte in its first 8 KiB is binary) as a reader sees it and compares it with each
form, both normalised the same way: HTML tags stripped, entities decoded, Unicode NFKC (d² → d2,
⁻ᵀ → -T), every minus/dash sign as '-', ≤ ≥ as <= >=, TeX commands unwrapped (\\cdot, \\left …),
multiplication signs (· × * ⋅) and markup (` ^ { } \\) dropped, lower case, no whitespace. A form
is found when it is a substring of a file so read, across line breaks. Exit 0: none found (or, with
--must-find, some found); 1: otherwise, each hit named (file:line, exercise, form); 2: bad input.

Docs mark the answers they state for the student version (readable in raw Markdown; the
instructors' site shows the answer, the comment is invisible):
    <!-- answer NAME: the question a student gets instead -->the answer<!-- /answer -->
--rewrite replaces such a span with its question when NAME is an exercise of lab N or a later lab,
and with the answer alone (markers dropped) for an earlier lab's exercise: once lab N is handed out
the earlier labs' answers are no secret (their solutions are in the copy).
"""
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unicodedata
from bisect import bisect_right

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from course import exercises as course_exercises  # noqa: E402 (beside this file)

ROOT = course_exercises.ROOT
ANSWERS = os.path.join(ROOT, "docs", "solutions", "answers.json")
SPAN = re.compile(r"<!-- answer ([a-z0-9_]+): (.*?) -->(.*?)<!-- /answer -->", re.S)
SKIP_DIRS = {".git", "node_modules", "__pycache__"}

_tex = [(re.compile(p), r) for p, r in [
    (r"\\(?:cdot|times|left|right|mathit|mathrm|mathbf|operatorname|text|quad|qquad|displaystyle)(?![a-z])", ""),
    (r"\\[,;:! ]", ""), (r"\\leq?(?![a-z])", "<="), (r"\\geq?(?![a-z])", ">="),
    (r"\\([a-z]+)", r"\1"),
]]
_chars = str.maketrans({
    "\u2212": "-", "\u2013": "-", "\u2014": "-", "\u2010": "-", "\u2011": "-", "\u2012": "-",
    "\u2264": "<=", "\u2265": ">=", "\u2032": "'", "\u2019": "'", "\u2018": "'",
    "\u00b7": "", "\u00d7": "", "\u22c5": "", "\u2217": "", "*": "", "\u2219": "",
    "^": "", "{": "", "}": "", "`": "", "\\": "",
    "\u200b": "", "\u200c": "", "\u200d": "", "\u2061": "", "\u2062": "", "\u2063": "", "\ufeff": "",
})


def norm(s):
    """A piece of text as the search compares it (see the top of this file)."""
    s = html.unescape(s)
    s = unicodedata.normalize("NFKC", s)
    s = s.lower()
    for p, r in _tex:
        s = p.sub(r, s)
    s = s.translate(_chars)
    return re.sub(r"\s+", "", s)


def fail(msg):
    print(f"check_answers: {msg}", file=sys.stderr)
    sys.exit(2)


def load_answers():
    try:
        with open(ANSWERS, encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        fail(f"{ANSWERS}: {e}")
    exercises = data.get("exercises")
    if not isinstance(exercises, dict) or not exercises:
        fail(f"{ANSWERS}: no \"exercises\" object")
    for name, e in exercises.items():
        if not isinstance(e.get("lab"), int) or not isinstance(e.get("forms"), list) or not e["forms"]:
            fail(f"{ANSWERS}: exercise {name}: needs \"lab\" (a number) and \"forms\" (a non-empty list)")
        for form in e["forms"]:
            if len(norm(form)) < 6:
                fail(f"{ANSWERS}: exercise {name}: form {form!r} is too short to search for (6+ characters normalised)")
    return exercises


def listed_exercises():
    """name → lab number: every lab's own exercises, from the markers in the labs' code
    (scripts/course/exercises.py; what `exercise.sh --list` lists)."""
    return {e.name: e.number for e in course_exercises.all_exercises(ROOT)}


def text_files(top):
    for dirpath, dirnames, filenames in os.walk(top):
        dirnames[:] = sorted(d for d in dirnames if d not in SKIP_DIRS and not (
            dirpath == top and os.path.exists(os.path.join(top, "CMakeLists.txt")) and
            (d.startswith("build") or d in ("student", "out"))))  # a project's build outputs
        for f in sorted(filenames):
            p = os.path.join(dirpath, f)
            if os.path.islink(p) or not os.path.isfile(p):
                continue
            with open(p, "rb") as fh:
                data = fh.read()
            if b"\0" in data[:8192]:
                continue
            yield p, data.decode("utf-8", errors="replace")


def seen_lines(path, text):
    """The lines of a file as a reader sees them (HTML: without tags, <style>, <svg> paths)."""
    if path.endswith((".html", ".htm")):
        text = re.sub(r"<style[\s\S]*?</style>", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.I)
        text = re.sub(r"<[^>]*>", lambda m: "\n" * m.group(0).count("\n"), text)
    return text.split("\n")


_normalised = {}  # (path, mtime, size) → normalised(): --prove searches the same tree once per lab


def normalised(path, text):
    """(the file read as the search compares it, where each of its lines starts in that text)."""
    st = os.stat(path)
    key = (path, st.st_mtime_ns, st.st_size)
    if key not in _normalised:
        starts, parts, at = [], [], 0
        for line in seen_lines(path, text):
            n = norm(line)
            starts.append(at)
            parts.append(n)
            at += len(n)
        _normalised[key] = ("".join(parts), starts)
    return _normalised[key]


def search(top, forms):
    """Yields (path, line, exercise, form) for every form found in a text file under top."""
    wanted = [(name, form, norm(form)) for name, form in forms]
    for path, text in text_files(top):
        whole, starts = normalised(path, text)
        for name, form, key in wanted:
            i = whole.find(key)
            if i >= 0:
                yield os.path.relpath(path, top), bisect_right(starts, i), name, form


def rewrite(top, n, exercises):
    changed = 0
    for path, text in text_files(top):
        if not path.endswith(".md") or "<!-- answer " not in text:
            continue

        def one(m):
            name, question, answer = m.group(1), m.group(2), m.group(3)
            if name not in exercises:
                fail(f"{path}: an answer span for '{name}', which answers.json does not declare")
            return question if exercises[name]["lab"] >= n else answer

        new = SPAN.sub(one, text)
        if "<!-- answer " in new or "<!-- /answer -->" in new:
            fail(f"{path}: an answer span that is not closed or not of the form "
                 "<!-- answer NAME: question -->answer<!-- /answer -->")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(new)
        changed += 1
    print(f"check_answers: {changed} Markdown file(s) of {top} rewritten for lab {n}")


def prove(commit, exercises):
    """Exit 0 when the search finds lab N's answers where they are, for every lab N."""
    if os.path.exists(os.path.join(ROOT, ".student-copy")):
        print("check_answers: this is a student copy: the proof runs in the complete project (skipped)")
        return 77
    problems = 0

    def must_find(what, top, n):
        nonlocal problems
        forms = [(name, f) for name, e in sorted(exercises.items()) if e["lab"] >= n for f in e["forms"]]
        hits = list(search(top, forms))
        print(f"  lab {n}, {what}: {len(hits)} answer(s) found"
              + (f", e.g. {hits[0][0]}:{hits[0][1]} ({hits[0][2]})" if hits else ": FAIL, the check cannot fail there"))
        problems += not hits

    tmp = tempfile.mkdtemp(prefix="check-answers-")
    try:
        old = None
        if commit:
            os.makedirs(os.path.join(tmp, "old"))
            archive = subprocess.run(f"git -C '{ROOT}' archive {commit} | tar -x -C '{tmp}/old'", shell=True,
                                     capture_output=True, text=True)
            if archive.returncode == 0:
                old = os.path.join(tmp, "old")
            else:
                print(f"check_answers: commit {commit} is not in this clone (a shallow clone?): "
                      "the copies it wrote are not tried")
        spans = [p for p, t in text_files(ROOT) if p.endswith(".md") and "<!-- answer " in t]
        if not spans:
            print("check_answers: FAIL: no Markdown file here marks an answer span")
            problems += 1
        for n in sorted({e["lab"] for e in exercises.values()}):
            must_find("the instructors' tree", ROOT, n)
            copy = os.path.join(tmp, f"copy{n}")
            subprocess.run(["bash", os.path.join(ROOT, "scripts", "exercise.sh"), str(n), "--out", copy],
                           cwd=ROOT, check=True, capture_output=True)
            for p in spans:  # a copy made without the span replacement: the instructors' Markdown
                rel = os.path.relpath(p, ROOT)
                if os.path.exists(os.path.join(copy, rel)):
                    shutil.copyfile(p, os.path.join(copy, rel))
            must_find("a copy with the instructors' Markdown", copy, n)
            if old:
                oldcopy = os.path.join(tmp, f"old{n}")
                subprocess.run(["bash", os.path.join(old, "scripts", "exercise.sh"), str(n), "--out", oldcopy],
                               cwd=old, check=True, capture_output=True)
                must_find(f"the copy commit {commit} writes", oldcopy, n)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"check_answers: {'FAIL: ' + str(problems) + ' place(s) where the check finds nothing' if problems else 'the check fails wherever answers are'}")
    return 1 if problems else 0


def prove_leaks(commit, names, exercises):
    """Exit 0 when, for each exercise in names, the search finds its answer in the copy of its lab
    that commit's exercise.sh writes: the forms declared for a leak catch the tree that had it."""
    if os.path.exists(os.path.join(ROOT, ".student-copy")):
        print("check_answers: this is a student copy: the proof runs in the complete project (skipped)")
        return 77
    unknown = [n for n in names if n not in exercises]
    if unknown or not names:
        fail(f"--prove-leaks: not exercises of answers.json: {' '.join(unknown) or '(none given)'}")
    tmp = tempfile.mkdtemp(prefix="check-leaks-")
    problems = 0
    try:
        old = os.path.join(tmp, "old")
        os.makedirs(old)
        archive = subprocess.run(f"git -C '{ROOT}' archive {commit} | tar -x -C '{old}'", shell=True, capture_output=True, text=True)
        if archive.returncode != 0:
            print(f"check_answers: commit {commit} is not in this clone (a shallow clone?): nothing to prove against (skipped)")
            return 77
        for lab in sorted({exercises[n]["lab"] for n in names}):
            copy = os.path.join(tmp, f"copy{lab}")
            subprocess.run(["bash", os.path.join(old, "scripts", "exercise.sh"), str(lab), "--out", copy],
                           cwd=old, check=True, capture_output=True)
            for n in sorted(n for n in names if exercises[n]["lab"] == lab):
                hits = list(search(copy, [(n, f) for f in exercises[n]["forms"]]))
                print(f"  {n} (lab {lab}) in the copy {commit} writes: "
                      + (f"{len(hits)} found, e.g. {os.path.relpath(hits[0][0], copy)}:{hits[0][1]} ({hits[0][3]})" if hits
                         else "FAIL, not found"))
                problems += not hits
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"check_answers: {'FAIL: ' + str(problems) + ' leak(s) the forms do not catch' if problems else 'every leak of ' + commit + ' is caught'}")
    return 1 if problems else 0


def main(argv):
    if argv[:1] in (["-h"], ["--help"]):  # the docstring above, nothing run
        print(__doc__.strip())
        return 0
    if argv and argv[0] == "--prove-leaks":
        if len(argv) < 3:
            fail("usage: check_answers.py --prove-leaks COMMIT NAME…")
        return prove_leaks(argv[1], argv[2:], load_answers())
    if argv and argv[0] == "--prove":
        if len(argv) > 2:
            fail("usage: check_answers.py --prove [COMMIT]")
        return prove(argv[1] if len(argv) == 2 else None, load_answers())
    mode = "check"
    if argv and argv[0] in ("--must-find", "--rewrite"):
        mode = argv.pop(0)[2:]
    if len(argv) != 2 or not os.path.isdir(argv[0]) or not re.fullmatch(r"(lab)?\d+(_\w+)?", argv[1]):
        fail("usage: check_answers.py [--must-find | --rewrite] DIR N (a folder and a lab: 2, lab2 or lab2_lighting)")
    top, n = argv[0], int(re.match(r"(?:lab)?(\d+)", argv[1]).group(1))
    exercises = load_answers()
    if mode == "rewrite":
        rewrite(top, n, exercises)
        return 0
    listed = listed_exercises()
    for name, lab in sorted(listed.items()):
        if name not in exercises:
            fail(f"{ANSWERS}: exercise {name} (lab {lab}) declares no answer forms")
        if exercises[name]["lab"] != lab:
            fail(f"{ANSWERS}: exercise {name} is lab {lab}'s (exercise.sh --list), not lab {exercises[name]['lab']}'s")
    forms = [(name, f) for name, e in sorted(exercises.items()) if e["lab"] >= n for f in e["forms"]]
    if not forms:
        fail(f"no exercise of lab {n} or later: nothing to look for")
    hits = list(search(top, forms))
    for i, (path, line, name, form) in enumerate(hits):
        if i < 40:
            print(f"{'found' if mode == 'must-find' else 'FAIL'} {path}:{line}: the answer of {name} "
                  f"(lab {exercises[name]['lab']}): {form}")
    if len(hits) > 40:
        print(f"… and {len(hits) - 40} more")
    names = len({name for name, _ in forms})
    print(f"check_answers: {top}: {len(forms)} forms of {names} exercises of lab {n} and later, {len(hits)} found")
    if mode == "must-find":
        if not hits:
            print("check_answers: FAIL: no answer found where answers are (the check cannot fail?)")
            return 1
        return 0
    return 1 if hits else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
