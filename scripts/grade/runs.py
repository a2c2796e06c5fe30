"""runs.py — finding a lab's tests and running them: GoogleTest programs in the sandbox, each test
with a wall-time limit of its own and a hang costing less once one has hung (run_tests); the probe
and the judge (run_judged); a CTest test as CTest runs it, with its own command, environment,
working folder, timeout and skip code (run_ctest_test); the scheduler that runs them side by side
(Scheduler); and what a test's output says: its ending and the exercise its message names first.
"""
import collections
import concurrent.futures as cf
import fnmatch
import heapq
import itertools
import json
import os
import queue
import re
import subprocess
import threading
import time

from model import die
from sandbox import MANIFEST, MAX_PROCESS_OUTPUT, OUT, PROBE, WORK, chown_tree, ended, kill_group, run_limited, sandbox, started

MAX_TEST_OUTPUT = 64 << 10     # what a report keeps of one test's output
MAX_LINE = 64 << 10            # a longer line is read in pieces
RUN_RE = re.compile(r"^\[ RUN      \] (\S+)")
END_TEST_RE = re.compile(r"^\[ +(OK|FAILED|SKIPPED) +\] (\S+?),?( |$)")
# The exercise a failing test's message names first (tests/exercise_hints.cpp, for a test that is
# no GoogleTest test tests/with_exercise_hint.sh), or that everything it needs is done.
NEEDS_RE = re.compile(r"^\[ exercise \] this test needs `([a-z0-9_]+)`", re.M)
DONE_RE = re.compile(r"^\[ exercise \] (every exercise|the exercise) this test needs is done", re.M)


def named_exercise(output):
    """The exercise a test's output names first; "done" when it says all it needs is done; "-"."""
    m = NEEDS_RE.search(output)
    return m.group(1) if m else ("done" if DONE_RE.search(output) else "-")


def test_message(output):
    """The grader's message in a test's output: the [ exercise ] lines and the failures."""
    keep = []
    lines = output.splitlines()
    for l in lines:
        if l.startswith("[ exercise ]") or (keep and keep[-1].startswith("[ exercise ]") and l.startswith(" ")) or \
                "Failure" in l or l.startswith("(") or "(probe)" in l or re.match(r"^(Expected|Value of|  Actual|Which is|    Which)", l):
            keep.append(l.replace(WORK + "/", "").replace(OUT + "/", "test_output/"))
    text = "\n".join(keep[:40]) or "\n".join(lines[-20:])
    return text + "\n"


# ---------------------------------------------------------------- the scheduler
class Scheduler:
    """Runs callables side by side, the costliest waiting one first (cost: the seconds it is
    expected to take), so that the last to start are short and every core stays busy to the end:
    `jobs` at a time, and besides them up to `light` more that are light (submitted with
    light=True: a job that mostly waits, such as a window test between its inputs). submit()
    returns a concurrent.futures.Future."""

    def __init__(self, jobs, light=0):
        self.jobs, self.light = max(1, jobs), max(0, light)
        self.waiting, self.order = [], itertools.count()
        self.running, self.running_light = 0, 0
        self.cv = threading.Condition()
        self.closed = False
        self.threads = [threading.Thread(target=self._work, daemon=True) for _ in range(self.jobs + self.light)]
        for t in self.threads:
            t.start()

    def submit(self, fn, *args, cost=0.0, light=False):
        fut = cf.Future()
        with self.cv:
            heapq.heappush(self.waiting, ((-cost, next(self.order)), light, fut, fn, args))
            self.cv.notify_all()
        return fut

    def _next(self):
        """The costliest waiting job that a free place can take, and whether it takes a light
        job's place; None when none can start now."""
        if self.running < self.jobs and self.waiting:
            return heapq.heappop(self.waiting), False
        if self.running_light < self.light:
            for item in sorted(self.waiting):
                if item[1]:
                    self.waiting.remove(item)
                    heapq.heapify(self.waiting)
                    return item, True
        return None

    def _work(self):
        while True:
            with self.cv:
                while True:
                    picked = self._next()
                    if picked or (self.closed and not self.waiting):
                        break
                    self.cv.wait()
                if not picked:
                    return
                (_, _, fut, fn, args), as_light = picked
                if as_light:
                    self.running_light += 1
                else:
                    self.running += 1
            try:
                if fut.set_running_or_notify_cancel():
                    try:
                        fut.set_result(fn(*args))
                    except BaseException as ex:  # the caller's result() raises it
                        fut.set_exception(ex)
            finally:
                with self.cv:
                    if as_light:
                        self.running_light -= 1
                    else:
                        self.running -= 1
                    self.cv.notify_all()

    def close(self):
        with self.cv:
            self.closed = True
            self.cv.notify_all()
        for t in self.threads:
            t.join()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


# ---------------------------------------------------------------- GoogleTest programs in the sandbox
def discover_tests(job, mode):
    """{binary: [(gtest name, env dict)]} of every gtest CTest knows in the copy."""
    code, out = run_limited(sandbox(job, mode) + ["ctest", "--test-dir", "build", "--show-only=json-v1"], 300)
    if code != 0:
        die(f"ctest --show-only failed in the pristine copy: {out[-400:]}", 1)
    data = json.loads(out[out.index("{"):])
    tests = collections.defaultdict(list)
    for t in data.get("tests", []):
        cmd = t.get("command") or []
        filt = [a for a in cmd if a.startswith("--gtest_filter=")]
        if not cmd or not filt:
            continue
        env = {}
        for p in t.get("properties", []):
            if p.get("name") == "ENVIRONMENT":
                for kv in p.get("value", []):
                    k, _, v = kv.partition("=")
                    env[k] = v
        tests[cmd[0]].append((filt[0].split("=", 1)[1], env))
    return tests


def pictures_under(outdir):
    found = set()
    for base, dirs, files in os.walk(outdir):
        for f in files:
            if f.endswith("_diff.png"):
                found.add(os.path.relpath(os.path.join(base, f), outdir))
    return found


class ProgramRun:
    """One start of a GoogleTest program on its pending tests, read line by line: each test it
    starts gets its own deadline (limits[name]), and the time between tests start_limit."""

    def __init__(self, cmd, pending, limits, start_limit, outdir):
        self.pending, self.limits, self.start_limit, self.outdir = pending, limits, start_limit, outdir
        self.results = {}
        self.cur, self.buf, self.started, self.before = None, [], time.time(), set()
        self.deadline = time.time() + start_limit
        self.killed_for = None  # the test running at its deadline, or "start"
        self.p = started(subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True))
        self.lines = queue.Queue()  # at most MAX_PROCESS_OUTPUT: the reader stops there
        threading.Thread(target=self._reader, daemon=True).start()

    def _reader(self):
        # Lines of at most MAX_LINE (a longer one comes in pieces), MAX_PROCESS_OUTPUT in all:
        # past that the program is killed, and the rest of its output is not read.
        total = 0
        for raw in iter(lambda: self.p.stdout.readline(MAX_LINE), b""):
            total += len(raw)
            if total > MAX_PROCESS_OUTPUT:
                self.lines.put(f"(the test program wrote more than {MAX_PROCESS_OUTPUT >> 20} MiB: killed)\n")
                kill_group(self.p)
                break
            self.lines.put(raw.decode("utf-8", "replace"))
        self.lines.put(None)

    def read(self):
        """Reads until the program ends or a deadline passes (then kills it)."""
        while True:
            try:
                line = self.lines.get(timeout=max(0.05, self.deadline - time.time()))
            except queue.Empty:
                line = ""
            if line is None:
                break
            if time.time() > self.deadline:
                self.killed_for = self.cur or "start"
                kill_group(self.p)
                break
            if line:
                self._line(line)
        kill_group(self.p)
        self.p.wait()
        ended(self.p)

    def _line(self, line):
        m = RUN_RE.match(line)
        if m and m.group(1) in self.pending:
            self.cur, self.buf, self.started = m.group(1), [], time.time()
            self.before = pictures_under(self.outdir)
            self.deadline = self.started + self.limits.get(self.cur, 30.0)
            return
        m = END_TEST_RE.match(line)
        if m and self.cur and m.group(2) == self.cur:
            self._ended({"OK": "ok", "FAILED": "failed", "SKIPPED": "failed"}[m.group(1)], m.group(1) == "SKIPPED")
            return
        if self.cur and sum(map(len, self.buf)) < MAX_TEST_OUTPUT:
            self.buf.append(line)

    def _ended(self, status, skipped):
        if skipped:
            self.buf.append("(the test skipped itself: a graded test must run)\n")
        self.results[self.cur] = {"status": status, "output": "".join(self.buf)[:MAX_TEST_OUTPUT],
                                  "seconds": time.time() - self.started,
                                  "pictures": sorted(pictures_under(self.outdir) - self.before)}
        self.pending.remove(self.cur)
        self.cur = None
        self.deadline = time.time() + self.start_limit

    def settle(self, binary, limits, after_hang):
        """The tests the program's ending decides (a hang, a crash, tests it never ran). True: start
        it again on the tests still pending."""
        name = os.path.basename(binary)
        if self.killed_for and self.killed_for != "start":
            t = self.killed_for
            self.results[t] = {"status": "timeout", "seconds": time.time() - self.started,
                               "output": "".join(self.buf)[:MAX_TEST_OUTPUT] +
                               f"\n(killed: still running after its limit of {limits.get(t, 30.0):.0f} s)\n",
                               "pictures": []}
            self.pending.remove(t)
            for n, lim in (after_hang or {}).items():  # a hang costs less from now on
                limits[n] = min(limits.get(n, lim), lim)
            return True
        if self.killed_for == "start":
            for n in self.pending:
                self.results[n] = {"status": "timeout", "seconds": 0, "pictures": [],
                                   "output": f"(the test program {name} hung before this test started; killed after {self.start_limit:.0f} s)\n"}
            return False
        if self.cur:  # the program ended inside a test: a crash
            rc = self.p.returncode
            why = f"killed by signal {-rc}" if rc < 0 else f"exited {rc}"
            self.results[self.cur] = {"status": "crashed", "seconds": time.time() - self.started,
                                      "output": "".join(self.buf)[:MAX_TEST_OUTPUT] + f"\n(the test program {why} during this test)\n",
                                      "pictures": []}
            self.pending.remove(self.cur)
            return True
        for n in self.pending:  # ended without running them
            self.results[n] = {"status": "not-run", "seconds": 0, "pictures": [],
                               "output": f"(the test program {name} exited {self.p.returncode} without running this test)\n"}
        return False


def run_tests(job, by_binary, limits, start_limit=30.0, shared=None, env_extra=None, work=None, binds=(), after_hang=None):
    """Runs tests {binary: [(name, env)]} in job's sandbox, each with its own wall limit
    (limits[name] seconds). Returns {name: {status, output, seconds, pictures}}; status is one of
    ok, failed, timeout, crashed, not-run. env_extra, work, binds: see sandbox(). after_hang: the
    limits once a test has hung (a hang costs less: 3× the solution's own time + 2 s)."""
    results = {}
    outdir = os.path.join(job, "out")
    limits = dict(limits)
    for binary in sorted(by_binary):
        pending = [n for n, _ in by_binary[binary]]
        env = {}
        for _, e in by_binary[binary]:
            env.update(e)
        env["LAB_TEST_OUTPUT"] = OUT
        env.update(env_extra or {})
        again = True
        while pending and again:
            cmd = sandbox(job, "test", env=env, shared=shared, work=work, binds=binds) + \
                [binary, "--gtest_color=no", "--gtest_filter=" + ":".join(pending)]
            run = ProgramRun(cmd, pending, limits, start_limit, outdir)
            run.read()
            again = run.settle(binary, limits, after_hang)
            results.update(run.results)
    return results


def run_judged(job, subset, tests, limits, judge_limits, shared, judge_work, source_dirs, manifest=None,
               start_limit=30.0, after_hang=None):
    """(results, the probe's own results) of tests on job's build: the probe records in job's
    sandbox, the judge decides in a sandbox of its own on the judge's build (judge_work) with the
    probe's records, job's source_dirs and manifest (the exercises' manifest of job's copy, which
    the hints read: $LAB_EXERCISE_MANIFEST) bound read-only. subset(names): {binary: [(name, env)]}
    of those tests."""
    records = os.path.join(job, "out", "probe")
    os.makedirs(records, exist_ok=True)
    chown_tree(job)
    probe = run_tests(job, subset(tests), limits, start_limit=start_limit, shared=shared,
                      env_extra={"LAB_PROBE": "record", "LAB_PROBE_DIR": OUT + "/probe"}, after_hang=after_hang)
    # A test the probe ran to its end (as far as its output tells: the student's code may print
    # anything) goes to the judge; a crash or a hang is the probe's own ending, and fails.
    ended = [n for n in tests if probe[n]["status"] in ("ok", "failed")]
    results = {n: dict(probe[n], pictures=[]) for n in tests if n not in ended}
    if ended:
        judge = job.rstrip("/") + "-judge"
        os.makedirs(os.path.join(judge, "out"))
        chown_tree(judge)
        binds = [(records, PROBE)] + [(os.path.join(job, "work", d), f"{WORK}/{d}") for d in source_dirs]
        env = {"LAB_PROBE": "replay", "LAB_PROBE_DIR": PROBE}
        if manifest:
            binds.append((manifest, MANIFEST))
            env["LAB_EXERCISE_MANIFEST"] = MANIFEST
        judged = run_tests(judge, subset(ended), judge_limits, start_limit=start_limit, work=judge_work, binds=binds,
                           env_extra=env)
        for n, r in judged.items():
            r["pictures_dir"] = os.path.join(judge, "out")
            if r["status"] in ("timeout", "crashed", "not-run"):
                r["output"] = "(the judge, which runs no student code, did not finish this test on the probe's values)\n" + r["output"]
        results.update(judged)
    return results, probe


# ---------------------------------------------------------------- CTest tests as CTest runs them
class CtestTest:
    """A test as `ctest --show-only=json-v1` describes it: its command, environment (added to the
    grader's), working folder, timeout, skip code, pass expressions and WILL_FAIL."""

    def __init__(self, t, default_cwd):
        p = {x["name"]: x["value"] for x in t.get("properties", [])}
        # A parameterized gtest's CTest name ends in "  # GetParam() = …": its gtest name is before.
        self.name = t["name"].split("  # ")[0]
        self.command = list(t.get("command") or [])
        self.disabled = bool(p.get("DISABLED"))
        self.env = dict(kv.partition("=")[::2] for kv in p.get("ENVIRONMENT", []))
        self.cwd = p.get("WORKING_DIRECTORY") or default_cwd
        self.timeout = float(p.get("TIMEOUT", 300))
        self.skip_code = int(p["SKIP_RETURN_CODE"]) if p.get("SKIP_RETURN_CODE") is not None else None
        self.pass_regex = p.get("PASS_REGULAR_EXPRESSION")
        self.will_fail = bool(p.get("WILL_FAIL"))

    def gtest(self):
        """(program, gtest name) for a GoogleTest test, else None."""
        filt = [a for a in self.command if a.startswith("--gtest_filter=")]
        return (self.command[0], filt[0].split("=", 1)[1]) if self.command and filt else None


def label_tests(build, short, exclude="^grader_", fixtures_out="^lab_build$"):
    """The tests of label `short` in build that a student copy runs (not the label `instructors`,
    which a copy disables: tests/CMakeLists.txt), without those matching exclude and without the
    tests that fixtures_out's fixtures would add."""
    cmd = ["ctest", "--test-dir", build, "--show-only=json-v1", "-L", "^%s$" % short, "-LE", "^instructors$",
           "-E", exclude, "-FA", fixtures_out]
    for attempt in range(3):  # a build folder being configured beside the grader lists nothing for a moment
        r = subprocess.run(cmd, capture_output=True, text=True)
        try:
            return [CtestTest(t, build) for t in json.loads(r.stdout)["tests"]]
        except ValueError:
            time.sleep(5)
    die(f"ctest --show-only failed in {build}: {r.stderr.strip()[-400:]}", 1)


def select(tests, only):
    """The tests whose names match one of only's names or fnmatch patterns (None: all)."""
    if only is None:
        return list(tests)
    return [t for t in tests if any(fnmatch.fnmatchcase(t.name, pat) for pat in only)]


def run_ctest_test(test, cmd, env, log_path):
    """Runs one CTest test as CTest would (cmd and env: its command and environment as the caller
    points them), killing its process group at its timeout. Returns {status: passed | failed |
    skipped, named: the exercise its output names first (named_exercise), seconds, cpu, output}."""
    r = run_limited(cmd, test.timeout, env=env, cwd=test.cwd, keep_tail=True)
    text = r.output + ("\n(timed out)\n" if r.code is None else "")
    code = -1 if r.code is None else r.code
    passed = code == 0
    if test.pass_regex:
        passed = any(re.search(rx, text) for rx in test.pass_regex)
    if test.will_fail:
        passed = not passed
    status = "passed" if passed else "failed"
    if code != 0 and test.skip_code is not None and code == test.skip_code:
        status = "skipped"
    os.makedirs(os.path.dirname(log_path), exist_ok=True)
    with open(log_path, "w") as f:
        f.write(" ".join(cmd) + "\n" + text)
    return {"status": status, "named": named_exercise(text), "seconds": r.seconds, "cpu": r.cpu, "output": text}
