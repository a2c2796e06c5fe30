#!/usr/bin/env python3
"""grade.py — grade every submission of a lab (scripts/grade.sh is the command; see docs/solutions.md
"Grading a class"), or prove that the lab's tests grade its exercises (CTest grader_labN).

    python3 scripts/grade/grade.py LAB SUBMISSIONS [--out DIR] [--jobs N] [--cache DIR]
    python3 scripts/grade/grade.py --prove BUILD LAB [--rows]      (prove.py)

How a grade is made:
  * The pristine copy: the student copy of LAB (scripts/exercise.sh) with the lab's own folders
    replaced by the instructors' solved ones, configured and built once inside the sandbox at the
    fixed path /grade/work, cached (--cache, default /tmp/vulkan-labs-grade-UID) under a key of the
    repository's HEAD and uncommitted changes; the cache keeps the newest two per lab (variants.py).
  * Only the exercises count: from a submission the grader reads only the text between each
    `TODO EXERCISE name` (or `EXERCISE name`) line and its `END EXERCISE` line. Every other file is
    compared with the handed-out copy and only listed ("changed outside the exercises";
    submissions.py).
  * Isolated credit: exercise e is graded on a copy of the pristine build in which only e's region
    holds the student's code (every other exercise: the solution). Only the changed files rebuild
    (make, object reuse); only the tests that check e run (its "Checked by" list). One more run
    with all the student's regions is "as handed in". Identical variants (a region equal to the
    solution, two students with the same stub) are built and run once.
  * No verdict comes from a process that runs the student's code (tests/probe.h). Each test runs
    twice: the probe, in the sandbox with the variant's build, records every value the lab's code
    computes for it (LAB_PROBE=record); then the judge, the same test built from the handed-out copy
    (every exercise its stub: no student code, no solution), reads those values back instead of
    computing them (LAB_PROBE=replay) and its own checks give the verdict. What the probe prints,
    and how it exits, decide nothing but a crash or a hang (runs.py).
  * A region that steps outside its exercise (region_check.py: unbalanced braces, preprocessor
    lines, output, process, file or dynamic-loading calls, inline assembly, builtins, the test side)
    gets 0 and a note that says why.
  * Every build and test runs in the sandbox (sandbox.py).
The modules: model.py (the course's exercises, read through scripts/course/exercises.py),
sandbox.py, submissions.py, variants.py, runs.py, reports.py, prove.py; this file is the command.
"""
import argparse
import concurrent.futures as cf
import fnmatch
import json
import os
import re
import shutil
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import model  # noqa: E402
from model import ROOT, die, log, resolve_lab, split_lines  # noqa: E402
from reports import STUDENTS, compiler_errors, write_outputs  # noqa: E402
from runs import Scheduler, test_message  # noqa: E402
from sandbox import check_isolation, kill_on_signals  # noqa: E402
from submissions import Submission, changed_outside, open_submission, read_regions, student_name  # noqa: E402
from variants import SandboxVariants, pristine, with_regions  # noqa: E402
# What the grader's own tests (tests/grading/) reach through this module.
from runs import MAX_TEST_OUTPUT, run_tests  # noqa: E402,F401
from sandbox import SANDBOX_NPROC, SANDBOX_TMP, WORK, chown_tree, run_limited, sandbox  # noqa: E402,F401


class Grader(SandboxVariants):
    """A lab ready to grade: its exercises, the pristine copy, and the graded tests timed on the solution."""

    def __init__(self, lab, cache_dir, jobs, scratch):
        self.jobs = jobs
        self.trust_regions = False
        self.exercises = model.exercises_of(lab)
        if not self.exercises:
            die(f"{lab} has no exercises")
        super().__init__(lab, pristine(lab, cache_dir, jobs), scratch)
        self.solved = {}  # file → lines of the solved (instructors') file
        for e in self.exercises:
            if e["file"] not in self.solved:
                with open(os.path.join(self.work, e["file"])) as f:
                    self.solved[e["file"]] = split_lines(f.read())
            if not model.find_region(self.solved[e["file"]], e["name"]):
                die(f"{e['file']}: exercise {e['name']} has no END EXERCISE", 1)
        # the tests: discovered and timed on the pristine build
        with open(os.path.join(self.pdir, "tests.json")) as f:
            self.tests = {b: [tuple(t) for t in ts] for b, ts in json.load(f).items()}  # binary → [(name, env)]
        self.binary_of = {n: b for b, ts in self.tests.items() for n, _ in ts}
        self.select_tests()
        self.time_solution()

    def select_tests(self):
        """An exercise's grade: the tests of its "Checked by" list (the tests written to check it),
        not every test that tests/graded_exercises.txt says can blame it (a textured picture needs
        texture_terms: running all of those for every exercise would multiply a submission's time)."""
        names = sorted(self.binary_of)
        for e in self.exercises:
            sel = {n for n in names if any(fnmatch.fnmatchcase(n, p) for p in e["checked"])}
            if not sel:
                die(f"exercise {e['name']}: no test of the copy matches its Checked by ({' '.join(e['checked'])})", 1)
            e["tests"] = sorted(sel)
        self.all_tests = sorted({t for e in self.exercises for t in e["tests"]})

    def time_solution(self):
        """Runs the solution through probe and judge (refusing to start if it fails a graded test)
        and sets each test's limits from its times."""
        log(f"grade: {self.lab}: {len(self.exercises)} exercises, {len(self.all_tests)} graded tests; timing the solution")
        t0 = time.time()
        job = self.new_job()
        first = {n: 120.0 for n in self.all_tests}
        base, probe = self.run_judged(job, self.all_tests, first, first, start_limit=120)
        shutil.rmtree(job, ignore_errors=True)
        shutil.rmtree(job + "-judge", ignore_errors=True)
        bad = [n for n in self.all_tests if base[n]["status"] != "ok"]
        if bad:
            n = bad[0]
            why = ("the probe" if probe[n]["status"] not in ("ok", "failed") else
                   "the judge, on the solution's own values: a value the test takes from the lab without LAB_PROBE (tests/probe.h) "
                   "comes from a stub there" if probe[n]["status"] == "ok" else "the probe (the solution's own run)")
            die(f"the solution itself fails {len(bad)} graded test(s) ({', '.join(bad[:5])}) in {why}: fix the repository first\n"
                f"{n}:\n{base[n]['output'][-1500:]}", 1)
        # A test's limit: ten times the solution's own time, plus 5 s (process start, a loaded
        # machine); once a test has hung, 3× plus 2 s for the rest of that program's tests.
        self.limits = {n: 10 * probe[n]["seconds"] + 5 for n in self.all_tests}
        self.after_hang = {n: 3 * probe[n]["seconds"] + 2 for n in self.all_tests}
        self.judge_limits = {n: 10 * base[n]["seconds"] + 5 for n in self.all_tests}
        self.baseline = base
        log(f"grade: the solution passes all {len(self.all_tests)} tests, probed and judged, in {time.time() - t0:.1f} s")

    def variant(self, changes, tests):
        """Results of the pristine copy with changes {file: text} applied, for tests: cached by content."""
        if not changes:
            return {"build": "ok", "tests": {n: self.baseline[n] for n in tests}}
        return super().variant(changes, tests)


# ---------------------------------------------------------------- a submission
def grade_submission(g, entry, name, outdir, progress):
    s = Submission(name)
    scratch = tempfile.mkdtemp(prefix="sub-", dir=g.scratch)
    try:
        root, why = open_submission(entry, scratch)
        if why:
            return not_graded(g, s, why)
        if not os.path.isdir(os.path.join(root, g.lab)):
            s.notes.append(f"no {g.lab}/ folder in the submission")
        read_regions(s, root, g.exercises, g.trust_regions)
        s.outside = changed_outside(g.copy, root)
        run_variants(g, s, progress)
        grade_exercises(g, s)
        keep_pictures(s, outdir)
        return s
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def not_graded(g, s, why):
    """A submission that could not be opened: 0 for every exercise, the reason in its notes."""
    s.fatal = why
    s.notes.append(why)
    for e in g.exercises:
        s.grades[e["name"]] = 0
        s.messages[e["name"]] = f"`{e['name']}` not graded: the submission is {why}"
    return s


def run_variants(g, s, progress):
    """Each exercise alone (its region in the solved lab) and all of them "as handed in", on the
    scheduler: the longest first (the solution's time for their tests), so that the last one to
    start is a short one and both cores stay busy to the end."""
    solution = {n for n, r in s.region.items() if r == "solution"}
    apply = lambda names: with_regions(g.solved, g.exercises, s.bodies, names, unchanged=solution)
    t0 = time.time()
    runs = [(e["name"], apply({e["name"]}), e["tests"]) for e in g.exercises if s.region[e["name"]] != "missing"]
    runs.append((None, apply({e["name"] for e in g.exercises}), g.all_tests))
    with Scheduler(g.jobs) as scheduler:
        futs = {scheduler.submit(g.variant, changes, tests, cost=sum(g.baseline[t]["seconds"] for t in tests)): ex
                for ex, changes, tests in runs}
        for f in cf.as_completed(futs):
            ex = futs[f]
            if ex is None:
                s.whole = f.result()
                continue
            r = s.isolated[ex] = f.result()
            ok = r["build"] == "ok" and all(r["tests"].get(t, {}).get("status") == "ok" for t in exercise(g, ex)["tests"])
            progress(f"{s.name}: {ex} {'passes' if ok else 'fails'} ({time.time() - t0:.0f} s)")


def exercise(g, name):
    return next(e for e in g.exercises if e["name"] == name)


def grade_exercises(g, s):
    """Each exercise's grade and message from its variant; the notes that sum them up."""
    compile_bad, stopped, grader_bad = [], [], []  # stopped: the exercises with a test that crashed or hung
    for e in g.exercises:
        n = e["name"]
        s.grades[n], s.messages[n], why = grade_exercise(g, s, e)
        if why == "grader":
            grader_bad.append(n)
        elif why == "compile":
            compile_bad.append(n)
        elif why == "stopped":
            stopped.append(n)
    if s.flagged:
        s.notes.append("flagged, 0, for the instructor to look at: " +
                       "; ".join(f"{n} ({', '.join(why)})" for n, why in s.flagged.items()))
    missing = [e["name"] for e in g.exercises if s.region[e["name"]] == "missing"]
    if missing:
        s.notes.append("markers deleted (not done): " + " ".join(missing))
    if compile_bad:
        s.notes.append("did not compile: " + " ".join(compile_bad))
    if grader_bad:
        s.notes.append("not graded, the grader's build failed (regrade): " + " ".join(grader_bad))
    # Which of an exercise's tests hit the wall-time limit and which crashed first can change
    # from run to run (code that allocates without end meets the time limit or the memory
    # limit first, depending on the machine's load): grades.csv names the exercises only, so a
    # regrade gives the same file; each test's own ending is in the report and results.json.
    if stopped:
        s.notes.append("did not finish (a crash or the time limit): " + " ".join(stopped))
    if s.outside:
        s.notes.append(f"changed outside the exercises (ignored): {len(s.outside)} file(s): " +
                       " ".join(s.outside[:5]) + (" …" if len(s.outside) > 5 else ""))
    if s.whole and s.whole["build"] != "ok":
        s.notes.append("as handed in: does not compile")


def grade_exercise(g, s, e):
    """(grade, message, why: None | "compile" | "grader" | "stopped") of exercise e."""
    n = e["name"]
    if s.region[n] == "missing":
        return 0, (f"`{n}` is not done: its markers (// TODO EXERCISE {n}: … // END EXERCISE) are not in "
                   f"{e['file']} any more, so there is no code to grade. Put the markers back around your code."), None
    r = s.isolated[n]
    if n in s.flagged:
        passing = sum(r["tests"].get(t, {}).get("status") == "ok" for t in e["tests"])
        return 0, (f"`{n}` is not graded: its region ({e['file']}) steps outside the exercise: "
                   f"{'; '.join(s.flagged[n])}. A region holds the exercise's own statements and nothing "
                   f"else (docs/solutions.md, \"What a region may hold\"). For the instructor: "
                   + (f"{passing} of its {len(e['tests'])} tests pass." if r["build"] == "ok" else "it does not build.")), None
    if r["build"] == "error":
        return 0, f"`{n}` ({e['file']}) was not graded: the grader's build failed, not the compiler:\n" + r.get("log", "")[-800:], "grader"
    if r["build"] != "ok":
        return 0, (f"`{n}` ({e['file']}) does not compile with the solution of every other exercise"
                   f"{' (the build ran out of time)' if r['build'] == 'timeout' else ''}:\n" + compiler_errors(r.get("log", ""))), "compile"
    failing = [t for t in e["tests"] if r["tests"].get(t, {}).get("status") != "ok"]
    if not failing:
        return 1, f"`{n}`: all {len(e['tests'])} tests that check it pass ({', '.join(e['tests'][:6])}{' …' if len(e['tests']) > 6 else ''}).", None
    status = lambda t: r["tests"].get(t, {}).get("status", "not-run")
    message = f"`{n}` fails {len(failing)} of its {len(e['tests'])} tests (run with the solution of every other exercise):\n\n" + \
        "\n".join(f"{t}: {status(t)}\n{test_message(r['tests'].get(t, {}).get('output', ''))}" for t in failing)
    if s.region[n] == "stub":
        message = f"`{n}` is still the stub.\n" + message
    return 0, message, "stopped" if any(status(t) in ("timeout", "crashed") for t in failing) else None


def keep_pictures(s, outdir):
    """The pictures of failing render tests (kept by the variant), copied next to the report."""
    for n, r in s.isolated.items():
        for t, tr in r.get("tests", {}).items():
            keep = []
            for pic, src in tr.get("pictures", []) if tr.get("status") != "ok" else []:
                dst = os.path.join("pictures", f"{n}--{pic.replace('/', '--')}")
                os.makedirs(os.path.join(outdir, "pictures"), exist_ok=True)
                shutil.copyfile(src, os.path.join(outdir, dst))
                keep.append(dst)
            s.kept[(n, t)] = keep


# ---------------------------------------------------------------- the command
def class_entries(submissions):
    """{student: entry} of the submissions folder; exit 2 on two entries for one student or a bad name."""
    by_name = {}
    for x in sorted(os.listdir(submissions)):
        if x.startswith("."):
            continue
        n = student_name(x)
        if n in by_name:
            die(f"{submissions}: two entries for student {n} ({by_name[n]}, {x})")
        by_name[n] = x
    if not by_name:
        die(f"{submissions}: no submissions in it")
    for n in by_name:
        if not re.match(r"^[A-Za-z0-9][A-Za-z0-9._ @+-]*$", n):
            die(f"{submissions}/{by_name[n]}: a student name must be letters, digits and . _ - @ + (got {n!r})")
    return by_name


def grade_class(a):
    lab = resolve_lab(a.lab)
    if not os.path.isdir(a.submissions):
        die(f"{a.submissions}: not a folder of submissions")
    out = os.path.abspath(a.out or os.path.join(ROOT, "build", f"grades-{lab.split('_')[0]}"))
    sub_real = os.path.realpath(a.submissions)
    if out == sub_real or out.startswith(sub_real + os.sep):
        die(f"--out {out} is inside the submissions folder")
    by_name = class_entries(a.submissions)
    os.makedirs(out, exist_ok=True)
    scratch = tempfile.mkdtemp(prefix="grade-run-")
    os.chmod(scratch, 0o711)
    t_start = time.time()
    try:
        check_isolation()
        g = Grader(lab, a.cache, max(1, a.jobs), scratch)
        g.trust_regions = a.no_region_check
        subs = []
        names = sorted(by_name)
        t_first = time.time()
        for i, n in enumerate(names):
            done = time.time() - t_first
            left = f", about {done / i * (len(names) - i):.0f} s left" if i else ""
            log(f"[{i + 1}/{len(names)}] {n}{left}")
            t0 = time.time()
            s = grade_submission(g, os.path.join(a.submissions, by_name[n]), n, os.path.join(out, STUDENTS, n),
                                 lambda m: log(f"    {m}"))
            subs.append(s)
            log(f"    {n}: {sum(s.grades.values())}/{len(g.exercises)} in {time.time() - t0:.1f} s" + (f" — {'; '.join(s.notes)}" if s.notes else ""))
        write_outputs(g, subs, out)
        log(f"grade: {len(subs)} submissions of {lab} in {time.time() - t_first:.0f} s (+{t_first - t_start:.0f} s setup): "
            f"{out}/grades.csv, {out}/index.html")
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def prove_command(argv):
    """--prove BUILD LAB [--rows]: prove.py's proof; its exit code."""
    import prove
    if len(argv) not in (2, 3) or (len(argv) == 3 and argv[2] != "--rows"):
        die("usage: grade.py --prove BUILD_DIR LAB [--rows]")
    if not os.path.isdir(argv[0]):
        die(f"--prove: no build folder {argv[0]}")
    lab = resolve_lab(argv[1])
    kill_on_signals()
    return prove.Proof(argv[0], lab, rows=len(argv) == 3, only=os.environ.get("PROVE_ONLY") or None,
                       scope=os.environ.get("GRADER_SCOPE", "label")).run()


def main():
    if sys.argv[1:2] == ["--prove"]:
        sys.exit(prove_command(sys.argv[2:]))
    ap = argparse.ArgumentParser(prog="grade.sh", description="Grade every submission of a lab.")
    ap.add_argument("lab")
    ap.add_argument("submissions")
    ap.add_argument("--out")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    # The default cache: the grader's user's own folder in /tmp (the sandbox's users must reach it,
    # so not under a private home), used only while it is that user's alone (owned_by_us).
    ap.add_argument("--cache", default=os.environ.get("GRADE_CACHE") or f"/tmp/vulkan-labs-grade-{os.geteuid()}")
    ap.add_argument("--no-region-check", action="store_true",
                    help="grade flagged regions as any other (the grader's own test: what the judge alone decides)")
    grade_class(ap.parse_args())


if __name__ == "__main__":
    main()
