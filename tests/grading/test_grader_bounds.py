#!/usr/bin/env python3
"""test_grader_bounds.py — the class grader's bounds (scripts/grade/grade.py), each shown to hold,
as the user running it and, when that is root, once more as a plain user (CTest: grader_bounds).

  * processes: a fork bomb in one job meets its own limit; a job beside it still starts 20;
  * /tmp in the sandbox holds at most SANDBOX_TMP;
  * a test program that floods its output without a newline is killed, and the grader keeps a
    bounded part of it (its own memory grows by far less than the flood);
  * after a hang, the limits of the tests left are 3× the solution's time + 2 s, however many hang;
  * a result the environment made (a timeout, a crash, a grader error) is not cached for the next
    submission with the same code; a compile failure is;
  * a cache folder that another user could write is refused (exit 2);
  * a student named like the class's own files (index.html, grades.csv) is graded like any other.

Exit 77 (skip) without a working bubblewrap, a failure in CI.
"""
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts", "grade"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import grade  # noqa: E402
from test_grading import skip_unless_gradable  # noqa: E402

problems = []
# Debian's python3: the plain user of the second run can run it wherever the caller's came from
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        problems.append(what)


def new_job(base, name):
    job = os.path.join(base, name)
    os.makedirs(os.path.join(job, "work"))
    os.makedirs(os.path.join(job, "out"))
    grade.chown_tree(job)
    return job


def in_sandbox(job, script, wall=60):
    return grade.run_limited(grade.sandbox(job, "test") + ["python3", "-c", script], wall)


def forker(label, count, child_seconds, hold_seconds=0):
    """A Python program that starts up to `count` children (each sleeps child_seconds), prints how
    many started, then holds them for hold_seconds."""
    return (f"import os, time\nn = 0\nfor i in range({count}):\n    try:\n"
            f"        if os.fork() == 0:\n            time.sleep({child_seconds}); os._exit(0)\n        n += 1\n"
            f"    except OSError:\n        pass\nprint('{label}', n, flush=True)\ntime.sleep({hold_seconds})\n")


FORK_BOMB = forker("bomb", 3000, 8, 8)
TWENTY = forker("beside", 20, 0.5)


def processes(base):
    bomb = new_job(base, "job1")
    beside = new_job(base, "job2")
    got = {}
    t = threading.Thread(target=lambda: got.update(bomb=in_sandbox(bomb, FORK_BOMB)))
    t.start()
    time.sleep(3)
    code, out = in_sandbox(beside, TWENTY)
    t.join()
    n = int(next((l.split()[1] for l in got["bomb"][1].splitlines() if l.startswith("bomb")), "-1"))
    check(0 < n < grade.SANDBOX_NPROC, f"the fork bomb stopped at its job's limit: {n} processes (limit {grade.SANDBOX_NPROC})")
    check("beside 20" in out, f"the job beside it started its 20 processes: {out.strip()[-200:]!r}")


def tmp_size(base):
    job = new_job(base, "job3")
    code, out = in_sandbox(job, """
import os
n = 0
try:
    with open("/tmp/big", "wb") as f:
        for i in range(400):
            f.write(b"\\0" * (1 << 20)); f.flush(); n += 1
except OSError as e:
    print("stopped", e.errno)
print("MiB", os.path.getsize("/tmp/big") >> 20)
""")
    mib = int(next((l.split()[1] for l in out.splitlines() if l.startswith("MiB")), "-1"))
    check("stopped" in out and 0 < mib <= grade.SANDBOX_TMP >> 20, f"/tmp holds at most {grade.SANDBOX_TMP >> 20} MiB: wrote {mib} MiB")


def fake_tests(job, text):
    """A test program in job's copy that prints what GoogleTest would, as a shell script."""
    path = os.path.join(job, "work", "fake_tests.sh")
    with open(path, "w") as f:
        f.write("#!/bin/sh\n" + text)
    os.chmod(path, 0o755)
    grade.chown_tree(job)
    return grade.WORK + "/fake_tests.sh"


def flood(base):
    job = new_job(base, "job4")
    prog = fake_tests(job, "echo '[ RUN      ] Flood.Test'\nhead -c 300000000 /dev/zero | tr '\\0' x\necho\necho '[       OK ] Flood.Test (0 ms)'\n")
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    res = grade.run_tests(job, {prog: [("Flood.Test", {})]}, {"Flood.Test": 120})
    grew = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) >> 10
    r = res["Flood.Test"]
    check(r["status"] != "ok" and len(r["output"]) <= grade.MAX_TEST_OUTPUT + 200,
          f"a 300 MB line is cut and the test fails: {r['status']}, {len(r['output'])} bytes kept")
    check(grew < 200, f"the grader's memory grew by {grew} MiB reading it (the flood: 286 MiB)")


def hangs(base):
    job = new_job(base, "job5")
    script = """
for t in $(echo "$2" | sed 's/--gtest_filter=//; s/:/ /g'); do
  echo "[ RUN      ] $t"
  case $t in Hang.*) sleep 1000 ;; *) sleep 2.5 ;; esac
  echo "[       OK ] $t (0 ms)"
done
"""
    prog = fake_tests(job, script)
    tests = ["Hang.A", "Hang.B", "Slow.C"]
    t0 = time.time()
    res = grade.run_tests(job, {prog: [(n, {}) for n in tests]}, {n: 4.0 for n in tests}, after_hang={n: 3 * 1.0 + 2 for n in tests})
    check([res[n]["status"] for n in tests] == ["timeout", "timeout", "ok"],
          f"after two hangs a 2.5 s test still has 3 × 1 s + 2 s: {[res[n]['status'] for n in tests]} ({time.time() - t0:.0f} s)")


def no_cached_environment_failures():
    g = object.__new__(grade.Grader)
    g.lock, g.variants = threading.Lock(), {}
    runs = []
    for outcome in ({"build": "ok", "tests": {"T.x": {"status": "timeout"}}}, {"build": "error", "tests": {}},
                    {"build": "ok", "tests": {"T.x": {"status": "crashed"}}}, {"build": "failed", "log": "error: x", "tests": {}}):
        g._run_variant = lambda changes, tests, o=outcome: runs.append(1) or o
        runs.clear()
        for _ in range(2):
            g.variant({"f.cpp": "x" + str(outcome)}, ["T.x"])
        want = 1 if outcome["build"] == "failed" else 2
        check(len(runs) == want, f"{outcome['build']}/{list(outcome['tests'].values())}: run {len(runs)} times for two identical submissions (expected {want})")


def cache_owner(base):
    loose = os.path.join(base, "loose-cache")
    os.makedirs(loose)
    os.chmod(loose, 0o777)
    subs = os.path.join(base, "subs")
    os.makedirs(os.path.join(subs, "someone"))
    r = subprocess.run([PYTHON, os.path.join(ROOT, "scripts/grade/grade.py"), "1", subs, "--out", os.path.join(base, "o"),
                        "--cache", loose], capture_output=True, text=True)
    check(r.returncode == 2 and "not trusted" in r.stderr, f"a cache anyone can write is refused: exit {r.returncode}, {r.stderr.strip()[-160:]!r}")


def student_names(base):
    class G:
        lab = "lab1_camera"
        exercises = [{"name": "x", "file": "f.cpp", "tests": ["T.x"]}]
        all_tests = ["T.x"]
    subs = []
    for name in ("index.html", "grades.csv", "students"):
        s = grade.Submission(name)
        s.grades = {"x": 1}
        subs.append(s)
    out = os.path.join(base, "names")
    os.makedirs(out)
    try:
        grade.write_outputs(G(), subs, out)
        ok = all(os.path.isfile(os.path.join(out, "students", n, "results.json")) for n in ("index.html", "grades.csv", "students"))
        check(ok and os.path.isfile(os.path.join(out, "index.html")) and os.path.isfile(os.path.join(out, "grades.csv")),
              "students named index.html, grades.csv and students get their reports beside the class's own files")
    except Exception as ex:
        check(False, f"students named like the class's files: {ex!r}")


def main():
    if "--as-user" not in sys.argv:
        skip_unless_gradable("grader_bounds")
    base = tempfile.mkdtemp(prefix="grader-bounds-")
    os.chmod(base, 0o755)
    who = "root" if os.geteuid() == 0 else f"uid {os.geteuid()}"
    print(f"grader_bounds as {who}")
    try:
        processes(base)
        tmp_size(base)
        flood(base)
        hangs(base)
        no_cached_environment_failures()
        cache_owner(base)
        student_names(base)
    finally:
        shutil.rmtree(base, ignore_errors=True)
    if os.geteuid() == 0:  # once more as a plain user (no user of its own per job)
        r = subprocess.run(["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", "--reset-env",
                            PYTHON, os.path.abspath(__file__), "--as-user"], text=True, capture_output=True)
        sys.stdout.write(r.stdout + r.stderr)
        if r.returncode != 0:
            problems.append(f"as a plain user: exit {r.returncode}")
    if problems:
        print(f"{len(problems)} bound(s) did not hold")
        sys.exit(1)
    print("grader_bounds: every bound holds")


if __name__ == "__main__":
    main()
