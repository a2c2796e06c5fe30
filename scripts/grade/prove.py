"""prove.py — the grader's own test (CTest grader_labN): the blame is measured, not declared.

    python3 scripts/grade/grade.py --prove BUILD LAB [--rows]

A synthetic class made from the model: one submission per exercise e of LAB with e as its stub
(every other exercise solved), and one per exercise with only e solved (the isolation
submissions). Each is a variant built from BUILD's `<target>_graded` targets (variants.GradedBuild:
object reuse, one at a time in BUILD/grader/, queued at the start) and run through the grader's
own run module: the same scheduler (two jobs at a time, the costliest first, builds first, and
beside them two tests that mostly wait: light_tests()), the same limits and process-group killing,
the same reading of a test's ending and of the exercise its message names. Every submission's
tests share the scheduler, so one's builds and tests fill the time another's leave.
It runs the CTest label of LAB as a student copy has it (without the tests labelled
`instructors`, which a copy disables and the class grader never runs), every test with its own
command, environment, working folder, timeout and skip code, seeing the variant's lab (prepare()).
Then for each exercise e:
  (a) at least one test fails with e stubbed, and every failing test's message names e first (the
      gtests' hint, tests/exercise_hints.cpp, or tests/with_exercise_hint.sh's for the others);
  (b) every row of tests/graded_exercises.txt that lists e matches only tests that failed: the
      table says what was measured, no more;
  (c) with only e solved (every other exercise stubbed, but the prerequisites that
      tests/graded_exercises.txt gives e's own code: "@e x y") one of e's own tests ("Checked
      by") that failed in (a) passes: the test isolates e.
A test whose result cannot differ between two variants runs once (LabelVariants.deps): a gtest
program that reads no lab (it never names LAB_EXE_DIR or LAB_SHADER_DIR) built the same.
Some tests run shorter than in the label: the random scenes RANDOM_SEEDS seeds a shard (each seed
so kept fails for every exercise whose stub fails that shard), a soak SOAK_MINUTES, its crash,
hang and validation checks kept but not its memory gate (SOAK_MEMORY_GATE=0: a stub changes what
is drawn, not what is kept; the label's own soak gates memory), and a test of many cases (the
random scenes) stops at its first failing one (LAB_FAIL_FAST=1): the proof asks
whether a test fails and what it names, not how often.

Prints per exercise how many tests failed and whether each named it; writes the measurement to
BUILD/grader/LAB.measured, each run's results (test, status, exercise named, seconds, CPU seconds,
the run it was taken from) to BUILD/grader/runs/RUN/results.tsv and its logs beside. --rows prints,
instead of judging, the rows that say what was measured (each failing test → the exercises whose
stub fails it), for tests/graded_exercises.txt; PROVE_ONLY=NAME measures that exercise alone.
GRADER_SCOPE=own (by hand, a quicker look) runs only the tests e's "Checked by" and its rows name.
Exit 0 when proven, 1 with problems, 77 when there is nothing to prove (no exercises, a student copy).
"""
import concurrent.futures as cf
import fnmatch
import hashlib
import json
import os
import re
import shutil
import sys
import threading
import time
import traceback

import model
from runs import Scheduler, label_tests, run_ctest_test, select
from variants import GradedBuild, VariantCache

RANDOM_SEEDS = 5      # seeds per random-scene shard in the proof (the label runs 40-50)
SOAK_MINUTES = "0.25"  # a soak's length in the proof (the label's: 1, lab 4's 3)
BUILD_FIRST = float("inf")  # a build's place in the scheduler: before every test
LIGHT = 2  # light tests (light_tests()) the scheduler runs beside its two jobs
WINDOW_DRIVERS = ("xvfb-run", "window_smoke.sh", "soak.py")  # what runs a lab in a window and drives it
SO_FAR = "\0so-far\0"     # in a line to print: the seconds since the proof started


def light_tests(tests):
    """The tests that mostly wait: a lab in a window, driven by inputs with pauses between them
    (their commands name WINDOW_DRIVERS, or gpu_passes.py's `window`). Measured alone, as user +
    system time against wall time: a soak 0.48 of a core, window_on_demand 0.30, a window smoke
    0.47, gpu_passes_window 0.59. A rule, not the last proof's timings, so that a fresh build (no
    timings yet) runs them beside the two jobs as well: LIGHT of them at a time."""
    def drives_window(t):
        cmd = [os.path.basename(a) for a in t.command]
        return any(a in WINDOW_DRIVERS for a in cmd) or ("gpu_passes.py" in cmd and cmd[-1] == "window")
    return {t.name for t in tests if drives_window(t)}


def safe(name):
    return re.sub(r"[^A-Za-z0-9_.-]", "_", name)


_programs = {}  # (path, mtime, size) → program()


def program(path):
    """(the hash of the program at path, whether it names LAB_EXE_DIR or LAB_SHADER_DIR: reads a lab)."""
    st = os.stat(path)
    key = (path, st.st_mtime_ns, st.st_size)
    if key not in _programs:
        with open(path, "rb") as f:
            data = f.read()
        _programs[key] = (hashlib.sha256(data).hexdigest(), b"LAB_EXE_DIR" in data or b"LAB_SHADER_DIR" in data)
    return _programs[key]


# ---------------------------------------------------------------- a variant's view of BUILD
def fake_build(build, lab, vdir):
    """vdir/build-LAB: a link to every entry of BUILD, but BUILD/LAB/LAB (the lab's binary) is a
    script that runs the variant's with its shaders."""
    fake = os.path.join(vdir, "build-" + lab)
    shutil.rmtree(fake, ignore_errors=True)  # links and the script only: rmtree removes links, never what they point to
    os.makedirs(os.path.join(fake, lab))
    for entry in os.listdir(build):
        if entry not in (lab, "shaders", "grader"):
            os.symlink(os.path.join(build, entry), os.path.join(fake, entry))
    for entry in os.listdir(os.path.join(build, lab)):
        if entry != lab:
            os.symlink(os.path.join(build, lab, entry), os.path.join(fake, lab, entry))
    # Its shaders too (make_gallery.sh passes --dev-shader-dir BUILD/shaders/LAB itself).
    os.makedirs(os.path.join(fake, "shaders"))
    for entry in os.listdir(os.path.join(build, "shaders")):
        target = os.path.join(vdir, "shaders", lab) if entry == lab else os.path.join(build, "shaders", entry)
        os.symlink(target, os.path.join(fake, "shaders", entry))
    exe = os.path.join(fake, lab, lab)
    with open(exe, "w") as f:
        f.write("#!/bin/sh\nexec '%s' --dev-shader-dir '%s' \"$@\"\n" % (
            os.path.join(vdir, "bin", lab), os.path.join(vdir, "shaders", lab)))
    os.chmod(exe, 0o755)
    return fake


def to_fake(arg, build, fake):
    """BUILD in a command's argument (a path, --build BUILD, LAB_BUILD_DIR=BUILD) → the fake build."""
    if "/grader/" in arg:
        return arg
    return re.sub(r"(^|=)" + re.escape(build) + r"(?=/|$)", lambda m: m.group(1) + fake, arg)


def prepare(test, build, lab, vdir, fake, out):
    """test's command and environment as the proof runs it on the variant in vdir: the gtests'
    runners read LAB_EXE_DIR, LAB_SHADER_DIR (tests/lab_runner.h) and the hints the variant's
    manifest, LAB_EXERCISE_MANIFEST (tests/exercise_hints.cpp); a unit test compiled from the lab's files runs
    as the variant's build of it; every other command sees BUILD through the fake build."""
    short = lab.split("_")[0]
    bin_dir = os.path.join(vdir, "bin")
    cmd = list(test.command)
    if os.path.dirname(cmd[0]).startswith(build) and os.path.exists(os.path.join(bin_dir, os.path.basename(cmd[0]))):
        cmd[0] = os.path.join(bin_dir, os.path.basename(cmd[0]))
    cmd = [to_fake(a, build, fake) for a in cmd]
    if test.name.startswith(short + "_random_scenes") and "--count" in cmd:
        k = cmd.index("--count") + 1
        cmd[k] = str(min(int(cmd[k]), RANDOM_SEEDS))
    env = dict(os.environ)
    for k, v in test.env.items():
        env[k] = v.replace(build, fake) if k == "LAB_BUILD_DIR" else v
    soak = [k for k, a in enumerate(cmd) if a.endswith("/bench/soak.py")]
    if soak and test.name.endswith("_soak"):
        cmd[soak[0] + 1] = SOAK_MINUTES
        env.update(SOAK_MEMORY_GATE="0", SOAK_MIN_SAMPLES="1")
    env.update(LAB_FAIL_FAST="1", LAB_EXE_DIR=bin_dir, LAB_SHADER_DIR=os.path.join(vdir, "shaders", lab),
               LAB_EXERCISE_MANIFEST=os.path.join(vdir, "exercises.json"),
               LAB_TEST_OUTPUT=os.path.join(out, "test_output", safe(test.name)))
    return cmd, env


# ---------------------------------------------------------------- the label on variants
class LabelVariants(VariantCache):
    """variant(sources, tests): the label's tests (names) run on the lab built with sources ({path:
    text} of the lab's files, some exercises stubbed), each test a job of the scheduler; the result
    {build, log, run, tests: {name: result}}. prebuild(sources, wanted) names the run (its folder
    in runs_dir) and queues its build. A test already run on a build whose result it cannot tell from this one's is not
    run again (deps)."""

    def __init__(self, build, lab, tests, scheduler, runs_dir, log_path, history):
        super().__init__()
        self.build_dir, self.lab, self.scheduler, self.runs_dir = build, lab, scheduler, runs_dir
        self.tests = {t.name: t for t in tests}
        self.builder = GradedBuild(build, lab, log_path)
        # a test's cost: its seconds in the last proof, else its timeout; light: light_tests()
        self.costs = {n: h["seconds"] for n, h in history.items()}
        self.light = light_tests(tests)
        self.names = {}         # sources' key → the run's name
        self.builds = {}        # sources' key → Future of the build: (None or why it failed, seconds)
        self.done = {}          # (test, sources' key or deps) → (result, the run it came from)
        self.build_queue, self.building = [], False

    @staticmethod
    def key(sources):
        return hashlib.sha256(json.dumps(sorted(sources.items())).encode("utf-8", "surrogateescape")).hexdigest()

    def prebuild(self, sources, wanted):
        """Names the run of sources (wanted, unless the same sources have a run already) and queues
        its build."""
        key = self.key(sources)
        with self.lock:
            run = self.names.setdefault(key, wanted)
        self._build_queued(key, sources, os.path.join(self.runs_dir, run))

    # ---- building: one build at a time, before every test waiting (BUILD/grader is one folder)
    def _build_queued(self, key, sources, vdir):
        """The Future of the build of sources in vdir, queued unless it is already."""
        with self.lock:
            fut = self.builds.get(key)
            if fut is None:
                fut = self.builds[key] = cf.Future()
                self.build_queue.append((sources, vdir, fut))
                self._pump()
        return fut

    def _pump(self):
        if self.building or not self.build_queue:
            return
        sources, vdir, fut = self.build_queue.pop(0)
        self.building = True

        def run():
            try:
                t0 = time.time()
                why = self.builder.build(sources, vdir)
                if not why:
                    fake_build(self.build_dir, self.lab, vdir)
                    model.write_manifest(os.path.join(vdir, "exercises.json"), model.ROOT, os.path.join(vdir, "src"))
                fut.set_result((why, time.time() - t0))
            except Exception as ex:
                fut.set_exception(ex)
            finally:
                with self.lock:
                    self.building = False
                    self._pump()
        self.scheduler.submit(run, cost=BUILD_FIRST)

    # ---- running
    def deps(self, test, vdir):
        """What test's result depends on in the variant when that is less than all of it: a gtest
        program that names neither LAB_EXE_DIR nor LAB_SHADER_DIR reads no lab but its own code
        (its hash); None: all of the variant."""
        g = test.gtest()
        if not g:
            return None
        path = g[0]
        local = os.path.join(vdir, "bin", os.path.basename(path))
        if os.path.dirname(path).startswith(self.build_dir) and os.path.exists(local):
            path = local
        digest, reads_lab = program(path)
        return None if reads_lab else digest

    def _run_variant(self, sources, names):
        key = self.key(sources)
        with self.lock:
            run = self.names.setdefault(key, key[:12])
        vdir = os.path.join(self.runs_dir, run)
        why, seconds = self._build_queued(key, sources, vdir).result()
        if why:
            return {"build": "failed", "log": why, "run": run, "tests": {}}
        futures = {n: self.scheduler.submit(self._run_test, self.tests[n], vdir, run, key,
                                            cost=self.costs.get(n, self.tests[n].timeout), light=n in self.light)
                   for n in names}
        return {"build": "ok", "run": run, "build_seconds": seconds, "tests": {n: f.result() for n, f in futures.items()}}

    def _run_test(self, test, vdir, run, key):
        d = self.deps(test, vdir)
        with self.lock:
            if (test.name, key) in self.done:
                r, was = self.done[(test.name, key)]
                return dict(r, source=was)
            if d and (test.name, d) in self.done:
                r, was = self.done[(test.name, d)]
                if r["status"] != "failed":  # from another build only a pass (a failure names that build's stub)
                    return dict(r, source=was)
        cmd, env = prepare(test, self.build_dir, self.lab, vdir, os.path.join(vdir, "build-" + self.lab), vdir)
        r = run_ctest_test(test, cmd, env, os.path.join(vdir, "logs", safe(test.name) + ".log"))
        del r["output"]
        with self.lock:
            self.done[(test.name, key)] = (r, run)
            if d:
                self.done[(test.name, d)] = (r, run)
        return dict(r, source=run)


# ---------------------------------------------------------------- the proof
class Proof:
    """The proof of BUILD's grader for lab (module docstring). run() → the exit code."""

    def __init__(self, build, lab, rows=False, only=None, scope="label", jobs=2, out=sys.stdout):
        self.build = os.path.realpath(build)
        self.lab, self.rows, self.only, self.scope, self.jobs, self.out = lab, rows, only, scope, jobs, out
        self.short = lab.split("_")[0]
        self.g = os.path.join(self.build, "grader")
        self.log_path = os.path.join(self.g, f"{lab}.log")
        self.measured_path = os.path.join(self.g, f"{lab}.measured")
        self.history_path = os.path.join(self.g, f"{lab}.seconds.json")
        self.failures = 0
        self.start = time.time()

    def say(self, line):
        print(line, file=self.out, flush=True)

    def fail(self, line):
        self.say(line)
        self.failures += 1

    # ---- the synthetic class
    def read_sources(self):
        """The lab's files and its shaders' ({path: text}), as the repository has them."""
        files = {}
        for top in (self.lab, os.path.join("shaders", self.lab)):
            for base, _, names in os.walk(os.path.join(model.ROOT, top)):
                for n in names:
                    path = os.path.join(base, n)
                    if os.path.isfile(path) and not os.path.islink(path):
                        with open(path, encoding="utf-8", errors="surrogateescape", newline="") as f:
                            files[os.path.relpath(path, model.ROOT)] = f.read()
        return files

    def stubbed(self, names):
        """The lab's files with the exercises names cut to their stubs."""
        return {rel: model.stub_text(text, set(names)) if names and "// EXERCISE " in text else text
                for rel, text in self.sources.items()}

    def run(self):
        conf = os.path.join(self.g, f"{self.lab}.env")
        if not os.path.isfile(conf):
            model.die(f"{conf} is missing: configure {self.build} first (scripts/setup.sh)")
        self.exercises = model.exercises_of(self.lab)
        if not self.exercises:
            self.say(f"grader: {self.lab} has no exercises (skipped)")
            return 77
        if model.is_student_copy(self.lab):
            self.say(f"grader: this is a student copy of {self.lab} (TODO EXERCISE markers): the grader's proof runs on the complete lab (skipped)")
            return 77
        self.table = model.graded_table(model.ROOT)
        self.names = [e["name"] for e in self.exercises]
        self.sources = self.read_sources()
        open(self.log_path, "w").close()
        os.makedirs(os.path.join(self.g, "runs"), exist_ok=True)
        self.say(f"grader: {self.lab}, {len(self.exercises)} exercises, each stubbed alone against every test of label "
                 f"{self.short} that a copy runs; building in {self.g}")
        tests = [t for t in label_tests(self.build, self.short) if t.command and not t.disabled]
        history = self.read_history()
        with Scheduler(self.jobs, light=LIGHT) as scheduler:
            self.variants = LabelVariants(self.build, self.lab, tests, scheduler, os.path.join(self.g, "runs"), self.log_path, history)
            with open(self.log_path, "a") as f:
                f.write(f"grader: light tests ({LIGHT} run beside the two jobs): {' '.join(sorted(self.variants.light)) or 'none'}\n")
            self.tests = tests
            self.prove_all()
        self.write_history(history)
        for run in {res["run"] for res in self.runs if res.get("run")}:  # each run's build (its results and logs stay)
            for part in ("bin", "shaders", "build-" + self.lab):
                shutil.rmtree(os.path.join(self.g, "runs", run, part), ignore_errors=True)
        return self.report()

    def prove_all(self):
        """Each exercise in a thread of its own (its stubbed run, then its isolation run); the
        lines printed in the exercises' order."""
        todo = [e for e in self.exercises if not self.only or e["name"] == self.only]
        self.measured, self.failed_of, self.iso_lines, self.table_lines = {}, {}, {}, {}
        self.runs = []
        ready = {e["name"]: threading.Event() for e in todo}
        lines = {}

        def one(e):
            try:
                lines[e["name"]] = self.guarded(self.stubbed_alone, e)
            finally:
                ready[e["name"]].set()
            if not self.rows:
                self.iso_lines[e["name"]] = self.guarded(self.isolated, e)

        # Every build queued at once, the isolation runs' after the stubbed ones: they need no
        # result, and built while the stubbed runs' tests run they are ready when those end.
        for e in todo:
            self.variants.prebuild(self.stubbed([e["name"]]), e["name"])
        for e in todo if not self.rows else []:
            self.variants.prebuild(self.stubbed(self.isolating(e)), "only-" + e["name"])
        threads = [threading.Thread(target=one, args=(e,), daemon=True) for e in todo]
        for t in threads:
            t.start()
        for e in todo:
            ready[e["name"]].wait()
            for line in lines.get(e["name"]) or []:
                self.emit(line)
        for t in threads:
            t.join()

    def guarded(self, step, e):
        """step(e)'s lines; the proof's own error as a problem."""
        try:
            return step(e)
        except Exception:
            with open(self.log_path, "a") as f:
                f.write(traceback.format_exc())
            return [f"grader: the proof failed on {e['name']}: {traceback.format_exc().strip().splitlines()[-1]} (see {self.log_path})"]

    def emit(self, line):
        """Prints line (SO_FAR in it: the seconds since the start); a FAIL line or the proof's own
        failure ("grader: …") is a problem."""
        line = line.replace(SO_FAR, f"{time.time() - self.start:.0f}")
        if line.startswith(("FAIL", "grader: ")):
            self.fail(line)
        else:
            self.say(line)

    def stubbed_alone(self, e):
        """(a) and (b) for e: the lines to print."""
        name = e["name"]
        names = None
        if self.scope == "own":
            # GRADER_SCOPE=own (by hand, a quicker look; CI runs the whole label): only the tests that e's "Checked
            # by" and its graded_exercises.txt rows name run. With measured rows those are the tests that
            # fail; a test failing outside them is what only the whole label (the default) finds.
            names = e["checked"] + list(self.table.rows_of(name))
        res = self.variants.variant(self.stubbed([name]), sorted(t.name for t in select(self.tests, names)))
        self.runs.append(res)
        if res["build"] != "ok":
            return [f"grader: {res['log']} (see {self.log_path})"]
        self.write_results(name, res)
        results = sorted(res["tests"].items())
        failed = [t for t, r in results if r["status"] == "failed"]
        self.failed_of[name] = failed
        self.measured[name] = [(t, res["tests"][t]["named"]) for t in failed]
        ran = len(results)
        if self.rows:
            return [f"     {name}: {len(failed)} of {ran} tests fail"]
        wrong = []
        for t in failed:
            named = res["tests"][t]["named"]
            if named != name:
                wrong.append(f"       {t} names no exercise" if named == "-" else
                             f"       {t} says every exercise it needs is done" if named == "done" else
                             f"       {t} names {named}")
        out = []
        if not failed:
            out.append(f"FAIL {name} ({e['file']}:{e['line']}): stubbed alone, none of the {ran} tests of {self.short} fails")
        elif wrong:
            out.append(f"FAIL {name}: stubbed alone, {len(failed)} of {ran} tests fail and {len(wrong)} of them do not name it "
                       f"(tests/graded_exercises.txt):")
            out += wrong[:20]
        else:
            out.append(f"ok   {name}: stubbed alone, {len(failed)} of {ran} tests fail, every one naming it "
                       f"({SO_FAR} s so far)")
        # (b) every row listing e matches only tests that failed.
        for pat in self.table.rows_of(name):
            for t, r in results:
                if fnmatch.fnmatchcase(t, pat) and t not in failed:
                    out.append(f"FAIL {name}: tests/graded_exercises.txt lists it for {pat}, but {t} {r['status']} with it stubbed")
        return out

    def isolating(self, e):
        """The exercises stubbed in e's isolation run: every other one but the prerequisites of e's code."""
        pre = self.table.prerequisites.get(e["name"], [])
        return [n for n in self.names if n != e["name"] and n not in pre]

    def isolated(self, e):
        """(c) for e: the lines to print (a FAIL line, or none); its isolation table line in table_lines."""
        name = e["name"]
        checked = [t for t in self.failed_of.get(name, []) if any(fnmatch.fnmatchcase(t, p) for p in e["checked"])]
        if not checked:
            if self.failed_of.get(name):
                return [f"FAIL {name}: none of its own tests ({' '.join(e['checked'])}) fails with it stubbed"]
            return []
        pre = self.table.prerequisites.get(name, [])
        res = self.variants.variant(self.stubbed(self.isolating(e)), checked)
        self.runs.append(res)
        if res["build"] != "ok":
            return [f"grader: {res['log']} (see {self.log_path})"]
        self.write_results("only-" + name, res)
        iso = next((t for t, r in sorted(res["tests"].items()) if r["status"] == "passed"), None)
        but = f" but {' '.join(pre)}" if pre else ""
        if not iso:
            return [f"FAIL {name}: solved with every other exercise of {self.lab} stubbed{but}, none of {','.join(checked)} passes"]
        self.table_lines[name] = "%-18s %s%s" % (name, iso, f" (with the prerequisites of its code solved: {' '.join(pre)})" if pre else "")
        return []

    def write_results(self, step, res):
        """runs/STEP/results.tsv: test, passed | failed | skipped, the exercise it named, seconds, CPU
        seconds, and the run that ran it (its logs are in runs/RUN/logs/)."""
        os.makedirs(os.path.join(self.g, "runs", step), exist_ok=True)
        with open(os.path.join(self.g, "runs", step, "results.tsv"), "w") as f:
            for n, r in sorted(res["tests"].items()):
                f.write("%s\t%s\t%s\t%.1f\t%.1f\t%s\n" % (n, r["status"], r["named"], r["seconds"], r["cpu"], r["source"]))

    def report(self):
        with open(self.measured_path, "w") as f:
            for e in self.exercises:
                for t, named in self.measured.get(e["name"], []):
                    f.write(f"{e['name']}\t{t}\t{named}\n")
        if self.rows:
            self.say(f"# ---- {self.short}: measured by scripts/exercise.sh --prove BUILD {self.short} --rows")
            by_test = {}
            for e in self.exercises:
                for t, _ in self.measured.get(e["name"], []):
                    by_test.setdefault(t, []).append(e["name"])
            for t in sorted(by_test, key=lambda s: s.encode()):
                self.say(t + "".join(" " + n for n in by_test[t]))
            return 0
        for n in self.names:
            for line in self.iso_lines.get(n) or []:
                self.emit(line)
        table = [self.table_lines[n] for n in self.names if n in self.table_lines]
        if table:
            self.say("isolation (exercise → one of its own tests that passes with only it solved):")
            for line in table:
                self.say("  " + line)
        self.say(f"grader: {time.time() - self.start:.0f} s; the failing tests of each run: {self.measured_path}, "
                 f"their logs: {self.g}/runs/")
        if self.failures:
            self.say(f"grader: {self.failures} problem(s); build log: {self.log_path}")
            return 1
        self.say(f"grader: every exercise of {self.lab} stubbed alone fails tests of {self.short} that all name it, and a test isolates it")
        return 0

    def read_history(self):
        """LAB.seconds.json: test → {seconds, cpu} in the last proof that ran it."""
        try:
            with open(self.history_path) as f:
                return {n: h for n, h in json.load(f).items() if isinstance(h, dict) and h.get("seconds")}
        except (OSError, ValueError):
            return {}

    def write_history(self, history):
        """Each test's seconds and CPU seconds in this proof (its longest run), for the next proof's
        order and light tests (LAB.seconds.json); and where the time went (LAB.times.tsv: run, test
        or "(build)", status, seconds, CPU seconds, the run that ran it)."""
        with open(os.path.join(self.g, f"{self.lab}.times.tsv"), "w") as f:
            for res in self.runs:
                if "build_seconds" in res:
                    f.write("%s\t(build)\t\t%.1f\t\t\n" % (res["run"], res["build_seconds"]))
                for n, r in sorted(res.get("tests", {}).items()):
                    f.write("%s\t%s\t%s\t%.1f\t%.1f\t%s\n" % (res["run"], n, r["status"], r["seconds"], r["cpu"], r["source"]))
        longest = {}
        for res in self.runs:
            for n, r in res.get("tests", {}).items():
                if r["source"] == res["run"] and r["seconds"] >= longest.get(n, {"seconds": -1})["seconds"]:
                    longest[n] = {"seconds": round(r["seconds"], 1), "cpu": round(r["cpu"], 1)}
        history.update(longest)
        with open(self.history_path, "w") as f:
            json.dump(history, f, indent=1, sort_keys=True)
