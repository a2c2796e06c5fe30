#!/usr/bin/env python3
"""grade.py — grade every submission of a lab (scripts/grade.sh is the command; see docs/solutions.md
"Grading a class").

    python3 scripts/grade/grade.py LAB SUBMISSIONS [--out DIR] [--jobs N] [--cache DIR]

How a grade is made:
  * The pristine copy: the student copy of LAB (scripts/exercise.sh) with the lab's own folders
    replaced by the instructors' solved ones, configured and built once inside the sandbox at the
    fixed path /grade/work, cached (--cache, default /tmp/vulkan-labs-grade-UID) under a key of the
    repository's HEAD and uncommitted changes; the cache keeps the newest two per lab (evict()).
  * Only the exercises count: from a submission the grader reads only the text between each
    `TODO EXERCISE name` (or `EXERCISE name`) line and its `END EXERCISE` line. Every other file is
    compared with the handed-out copy and only listed ("changed outside the exercises").
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
    and how it exits, decide nothing but a crash or a hang.
  * A region that steps outside its exercise (region_check.py: unbalanced braces, preprocessor
    lines, output, process, file or dynamic-loading calls, inline assembly, builtins, the test side)
    gets 0 and a note that says why.
  * Every build and test runs in sandbox() below.
"""
import argparse
import collections
import concurrent.futures as cf
import csv
import fnmatch
import hashlib
import html
import io
import json
import os
import queue
import re
import shutil
import signal
import stat
import subprocess
import sys
import tarfile
import tempfile
import threading
import time
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import region_check  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
WORK = "/grade/work"   # where a copy is seen inside the sandbox (its build has this path baked in)
OUT = "/grade/out"     # the tests' output folder inside the sandbox (LAB_TEST_OUTPUT)
PROBE = "/grade/probe" # the judge's read-only view of the probe's records (tests/probe.h)
# As root, each job's sandbox runs as a user of its own, SANDBOX_UID + the job's number (no account
# needs to exist for it): RLIMIT_NPROC counts the processes and threads of a user, so a fork bomb in
# one job exhausts its own user's count, never that of a job running beside it; and no job can
# write another job's files.
SANDBOX_UID = 200000
IGNORED_TOP = re.compile(r"^(build[^/]*|out|student|\.git|\.cache|\.vscode|\.idea)$")
EXT_ARCHIVE = (".tar.gz", ".tgz", ".zip")
MAX_EXTRACT_BYTES = 512 << 20
MAX_EXTRACT_FILES = 20000
MAX_REGION_BYTES = 256 << 10
STUDENTS = "students"          # each student's report is in OUT/students/NAME/ (any name is safe there)
MAX_TEST_OUTPUT = 64 << 10     # what a report keeps of one test's output
MAX_PROCESS_OUTPUT = 64 << 20  # what the grader reads of one test program's output before killing it
MAX_LINE = 64 << 10            # a longer line is read in pieces
SANDBOX_TMP = 256 << 20        # the sandbox's /tmp (memory)
SANDBOX_NPROC = 512            # processes and threads of one job


def die(msg, code=2):
    print(f"grade: {msg}", file=sys.stderr)
    sys.exit(code)


def log(msg):
    print(msg, file=sys.stderr, flush=True)


# ---------------------------------------------------------------- the sandbox
# bubblewrap, run as an unprivileged user (nobody when the grader is root):
#   - new user, PID, network, IPC, UTS and cgroup namespaces (--unshare-all): no network at all
#     (only a loopback device), no other process visible, every process of the sandbox killed when
#     its first process ends or the grader kills it (--die-with-parent, the PID namespace);
#   - a file system of /usr and /etc read-only, a private /proc, a minimal /dev, an empty private
#     /tmp (tmpfs), and the job's copy at /grade/work: read-only, but for its build/ folder while it
#     builds and /grade/out (the tests' pictures) while its tests run. The instructors'
#     repository, the submissions, the cache and the output folder are not in it;
#   - limits (prlimit, per process): CPU seconds, address space, file size, open files, no core
#     files; wall time: the grader kills it; /tmp at most SANDBOX_TMP;
#   - the number of processes and threads, per job, with or without root: prlimit --nproc runs
#     inside the sandbox's own user namespace, and Linux (5.14 on) counts a user's processes per
#     user namespace, so a fork bomb meets its own job's limit, never a neighbour's (check_isolation).
def job_uid(job):
    """The user job's sandbox runs as (when the grader is root): SANDBOX_UID + N for scratch/jobN."""
    m = re.fullmatch(r"job(\d+)", os.path.basename(os.path.normpath(job)))
    return SANDBOX_UID + (int(m.group(1)) if m else 0)


def sandbox(job, mode, env=None, cpu=600, shared=None, work=None, binds=()):
    """The command prefix that runs a command in job's copy. mode: build | test | setup. shared:
    the pristine copy whose build/common (never rebuilt by a submission) is seen read-only. work:
    another tree to see read-only at WORK (the judge's); binds: (path, place) pairs seen read-only."""
    work = work or os.path.join(job, "work")
    cmd = []
    if os.geteuid() == 0:
        uid = job_uid(job)
        cmd += ["setpriv", f"--reuid={uid}", f"--regid={uid}", "--clear-groups"]
    cmd += ["prlimit", f"--cpu={cpu}", f"--as={8 << 30}", f"--fsize={1 << 30}", "--nofile=1024", "--core=0", "--"]
    cmd += ["bwrap", "--unshare-all", "--die-with-parent", "--new-session", "--clearenv",
            "--ro-bind", "/usr", "/usr", "--ro-bind", "/etc", "/etc"]
    for link in ("bin", "lib", "lib64", "sbin", "lib32"):
        if os.path.islink("/" + link):
            cmd += ["--symlink", os.readlink("/" + link), "/" + link]
    cmd += ["--proc", "/proc", "--dev", "/dev", "--size", str(SANDBOX_TMP), "--tmpfs", "/tmp"]
    if mode == "setup":
        cmd += ["--bind", work, WORK]
    else:
        cmd += ["--ro-bind", work, WORK]
        if mode == "build":
            cmd += ["--bind", os.path.join(work, "build"), WORK + "/build"]
        else:
            cmd += ["--bind", os.path.join(job, "out"), OUT]
        if shared:
            cmd += ["--ro-bind", os.path.join(shared, "build", "common"), WORK + "/build/common"]
    for path, place in binds:
        cmd += ["--ro-bind", path, place]
    cmd += ["--chdir", WORK]
    base = {"PATH": "/usr/bin:/bin", "HOME": "/tmp", "LANG": "C.UTF-8", "TMPDIR": "/tmp"}
    if os.environ.get("LP_NUM_THREADS"):
        base["LP_NUM_THREADS"] = os.environ["LP_NUM_THREADS"]
    base.update(env or {})
    for k, v in sorted(base.items()):
        cmd += ["--setenv", k, v]
    return cmd + ["--", "prlimit", f"--nproc={SANDBOX_NPROC}", "--"]


def check_isolation():
    """Refuses to grade where one job's processes could exhaust another's: without root (no user of
    its own per job) that takes Linux 5.14 or later, which counts processes per user namespace."""
    if os.geteuid() == 0:
        return
    release = re.match(r"(\d+)\.(\d+)", os.uname().release)
    if not release or (int(release.group(1)), int(release.group(2))) < (5, 14):
        die(f"not graded: without root, a job's process limit holds apart from its neighbours' only on Linux 5.14 "
            f"or later (this is {os.uname().release}); run grade.sh as root (each job its own user) or on a newer kernel", 2)


def kill_group(p):
    try:
        os.killpg(p.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def run_limited(cmd, wall):
    """Runs cmd (a sandbox command) with a wall-time limit: (exit code, or None if killed at the limit; output)."""
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True)
    chunks, size, fired = [], 0, []
    timer = threading.Timer(wall, lambda: (fired.append(1), kill_group(p)))
    timer.start()
    try:
        for chunk in iter(lambda: p.stdout.read(65536), b""):
            if size < (4 << 20):
                chunks.append(chunk)
            size += len(chunk)
            if size > MAX_PROCESS_OUTPUT:
                kill_group(p)
                break
        p.wait()
    finally:
        timer.cancel()
        kill_group(p)
    out = b"".join(chunks).decode("utf-8", "replace")
    return (None if fired else p.returncode), out


def chown_tree(path):
    """path (a job's folder) made its sandbox user's."""
    if os.geteuid() != 0:
        return
    uid = job_uid(path)
    subprocess.run(["chown", "-R", "-h", f"{uid}:{uid}", path], check=True)


# ---------------------------------------------------------------- the lab and its exercises
def resolve_lab(want):
    labs = sorted(d for d in os.listdir(ROOT) if re.match(r"^lab\d+_", d) and os.path.isfile(os.path.join(ROOT, d, "CMakeLists.txt")))
    w = want if want.startswith("lab") else "lab" + want
    for d in labs:
        if d == w or d.split("_")[0] == w:
            return d
    die(f"no lab '{want}' here; the labs are: {' '.join(labs)}")


def exercises_of(lab):
    out = subprocess.run(["bash", os.path.join(ROOT, "scripts/exercise.sh"), "--list", lab],
                         capture_output=True, text=True, check=True).stdout
    ex = []
    for line in out.splitlines():
        m = re.match(r"^  (\S+)\s+(\S+):(\d+)\s+\(tests: (.*)\)$", line)
        if m:
            ex.append({"name": m.group(1), "file": m.group(2), "line": int(m.group(3)),
                       "checked": [] if m.group(4) == "none" else m.group(4).split()})
    return ex


END_RE = re.compile(r"^[ \t]*// END EXERCISE[ \t]*$")


def find_region(lines, name):
    """(start, end) line indexes of the marker and END lines of exercise name, or None."""
    marker = re.compile(r"// (TODO )?EXERCISE " + re.escape(name) + r": ")
    for i, line in enumerate(lines):
        if marker.search(line):
            for j in range(i + 1, len(lines)):
                if END_RE.match(lines[j]):
                    return i, j
                if re.search(r"// (TODO )?EXERCISE [a-z0-9_]+: ", lines[j]):
                    return None
            return None
    return None


def split_lines(text):
    return text.splitlines(keepends=True)


# ---------------------------------------------------------------- the pristine copy
def repo_key(lab):
    h = hashlib.sha256(lab.encode())
    git = lambda *a: subprocess.run(["git", "-C", ROOT, *a], capture_output=True).stdout
    h.update(git("rev-parse", "HEAD"))
    h.update(git("diff", "HEAD", "--binary"))
    for f in sorted(git("ls-files", "--others", "--exclude-standard", "-z").split(b"\0")):
        if f:
            h.update(f)
            try:
                with open(os.path.join(ROOT, f.decode()), "rb") as fh:
                    h.update(hashlib.sha256(fh.read()).digest())
            except OSError:
                pass
    return os.environ.get("GRADE_PRISTINE_KEY") or h.hexdigest()[:16]


def owned_by_us(path):
    """path is this user's and nobody else can write it (a cache another user could fill is not used)."""
    st = os.lstat(path)
    return stat.S_ISDIR(st.st_mode) and st.st_uid == os.geteuid() and not st.st_mode & 0o022


def pristine(lab, cache_root, jobs):
    """The cached pristine copy of lab: {dir, copy (the handed-out copy), work (solved + build),
    judge (the handed-out copy built: the judge's tests)}."""
    key = repo_key(lab)
    d = os.path.join(cache_root, f"{lab}-{key}")
    os.makedirs(cache_root, mode=0o755, exist_ok=True)
    if not owned_by_us(cache_root):
        die(f"--cache {cache_root}: not a folder of this user's that only this user can write; "
            f"a cache that another user could fill is not trusted (choose another --cache)", 2)
    if os.path.isfile(os.path.join(d, "done")):
        if not owned_by_us(d):
            die(f"{d}: the cached pristine copy is not this user's alone; delete it or choose another --cache", 2)
        log(f"grade: pristine {lab} from the cache ({d})")
        return d
    tmp = tempfile.mkdtemp(prefix=f"{lab}-{key}-", dir=cache_root)
    os.chmod(tmp, 0o755)
    t0 = time.time()
    log(f"grade: writing the student copy of {lab} and building the pristine copy in {tmp} (once per lab and commit)")
    r = subprocess.run(["bash", os.path.join(ROOT, "scripts/exercise.sh"), lab, "--out", os.path.join(tmp, "copy")],
                       capture_output=True, text=True)
    if r.returncode:
        die(f"scripts/exercise.sh {lab} failed: {r.stderr.strip()[:300]}", 1)
    work = os.path.join(tmp, "work")
    shutil.copytree(os.path.join(tmp, "copy"), work, symlinks=True)
    for sub in (lab, os.path.join("shaders", lab)):
        if os.path.isdir(os.path.join(ROOT, sub)):
            shutil.rmtree(os.path.join(work, sub), ignore_errors=True)
            shutil.copytree(os.path.join(ROOT, sub), os.path.join(work, sub), symlinks=True)
    os.makedirs(os.path.join(work, "build"))
    chown_tree(work)
    # The students' build type (scripts/setup.sh), without its -g: GCC makes the same code with and
    # without debug information, and without it every variant copies and links fewer bytes.
    code, out = run_limited(sandbox(tmp, "setup", cpu=3600) + ["cmake", "-S", ".", "-B", "build", "-DCMAKE_BUILD_TYPE=RelWithDebInfo",
                                                              "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -DNDEBUG",
                                                              "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -DNDEBUG"], 600)
    if code != 0:
        fail_build(tmp, lab, out)
    # Only what grading runs: the lab and the test programs labelled like it (their CTest include
    # files name the label); everything when an exercise names a test none of them holds.
    short = lab.split("_")[0]
    targets = [lab]
    for f in sorted(os.listdir(os.path.join(work, "build", "tests"))):
        m = re.match(r"^(.+)\[1\]_include\.cmake$", f)
        if m and re.search(r"LABELS;" + short + r"\]", open(os.path.join(work, "build", "tests", f)).read()):
            targets.append(m.group(1))
    for attempt in (targets, ["all"]):
        code, out = run_limited(sandbox(tmp, "setup", cpu=3600) + ["nice", "-n", "10", "cmake", "--build", "build", f"-j{jobs}", "--target", *attempt], 3600)
        if code != 0:
            fail_build(tmp, lab, out)
        tests = discover_tests(tmp, "setup")
        suites = {n.split("/")[-1].split(".")[0] for ts in tests.values() for n, _ in ts} | \
                 {n.split("/")[0].split(".")[0] for ts in tests.values() for n, _ in ts}
        wanted = {p.split("/")[-1].split(".")[0] for e in exercises_of(lab) for p in e["checked"]}
        if wanted <= suites:
            break
        log(f"grade: the {short} test programs lack {' '.join(sorted(wanted - suites))}: building everything")
    with open(os.path.join(tmp, "tests.json"), "w") as f:
        json.dump(tests, f, indent=1, sort_keys=True)
    # The judge: the handed-out copy (every exercise its stub) built with the same test programs. It
    # runs the tests on the probe's records (tests/probe.h): no student code, and no solution either,
    # so a value that a test takes from the lab without a probe comes from a stub and the solution
    # fails its own test there (Grader refuses to start).
    judge = os.path.join(tmp, "judge")
    shutil.copytree(os.path.join(tmp, "copy"), os.path.join(judge, "work"), symlinks=True)
    os.makedirs(os.path.join(judge, "work", "build"))
    chown_tree(judge)
    code, out = run_limited(sandbox(judge, "setup", cpu=3600) + ["cmake", "-S", ".", "-B", "build", "-DCMAKE_BUILD_TYPE=RelWithDebInfo",
                                                                "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -DNDEBUG",
                                                                "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -DNDEBUG"], 600)
    if code == 0:
        code, out = run_limited(sandbox(judge, "setup", cpu=3600) + ["nice", "-n", "10", "cmake", "--build", "build", f"-j{jobs}",
                                                                    "--target", *sorted({os.path.basename(b) for b in tests})], 3600)
    if code != 0:
        fail_build(tmp, lab + " (the judge: the handed-out copy)", out)
    if os.geteuid() == 0:  # the cache is the grader's: no sandbox may change it
        subprocess.run(["chown", "-R", "-h", "0:0", work, os.path.join(judge, "work")], check=True)
    open(os.path.join(tmp, "done"), "w").write(f"built in {time.time() - t0:.0f} s\n")
    try:
        os.rename(tmp, d)
    except OSError:  # another grader finished first
        shutil.rmtree(tmp, ignore_errors=True)
    log(f"grade: pristine {lab} built in {time.time() - t0:.0f} s")
    evict(cache_root, lab, keep=d)
    return d


# A pristine copy takes 100-300 MB and every commit makes a new one: the cache keeps the newest
# CACHE_KEEP per lab (by when each was built) and drops copies that never finished (a grader
# killed while building) after CACHE_STALE_S.
CACHE_KEEP = 2
CACHE_STALE_S = 6 * 3600


def evict(cache_root, lab, keep):
    """Deletes lab's older pristine copies in cache_root (never keep, the one in use)."""
    done, now = [], time.time()
    for name in os.listdir(cache_root):
        path = os.path.join(cache_root, name)
        if not name.startswith(lab + "-") or os.path.normpath(path) == os.path.normpath(keep) or not os.path.isdir(path):
            continue
        marker = os.path.join(path, "done")
        if os.path.isfile(marker):
            done.append((os.path.getmtime(marker), path))
        elif now - os.path.getmtime(path) > CACHE_STALE_S:
            shutil.rmtree(path, ignore_errors=True)
    for _, path in sorted(done, reverse=True)[CACHE_KEEP - 1:]:
        log(f"grade: dropping an older pristine {lab} from the cache ({path})")
        shutil.rmtree(path, ignore_errors=True)


def fail_build(tmp, lab, out):
    with open(os.path.join(tmp, "build.log"), "w") as f:
        f.write(out)
    die(f"the pristine copy of {lab} does not build (see {tmp}/build.log)", 1)


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


# ---------------------------------------------------------------- running tests
RUN_RE = re.compile(r"^\[ RUN      \] (\S+)")
END_TEST_RE = re.compile(r"^\[ +(OK|FAILED|SKIPPED) +\] (\S+?),?( |$)")


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
        while pending:
            cmd = sandbox(job, "test", env=env, shared=shared, work=work, binds=binds) + \
                [binary, "--gtest_color=no", "--gtest_filter=" + ":".join(pending)]
            p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True)
            lines = queue.Queue()  # at most MAX_PROCESS_OUTPUT: the reader stops there

            def reader(stream=p.stdout, q=lines, proc=p):
                # Lines of at most MAX_LINE (a longer one comes in pieces), MAX_PROCESS_OUTPUT in all:
                # past that the program is killed, and the rest of its output is not read.
                total = 0
                for raw in iter(lambda: stream.readline(MAX_LINE), b""):
                    total += len(raw)
                    if total > MAX_PROCESS_OUTPUT:
                        q.put(f"(the test program wrote more than {MAX_PROCESS_OUTPUT >> 20} MiB: killed)\n")
                        kill_group(proc)
                        break
                    q.put(raw.decode("utf-8", "replace"))
                q.put(None)
            threading.Thread(target=reader, daemon=True).start()
            cur, buf, started, any_started = None, [], time.time(), False
            before = set()
            deadline = time.time() + start_limit
            killed_for = None
            while True:
                try:
                    line = lines.get(timeout=max(0.05, deadline - time.time()))
                except queue.Empty:
                    line = ""
                if line is None:
                    break
                if time.time() > deadline:
                    killed_for = cur or "start"
                    kill_group(p)
                    break
                if not line:
                    continue
                m = RUN_RE.match(line)
                if m and m.group(1) in pending:
                    cur, buf, started, any_started = m.group(1), [], time.time(), True
                    before = pictures_under(outdir)
                    deadline = started + limits.get(cur, 30.0)
                    continue
                m = END_TEST_RE.match(line)
                if m and cur and m.group(2) == cur:
                    status = {"OK": "ok", "FAILED": "failed", "SKIPPED": "failed"}[m.group(1)]
                    if m.group(1) == "SKIPPED":
                        buf.append("(the test skipped itself: a graded test must run)\n")
                    results[cur] = {"status": status, "output": "".join(buf)[:MAX_TEST_OUTPUT],
                                    "seconds": time.time() - started,
                                    "pictures": sorted(pictures_under(outdir) - before)}
                    pending.remove(cur)
                    cur = None
                    deadline = time.time() + start_limit
                    continue
                if cur and sum(map(len, buf)) < MAX_TEST_OUTPUT:
                    buf.append(line)
            kill_group(p)
            p.wait()
            if killed_for == "start" or (cur is None and not any_started and pending and p.returncode != 0 and killed_for is None and False):
                pass
            if killed_for and killed_for != "start":
                results[killed_for] = {"status": "timeout", "seconds": time.time() - started,
                                       "output": "".join(buf)[:MAX_TEST_OUTPUT] +
                                       f"\n(killed: still running after its limit of {limits.get(killed_for, 30.0):.0f} s)\n",
                                       "pictures": []}
                pending.remove(killed_for)
                for n, lim in (after_hang or {}).items():
                    limits[n] = min(limits.get(n, lim), lim)
                continue
            if killed_for == "start":
                for n in pending:
                    results[n] = {"status": "timeout", "output": f"(the test program {os.path.basename(binary)} hung before this test started; killed after {start_limit:.0f} s)\n", "seconds": 0, "pictures": []}
                break
            if cur:  # the program ended inside a test: a crash
                rc = p.returncode
                why = f"killed by signal {-rc}" if rc < 0 else f"exited {rc}"
                results[cur] = {"status": "crashed", "seconds": time.time() - started,
                                "output": "".join(buf)[:MAX_TEST_OUTPUT] + f"\n(the test program {why} during this test)\n",
                                "pictures": []}
                pending.remove(cur)
                continue
            for n in pending:  # ended without running them
                results[n] = {"status": "not-run", "output": f"(the test program {os.path.basename(binary)} exited {p.returncode} without running this test)\n", "seconds": 0, "pictures": []}
            break
    return results


def pictures_under(outdir):
    found = set()
    for base, dirs, files in os.walk(outdir):
        for f in files:
            if f.endswith("_diff.png"):
                found.add(os.path.relpath(os.path.join(base, f), outdir))
    return found


# ---------------------------------------------------------------- variants
class Grader:
    def __init__(self, lab, cache_dir, jobs, scratch):
        self.lab, self.jobs, self.scratch = lab, jobs, scratch
        self.trust_regions = False
        self.exercises = exercises_of(lab)
        if not self.exercises:
            die(f"{lab} has no exercises")
        self.pdir = pristine(lab, cache_dir, jobs)
        self.copy = os.path.join(self.pdir, "copy")
        self.work = os.path.join(self.pdir, "work")
        self.judge_work = os.path.join(self.pdir, "judge", "work")
        # the folders whose text the judge's hints read (the lab's own, as the variant has them)
        self.source_dirs = [d for d in (lab, os.path.join("shaders", lab)) if os.path.isdir(os.path.join(self.work, d))]
        self.solved = {}  # file → lines of the solved (instructors') file
        for e in self.exercises:
            if e["file"] not in self.solved:
                with open(os.path.join(self.work, e["file"])) as f:
                    self.solved[e["file"]] = split_lines(f.read())
            reg = find_region(self.solved[e["file"]], e["name"])
            if not reg:
                die(f"{e['file']}: exercise {e['name']} has no END EXERCISE", 1)
            body = self.solved[e["file"]][reg[0] + 1:reg[1]]
            e["stub_lines"] = [l for l in body if re.match(r"^[ \t]*// STUB:", l)]
            e["solution"] = [l for l in body if not re.match(r"^[ \t]*// STUB:", l)]
            e["stub"] = [re.sub(r"// STUB: ?", "", l, count=1) for l in e["stub_lines"]]
        self.counter = 0
        self.lock = threading.Lock()
        self.variants = {}
        self.make_dirs = {}
        # the tests: discovered and timed on the pristine build
        job = self.new_job()
        with open(os.path.join(self.pdir, "tests.json")) as f:
            self.tests = {b: [tuple(t) for t in ts] for b, ts in json.load(f).items()}  # binary → [(name, env)]
        self.binary_of = {n: b for b, ts in self.tests.items() for n, _ in ts}
        # An exercise's grade: the tests of its "Checked by" list (the tests written to check it),
        # not every test that tests/graded_exercises.txt says can blame it (a textured picture needs
        # texture_terms: running all of those for every exercise would multiply a submission's time).
        names = sorted(self.binary_of)
        for e in self.exercises:
            sel = {n for n in names if any(fnmatch.fnmatchcase(n, p) for p in e["checked"])}
            if not sel:
                die(f"exercise {e['name']}: no test of the copy matches its Checked by ({' '.join(e['checked'])})", 1)
            e["tests"] = sorted(sel)
        self.all_tests = sorted({t for e in self.exercises for t in e["tests"]})
        log(f"grade: {lab}: {len(self.exercises)} exercises, {len(self.all_tests)} graded tests; timing the solution")
        t0 = time.time()
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

    def run_judged(self, job, tests, limits, judge_limits, start_limit=30.0, after_hang=None):
        """(results, the probe's own results) of tests on job's build: the probe records in job's
        sandbox, the judge decides in a sandbox of its own on the judge's build (module docstring)."""
        records = os.path.join(job, "out", "probe")
        os.makedirs(records, exist_ok=True)
        chown_tree(job)
        probe = run_tests(job, self.subset(tests), limits, start_limit=start_limit, shared=self.work,
                          env_extra={"LAB_PROBE": "record", "LAB_PROBE_DIR": OUT + "/probe"}, after_hang=after_hang)
        # A test the probe ran to its end (as far as its output tells: the student's code may print
        # anything) goes to the judge; a crash or a hang is the probe's own ending, and fails.
        ended = [n for n in tests if probe[n]["status"] in ("ok", "failed")]
        results = {n: dict(probe[n], pictures=[]) for n in tests if n not in ended}
        if ended:
            judge = job.rstrip("/") + "-judge"
            os.makedirs(os.path.join(judge, "out"))
            chown_tree(judge)
            binds = [(records, PROBE)] + [(os.path.join(job, "work", d), f"{WORK}/{d}") for d in self.source_dirs]
            judged = run_tests(judge, self.subset(ended), judge_limits, start_limit=start_limit, work=self.judge_work, binds=binds,
                               env_extra={"LAB_PROBE": "replay", "LAB_PROBE_DIR": PROBE})
            for n, r in judged.items():
                r["pictures_dir"] = os.path.join(judge, "out")
                if r["status"] in ("timeout", "crashed", "not-run"):
                    r["output"] = "(the judge, which runs no student code, did not finish this test on the probe's values)\n" + r["output"]
            results.update(judged)
        return results, probe

    def subset(self, names):
        out = collections.defaultdict(list)
        for b, ts in self.tests.items():
            for n, env in ts:
                if n in names:
                    out[b].append((n, env))
        return out

    def new_job(self):
        with self.lock:
            self.counter += 1
            job = os.path.join(self.scratch, f"job{self.counter}")
        os.makedirs(os.path.join(job, "out"))
        # the pristine copy but its build/common, which the sandbox sees read-only from the cache
        dst = os.path.join(job, "work")
        os.makedirs(os.path.join(dst, "build", "common"))
        tops = [os.path.join(self.work, x) for x in os.listdir(self.work) if x != "build"]
        builds = [os.path.join(self.work, "build", x) for x in os.listdir(os.path.join(self.work, "build")) if x != "common"]
        subprocess.run(["cp", "-a", *tops, dst], check=True)
        subprocess.run(["cp", "-a", *builds, os.path.join(dst, "build")], check=True)
        shutil.copystat(self.work, dst)
        shutil.copystat(os.path.join(self.work, "build"), os.path.join(dst, "build"))
        chown_tree(job)
        return job

    def make_dirs_of(self, rel):
        """The build.make folders of the targets that compile source rel (not the prover's _graded)."""
        with self.lock:
            if rel in self.make_dirs:
                return self.make_dirs[rel]
        found = []
        build = os.path.join(self.work, "build")
        for base, dirs, files in os.walk(build):
            if base.endswith(".dir") and "build.make" in files and not base.endswith("_graded.dir") and \
                    not os.path.relpath(base, build).startswith("common"):
                if f"{WORK}/{rel}" in open(os.path.join(base, "build.make"), errors="replace").read():
                    found.append(os.path.relpath(base, build))
        with self.lock:
            self.make_dirs[rel] = sorted(found)
        return sorted(found)

    def variant(self, changes, tests):
        """Results of the pristine copy with changes {file: text} applied, for tests: cached by content."""
        if not changes:
            return {"build": "ok", "tests": {n: self.baseline[n] for n in tests}}
        key = hashlib.sha256(json.dumps([sorted(changes.items()), sorted(tests)]).encode()).hexdigest()
        with self.lock:
            fut = self.variants.get(key)
            owner = fut is None
            if owner:
                fut = self.variants[key] = cf.Future()
        if not owner:
            return fut.result()
        try:
            res = self._run_variant(changes, tests)
        except Exception as ex:  # the grader's own failure: reported, the class goes on
            res = {"build": "error", "log": f"grader error: {ex}", "tests": {}}
        fut.set_result(res)
        # Kept for the next submission with the same code only when the environment had no say in
        # it: not a grader error, a build or test that ran out of time, or a crash (a loaded
        # machine, a neighbour's fork bomb, memory), which the next run may not repeat.
        if res["build"] in ("error", "timeout") or \
                any(r["status"] in ("timeout", "crashed", "not-run") for r in res["tests"].values()):
            with self.lock:
                self.variants.pop(key, None)
        return res

    def _run_variant(self, changes, tests):
        t0 = time.time()
        job = self.new_job()
        t_copy = time.time() - t0
        work = os.path.join(job, "work")
        for f, text in changes.items():
            path = os.path.join(work, f)
            with open(path, "w") as fh:
                fh.write(text)
            now = time.time() + 1  # newer than every object of the copy
            os.utime(path, (now, now))
        chown_tree(job)
        # only the targets that compile a changed file, each by its own build.make (the rest of the
        # pristine build is up to date): make compiles the changed file and links
        dirs = sorted({d for f in changes for d in self.make_dirs_of(f)})
        t1 = time.time()
        if dirs and all(self.make_dirs_of(f) for f in changes):
            script = " && ".join(f"make -s -f {d}/build.make {d}/build" for d in dirs)
            code, out = run_limited(sandbox(job, "build", cpu=600, shared=self.work) + ["sh", "-c", "cd build && " + script], 600)
        else:
            targets = sorted({os.path.basename(self.binary_of[n]) for n in tests} | {self.lab})
            code, out = run_limited(sandbox(job, "build", cpu=600, shared=self.work) + ["cmake", "--build", "build", "-j1", "--target", *targets], 600)
        t_build = time.time() - t1
        if code != 0:
            shutil.rmtree(job, ignore_errors=True)
            # "does not compile" only on the compiler's word; a build that stopped without one
            # (killed for memory, a full disk) is the environment's failure
            compiled = code is not None and re.search(r"\berror\b", out)
            return {"build": "timeout" if code is None else "failed" if compiled else "error",
                    "log": out if compiled or code is None else "grader error: the build stopped without a compiler error:\n" + out[-2000:],
                    "tests": {}}
        t2 = time.time()
        res, _ = self.run_judged(job, tests, self.limits, self.judge_limits, after_hang=self.after_hang)
        if os.environ.get("GRADE_PROFILE"):
            log(f"    profile {sorted(changes)} {len(tests)} tests: copy {t_copy:.1f} s, build {t_build:.1f} s, tests {time.time() - t2:.1f} s")
        # the failing tests' pictures, kept (plain PNG files only) before the job's copy goes
        pics = os.path.join(self.scratch, "pictures", os.path.basename(job))
        for t, r in res.items():
            kept = []
            for i, pic in enumerate(r.get("pictures", []) if r["status"] != "ok" else []):
                os.makedirs(pics, exist_ok=True)
                dst = os.path.join(pics, f"{len(os.listdir(pics))}.png")
                if copy_png(os.path.join(r.get("pictures_dir", os.path.join(job, "out")), pic), dst):
                    kept.append((pic, dst))
            r["pictures"] = kept
            r.pop("pictures_dir", None)
        shutil.rmtree(job, ignore_errors=True)
        shutil.rmtree(job + "-judge", ignore_errors=True)
        return {"build": "ok", "tests": res}


# ---------------------------------------------------------------- a submission
def open_submission(entry, scratch):
    """(root folder of the student's copy, None) or (None, reason)."""
    name = os.path.basename(entry)
    if os.path.islink(entry):
        return None, "the entry is a link (not followed)"
    if os.path.isdir(entry):
        root = entry
    elif os.path.isfile(entry) and name.lower().endswith(EXT_ARCHIVE):
        root = os.path.join(scratch, "unpacked")
        os.makedirs(root)
        try:
            extract(entry, root)
        except Exception as ex:
            return None, f"could not unpack the archive ({str(ex)[:120]})"
    else:
        return None, "not a folder or a .tar.gz/.tgz/.zip archive"
    try:
        top = [x for x in os.listdir(root) if not x.startswith(".") and x != "__MACOSX"]
    except OSError as ex:
        return None, f"unreadable ({ex.strerror})"
    if not top and not os.listdir(root):
        return None, "empty"
    if len(top) == 1 and os.path.isdir(os.path.join(root, top[0])) and not os.path.islink(os.path.join(root, top[0])) \
            and not re.match(r"^lab\d+_", top[0]):
        root = os.path.join(root, top[0])
    return root, None


def extract(archive, dest):
    total, count = 0, 0
    if archive.lower().endswith(".zip"):
        with zipfile.ZipFile(archive) as z:
            for info in z.infolist():
                count += 1
                total += info.file_size
                if count > MAX_EXTRACT_FILES or total > MAX_EXTRACT_BYTES:
                    raise ValueError("more than 512 MiB or 20000 files")
                target = os.path.realpath(os.path.join(dest, info.filename))
                if not target.startswith(os.path.realpath(dest) + os.sep) or (info.external_attr >> 16) & 0o170000 == 0o120000:
                    continue  # a path outside, or a link: skipped
                if info.is_dir():
                    os.makedirs(target, exist_ok=True)
                    continue
                os.makedirs(os.path.dirname(target), exist_ok=True)
                with z.open(info) as src, open(target, "wb") as dst:
                    shutil.copyfileobj(src, dst)
    else:
        with tarfile.open(archive, "r:gz") as t:
            members = []
            for m in t:
                count += 1
                total += max(m.size, 0)
                if count > MAX_EXTRACT_FILES or total > MAX_EXTRACT_BYTES:
                    raise ValueError("more than 512 MiB or 20000 files")
                if m.isfile() or m.isdir():
                    members.append(m)
            t.extractall(dest, members=members, filter="data")


def read_student_file(root, rel):
    """Text of root/rel if it is a regular file inside root (no link anywhere on the way), else None."""
    path = root
    for part in rel.split("/"):
        path = os.path.join(path, part)
        if os.path.islink(path):
            return None
    try:
        st = os.stat(path)
        if not stat.S_ISREG(st.st_mode) or st.st_size > (4 << 20):
            return None
        with open(path, "rb") as f:
            return f.read().decode("utf-8", "replace")
    except OSError:
        return None


def masked(text):
    """A file's text without its exercise regions' code (and TODO/EXERCISE spelled one way)."""
    out, inside = [], False
    for line in split_lines(text):
        if re.search(r"// (TODO )?EXERCISE [a-z0-9_]+: ", line):
            out.append(line.replace("// TODO EXERCISE ", "// EXERCISE "))
            inside = True
        elif inside and END_RE.match(line):
            out.append(line)
            inside = False
        elif not inside:
            out.append(line)
    return "".join(out)


def tree_files(root):
    files = {}
    for base, dirs, names in os.walk(root):
        rel = os.path.relpath(base, root)
        if rel == ".":
            dirs[:] = [d for d in dirs if not IGNORED_TOP.match(d)]
            rel = ""
        dirs[:] = sorted(d for d in dirs if d != "__pycache__")
        for n in names:
            files[(rel + "/" if rel else "") + n] = os.path.join(base, n)
        for d in list(dirs):
            if os.path.islink(os.path.join(base, d)):
                files[(rel + "/" if rel else "") + d] = os.path.join(base, d)
                dirs.remove(d)
    return files


def changed_outside(copy, root):
    ours, theirs = tree_files(copy), tree_files(root)
    changed = []
    for rel in sorted(set(ours) | set(theirs)):
        if rel not in theirs:
            changed.append(rel + " (deleted)")
        elif rel not in ours:
            changed.append(rel + " (added)")
        elif os.path.islink(theirs[rel]):
            changed.append(rel + " (a link)")
        else:
            a, b = read_student_file(copy, rel), read_student_file(root, rel)
            if b is None or masked(a or "") != masked(b):
                changed.append(rel)
    return changed


class Submission:
    def __init__(self, name):
        self.name = name
        self.notes = []
        self.grades = {}
        self.messages = {}
        self.isolated = {}   # exercise → variant result
        self.whole = None
        self.outside = []
        self.region = {}     # exercise → "ok" | "missing" | "stub" | "solution"
        self.fatal = None
        self.kept = {}       # (exercise, test) → pictures next to the report
        self.code = {}       # exercise → the student's region, as handed in
        self.flagged = {}    # exercise → why its region is not graded (region_check.py)
        self.line = {}       # exercise → the line of its marker in the student's own file


def grade_submission(g, entry, name, outdir, progress):
    s = Submission(name)
    scratch = tempfile.mkdtemp(prefix="sub-", dir=g.scratch)
    try:
        root, why = open_submission(entry, scratch)
        if why:
            s.fatal = why
            s.notes.append(why)
            for e in g.exercises:
                s.grades[e["name"]] = 0
                s.messages[e["name"]] = f"`{e['name']}` not graded: the submission is {why}"
            return s
        if not os.path.isdir(os.path.join(root, g.lab)):
            s.notes.append(f"no {g.lab}/ folder in the submission")
        bodies, changes_all = {}, {}
        for e in g.exercises:
            text = read_student_file(root, e["file"])
            reg = find_region(split_lines(text), e["name"]) if text is not None else None
            if reg is None:
                s.region[e["name"]] = "missing"
                continue
            lines = split_lines(text)
            body = lines[reg[0] + 1:reg[1]]
            if sum(map(len, body)) > MAX_REGION_BYTES:
                s.region[e["name"]] = "missing"
                s.notes.append(f"{e['name']}: region over 256 KiB, ignored")
                continue
            if body and not body[-1].endswith("\n"):
                body[-1] += "\n"
            bodies[e["name"]] = body
            s.line[e["name"]] = reg[0] + 1
            s.code[e["name"]] = "".join(body)
            strip = lambda ls: [l.rstrip() for l in ls if l.strip()]
            s.region[e["name"]] = ("solution" if strip(body) == strip(e["solution"]) else
                                   "stub" if strip(body) == strip(e["stub"]) or strip(body) == strip(e["stub_lines"]) else "code")
            why_not = None if g.trust_regions else region_check.problems("".join(body))
            if why_not:
                s.flagged[e["name"]] = why_not
        s.outside = changed_outside(g.copy, root)

        def apply(names):
            """The solved files with the student's regions of names in them: {file: text}, only changed files."""
            files = {}
            for e in g.exercises:
                if e["name"] not in names or s.region[e["name"]] == "solution":
                    continue
                lines = files.setdefault(e["file"], list(g.solved[e["file"]]))
                reg = find_region(lines, e["name"])
                body = bodies.get(e["name"], e["stub"])  # markers gone: the stub (not done)
                lines[reg[0] + 1:reg[1]] = e["stub_lines"] + body
            return {f: "".join(ls) for f, ls in files.items()}

        t0 = time.time()
        # The variants, longest first (the solution's time for their tests), so that the last one
        # to start is a short one and both cores stay busy to the end.
        runs = [(e["name"], apply({e["name"]}), e["tests"]) for e in g.exercises if s.region[e["name"]] != "missing"]
        runs.append((None, apply({e["name"] for e in g.exercises}), g.all_tests))
        runs.sort(key=lambda r: -sum(g.baseline[t]["seconds"] for t in r[2]))
        with cf.ThreadPoolExecutor(max_workers=g.jobs) as pool:
            futs = {pool.submit(g.variant, changes, tests): ex for ex, changes, tests in runs}
            for f in cf.as_completed(futs):
                ex = futs[f]
                if ex is None:
                    s.whole = f.result()
                else:
                    s.isolated[ex] = f.result()
                    r = s.isolated[ex]
                    ok = r["build"] == "ok" and all(r["tests"].get(t, {}).get("status") == "ok" for t in next(e for e in g.exercises if e["name"] == ex)["tests"])
                    progress(f"{name}: {ex} {'passes' if ok else 'fails'} ({time.time() - t0:.0f} s)")
        compile_bad, stopped, grader_bad = [], [], []  # stopped: the exercises with a test that crashed or hung
        for e in g.exercises:
            n = e["name"]
            if s.region[n] == "missing":
                s.grades[n] = 0
                s.messages[n] = (f"`{n}` is not done: its markers (// TODO EXERCISE {n}: … // END EXERCISE) are not in "
                                 f"{e['file']} any more, so there is no code to grade. Put the markers back around your code.")
                continue
            r = s.isolated[n]
            if n in s.flagged:
                s.grades[n] = 0
                passing = sum(r["tests"].get(t, {}).get("status") == "ok" for t in e["tests"])
                s.messages[n] = (f"`{n}` is not graded: its region ({e['file']}) steps outside the exercise: "
                                 f"{'; '.join(s.flagged[n])}. A region holds the exercise's own statements and nothing "
                                 f"else (docs/solutions.md, \"What a region may hold\"). For the instructor: "
                                 + (f"{passing} of its {len(e['tests'])} tests pass." if r["build"] == "ok" else "it does not build."))
                continue
            if r["build"] == "error":
                s.grades[n] = 0
                grader_bad.append(n)
                s.messages[n] = f"`{n}` ({e['file']}) was not graded: the grader's build failed, not the compiler:\n" + r.get("log", "")[-800:]
                continue
            if r["build"] != "ok":
                s.grades[n] = 0
                compile_bad.append(n)
                s.messages[n] = (f"`{n}` ({e['file']}) does not compile with the solution of every other exercise"
                                 f"{' (the build ran out of time)' if r['build'] == 'timeout' else ''}:\n" + compiler_errors(r.get("log", "")))
                continue
            failing = [t for t in e["tests"] if r["tests"].get(t, {}).get("status") != "ok"]
            s.grades[n] = 0 if failing else 1
            for t in failing:
                st = r["tests"].get(t, {}).get("status", "not-run")
                if st in ("timeout", "crashed") and n not in stopped:
                    stopped.append(n)
            if failing:
                s.messages[n] = f"`{n}` fails {len(failing)} of its {len(e['tests'])} tests (run with the solution of every other exercise):\n\n" + \
                    "\n".join(f"{t}: {r['tests'].get(t, {}).get('status', 'not-run')}\n{test_message(r['tests'].get(t, {}).get('output', ''))}" for t in failing)
                if s.region[n] == "stub":
                    s.messages[n] = f"`{n}` is still the stub.\n" + s.messages[n]
            else:
                s.messages[n] = f"`{n}`: all {len(e['tests'])} tests that check it pass ({', '.join(e['tests'][:6])}{' …' if len(e['tests']) > 6 else ''})."
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
        # pictures of failing render tests (kept by the variant), copied next to the report
        for n, r in s.isolated.items():
            for t, tr in r.get("tests", {}).items():
                keep = []
                for pic, src in tr.get("pictures", []) if tr.get("status") != "ok" else []:
                    dst = os.path.join("pictures", f"{n}--{pic.replace('/', '--')}")
                    os.makedirs(os.path.join(outdir, "pictures"), exist_ok=True)
                    shutil.copyfile(src, os.path.join(outdir, dst))
                    keep.append(dst)
                s.kept[(n, t)] = keep
        return s
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def copy_png(src, dst):
    try:
        fd = os.open(src, os.O_RDONLY | os.O_NOFOLLOW)
    except OSError:
        return False
    with os.fdopen(fd, "rb") as f:
        if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
            return False
        data = f.read(32 << 20)
    if not data.startswith(b"\x89PNG\r\n\x1a\n"):
        return False
    with open(dst, "wb") as f:
        f.write(data)
    return True


def compiler_errors(text):
    lines = [l.replace(WORK + "/", "") for l in text.splitlines()]
    errs = [l for l in lines if re.search(r"error|ERROR", l) and "make" not in l.split(":")[0]]
    return "\n".join((errs or lines[-15:])[:15])


def test_message(output):
    """The grader's message in a test's output: the [ exercise ] lines and the failures."""
    keep = []
    lines = output.splitlines()
    for i, l in enumerate(lines):
        if l.startswith("[ exercise ]") or (keep and keep[-1].startswith("[ exercise ]") and l.startswith(" ")) or \
                "Failure" in l or l.startswith("(") or "(probe)" in l or re.match(r"^(Expected|Value of|  Actual|Which is|    Which)", l):
            keep.append(l.replace(WORK + "/", "").replace(OUT + "/", "test_output/"))
    text = "\n".join(keep[:40]) or "\n".join(lines[-20:])
    return text + "\n"


# ---------------------------------------------------------------- outputs
def write_outputs(g, subs, out):
    names = [e["name"] for e in g.exercises]
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["student", *names, "score", "notes"])
    for s in subs:
        w.writerow([s.name, *[s.grades.get(n, 0) for n in names], sum(s.grades.get(n, 0) for n in names), "; ".join(s.notes)])
    with open(os.path.join(out, "grades.csv"), "w") as f:
        f.write(buf.getvalue())
    for s in subs:
        d = os.path.join(out, STUDENTS, s.name)
        os.makedirs(d, exist_ok=True)
        whole_ok = sorted(t for t, r in (s.whole or {}).get("tests", {}).items() if r["status"] == "ok")
        res = {"score": sum(s.grades.get(n, 0) for n in names),
               "max_score": len(names),
               "output": (f"{len(whole_ok)} of {len(g.all_tests)} graded tests pass with the code as handed in. " if s.whole else "") +
                         ("; ".join(s.notes)),
               "tests": [{"name": n, "score": s.grades.get(n, 0), "max_score": 1, "output": s.messages.get(n, "")} for n in names]}
        with open(os.path.join(d, "results.json"), "w") as f:
            json.dump(res, f, indent=2)
            f.write("\n")
        with open(os.path.join(d, "report.html"), "w") as f:
            f.write(report_html(g, s))
    with open(os.path.join(out, "index.html"), "w") as f:
        f.write(index_html(g, subs))


CSS = """body{font:14px/1.45 system-ui,sans-serif;margin:24px;color:#1d232b;max-width:1200px}
h1{font-size:22px}h2{font-size:17px;margin-top:28px}table{border-collapse:collapse;margin:8px 0}
td,th{border:1px solid #ccd3db;padding:4px 8px;text-align:left;vertical-align:top}th{background:#eef2f6}
.p{background:#d9f2df}.f{background:#f8d7d7}.m{color:#5a6573}pre{background:#f5f7f9;border:1px solid #dde3e9;padding:8px;
white-space:pre-wrap;font-size:12px;max-height:420px;overflow:auto}img{max-width:100%;border:1px solid #ccd3db;margin:4px 0}
.ex{border:1px solid #ccd3db;border-radius:6px;padding:4px 14px;margin:14px 0}.badge{font-weight:600;padding:1px 8px;border-radius:4px}
a{color:#0b5cad}"""


def page(title, body):
    return (f"<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{html.escape(title)}</title>"
            f"<style>{CSS}</style></head><body>\n{body}\n</body></html>\n")


def report_html(g, s):
    e_ = html.escape
    names = [e["name"] for e in g.exercises]
    score = sum(s.grades.get(n, 0) for n in names)
    b = [f"<h1>{e_(g.lab)}: {e_(s.name)} — {score} / {len(names)}</h1>", "<p><a href=\"../../index.html\">← class summary</a></p>"]
    if s.notes:
        b.append("<p><b>Notes:</b> " + e_("; ".join(s.notes)) + "</p>")
    whole = (s.whole or {}).get("tests", {})
    for e in g.exercises:
        n = e["name"]
        ok = s.grades.get(n, 0)
        b.append(f"<div class=\"ex\"><h2><span class=\"badge {'p' if ok else 'f'}\">{ok}</span> {e_(n)} "
                 f"<span class=\"m\">{e_(e['file'])}{':' + str(s.line[n]) if n in s.line else ''}</span></h2>")
        b.append(f"<pre>{e_(s.messages.get(n, ''))}</pre>")
        if n in s.code:
            b.append(f"<details><summary>the student's code for {e_(n)}</summary><pre>{e_(s.code[n])}</pre></details>")
        r = s.isolated.get(n)
        if r and r.get("tests"):
            b.append("<table><tr><th>test</th><th>this exercise alone</th><th>as handed in</th></tr>")
            for t in e["tests"]:
                st = r["tests"].get(t, {}).get("status", "—")
                wst = whole.get(t, {}).get("status", "—" if not s.whole or s.whole["build"] == "ok" else "did not compile")
                b.append(f"<tr><td>{e_(t)}</td><td class=\"{'p' if st == 'ok' else 'f'}\">{e_(st)}</td>"
                         f"<td class=\"{'p' if wst == 'ok' else 'f'}\">{e_(wst)}</td></tr>")
            b.append("</table>")
            for t in e["tests"]:
                for pic in s.kept.get((n, t), []):
                    b.append(f"<p>{e_(t)} — expected | actual | difference:<br><img src=\"{e_(pic)}\" alt=\"{e_(t)}\"></p>")
        b.append("</div>")
    if s.outside:
        b.append("<h2>Changed outside the exercises (ignored by the grade)</h2><ul>" +
                 "".join(f"<li>{e_(p)}</li>" for p in s.outside[:200]) + "</ul>")
    return page(f"{s.name}: {g.lab}", "\n".join(b))


def first_message(msg):
    """The line of a message that says most (the hint's blame first), numbers as # to group alike ones."""
    lines = msg.splitlines()
    for want in ("[ exercise ]", "does not compile", "not done", "not graded", "Failure"):
        for l in lines:
            if want in l:
                return re.sub(r"(?<![A-Za-z_])\d+(\.\d+)?", "#", l.strip())[:160]
    return lines[0][:160] if lines else ""


def index_html(g, subs):
    e_ = html.escape
    names = [e["name"] for e in g.exercises]
    b = [f"<h1>{e_(g.lab)}: class summary, {len(subs)} submissions</h1>"]
    b.append("<h2>Per exercise</h2><table><tr><th>exercise</th><th>passed</th><th>most common failing tests</th><th>most common messages</th></tr>")
    for e in g.exercises:
        n = e["name"]
        passed = sum(s.grades.get(n, 0) for s in subs)
        tests, msgs = collections.Counter(), collections.Counter()
        for s in subs:
            if s.grades.get(n, 0) or s.fatal:
                continue
            for t, r in (s.isolated.get(n) or {}).get("tests", {}).items():
                if r["status"] != "ok":
                    tests[t] += 1
            msgs[first_message(s.messages.get(n, ""))] += 1
        top = lambda c: "<br>".join(f"{k} <span class=\"m\">×{v}</span>" for k, v in sorted(c.items(), key=lambda kv: (-kv[1], kv[0]))[:3])
        b.append(f"<tr><td>{e_(n)}</td><td>{passed} / {len(subs)}</td><td>{top(collections.Counter({e_(k): v for k, v in tests.items()}))}</td>"
                 f"<td>{top(collections.Counter({e_(k): v for k, v in msgs.items() if k}))}</td></tr>")
    b.append("</table><h2>Students</h2><table><tr><th>student</th>" + "".join(f"<th>{e_(n)}</th>" for n in names) +
             "<th>score</th><th>notes</th></tr>")
    for s in subs:
        cells = "".join(f"<td class=\"{'p' if s.grades.get(n, 0) else 'f'}\">{s.grades.get(n, 0)}</td>" for n in names)
        b.append(f"<tr><td><a href=\"{STUDENTS}/{e_(s.name)}/report.html\">{e_(s.name)}</a></td>{cells}"
                 f"<td>{sum(s.grades.get(n, 0) for n in names)}</td><td>{e_('; '.join(s.notes))}</td></tr>")
    b.append("</table>")
    return page(f"{g.lab} grades", "\n".join(b))


# ---------------------------------------------------------------- main
def student_name(entry):
    n = os.path.basename(entry.rstrip("/"))
    for ext in EXT_ARCHIVE:
        if n.lower().endswith(ext):
            return n[: -len(ext)]
    return n


def main():
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
    a = ap.parse_args()
    lab = resolve_lab(a.lab)
    if not os.path.isdir(a.submissions):
        die(f"{a.submissions}: not a folder of submissions")
    out = os.path.abspath(a.out or os.path.join(ROOT, "build", f"grades-{lab.split('_')[0]}"))
    sub_real = os.path.realpath(a.submissions)
    if out == sub_real or out.startswith(sub_real + os.sep):
        die(f"--out {out} is inside the submissions folder")
    entries = sorted(os.listdir(a.submissions))
    by_name = {}
    for x in entries:
        if x.startswith("."):
            continue
        n = student_name(x)
        if n in by_name:
            die(f"{a.submissions}: two entries for student {n} ({by_name[n]}, {x})")
        by_name[n] = x
    if not by_name:
        die(f"{a.submissions}: no submissions in it")
    for n in by_name:
        if not re.match(r"^[A-Za-z0-9][A-Za-z0-9._ @+-]*$", n):
            die(f"{a.submissions}/{by_name[n]}: a student name must be letters, digits and . _ - @ + (got {n!r})")
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


if __name__ == "__main__":
    main()
