"""sandbox.py — where the student's code runs: bubblewrap with limits, the isolation check, and
running and killing a process group with a wall-time limit.

bubblewrap, run as an unprivileged user (a user of the job's own when the grader is root):
  - new user, PID, network, IPC, UTS and cgroup namespaces (--unshare-all): no network at all
    (only a loopback device), no other process visible, every process of the sandbox killed when
    its first process ends or the grader kills it (--die-with-parent, the PID namespace);
  - a file system of /usr and /etc read-only, a private /proc, a minimal /dev, an empty private
    /tmp (tmpfs), and the job's copy at /grade/work: read-only, but for its build/ folder while it
    builds and /grade/out (the tests' pictures) while its tests run. The instructors'
    repository, the submissions, the cache and the output folder are not in it;
  - limits (prlimit, per process): CPU seconds, address space, file size, open files, no core
    files; wall time: the grader kills it; /tmp at most SANDBOX_TMP;
  - the number of processes and threads, per job, with or without root: prlimit --nproc runs
    inside the sandbox's own user namespace, and Linux (5.14 on) counts a user's processes per
    user namespace, so a fork bomb meets its own job's limit, never a neighbour's (check_isolation).
"""
import os
import re
import signal
import subprocess
import threading
import time

from model import die

WORK = "/grade/work"   # where a copy is seen inside the sandbox (its build has this path baked in)
OUT = "/grade/out"     # the tests' output folder inside the sandbox (LAB_TEST_OUTPUT)
PROBE = "/grade/probe" # the judge's read-only view of the probe's records (tests/probe.h)
MANIFEST = "/grade/exercises.json"  # the judge's view of the variant's exercises' manifest (its hints')
CCACHE = "/grade/ccache" # the pristine builds' compiler cache (compiler_cache=)
# As root, each job's sandbox runs as a user of its own, SANDBOX_UID + the job's number (no account
# needs to exist for it): RLIMIT_NPROC counts the processes and threads of a user, so a fork bomb in
# one job exhausts its own user's count, never that of a job running beside it; and no job can
# write another job's files.
SANDBOX_UID = 200000
MAX_PROCESS_OUTPUT = 64 << 20  # what the grader reads of one process's output before killing it
KEPT_OUTPUT = 4 << 20          # what run_limited keeps of it (the start, and with keep_tail the end too)
SANDBOX_TMP = 256 << 20        # the sandbox's /tmp (memory)
SANDBOX_NPROC = 512            # processes and threads of one job


def job_uid(job):
    """The user job's sandbox runs as (when the grader is root): SANDBOX_UID + N for scratch/jobN."""
    m = re.fullmatch(r"job(\d+)", os.path.basename(os.path.normpath(job)))
    return SANDBOX_UID + (int(m.group(1)) if m else 0)


def sandbox(job, mode, env=None, cpu=600, shared=None, work=None, binds=(), compiler_cache=None):
    """The command prefix that runs a command in job's copy. mode: build | test | setup. shared:
    the pristine copy whose build/common (never rebuilt by a submission) is seen read-only. work:
    another tree to see read-only at WORK (the judge's); binds: (path, place) pairs seen read-only.
    compiler_cache: a folder seen writable at CCACHE as ccache's (the pristine copy's two builds,
    instructors' code only); without it ccache, where a build names it, only runs the compiler."""
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
    if compiler_cache:
        cmd += ["--bind", compiler_cache, CCACHE]
        base["CCACHE_DIR"] = CCACHE
    else:
        base["CCACHE_DISABLE"] = "1"  # ccache's switch: set at all, it runs the compiler alone
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


_live, _live_lock = set(), threading.Lock()  # the process groups started and not yet ended


def started(p):
    with _live_lock:
        _live.add(p)
    return p


def ended(p):
    with _live_lock:
        _live.discard(p)


def kill_on_signals():
    """On SIGTERM, SIGINT or SIGHUP (a CTest timeout, ^C), every process group still running is
    killed before the grader exits: each runs in a session of its own, out of reach of a signal to
    the grader's."""
    def handler(signum, frame):
        with _live_lock:
            for p in list(_live):
                kill_group(p)
        os._exit(128 + signum)
    for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(sig, handler)


class Limited(tuple):
    """The ending of a run_limited process, a pair (exit code, None if killed at the wall limit;
    output) with code, output, and the wall and CPU seconds it took (the CPU of it and of the
    children it waited for) as attributes."""
    def __new__(cls, code, output, seconds, cpu):
        self = super().__new__(cls, (code, output))
        self.code, self.output, self.seconds, self.cpu = code, output, seconds, cpu
        return self


def run_limited(cmd, wall, env=None, cwd=None, keep_tail=False):
    """Runs cmd in a process group of its own with a wall-time limit, killing the whole group at the
    limit, when it ends, or once it has written MAX_PROCESS_OUTPUT. Unpacks as (exit code, or None
    if killed at the limit; output: its first KEPT_OUTPUT, with keep_tail its last too); see Limited."""
    start = time.monotonic()
    p = started(subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True,
                                 env=env, cwd=cwd))
    chunks, tail, size, fired = [], [], 0, []
    timer = threading.Timer(wall, lambda: (fired.append(1), kill_group(p)))
    timer.start()
    usage = None
    try:
        for chunk in iter(lambda: p.stdout.read(65536), b""):
            if size < KEPT_OUTPUT:
                chunks.append(chunk)
            elif keep_tail:
                tail.append(chunk)
                while len(tail) > 1 and sum(map(len, tail)) - len(tail[0]) >= KEPT_OUTPUT // 4:
                    tail.pop(0)
            size += len(chunk)
            if size > MAX_PROCESS_OUTPUT:
                kill_group(p)
                break
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
    finally:
        timer.cancel()
        kill_group(p)
        if p.returncode is None:
            p.wait()
        ended(p)
    out = b"".join(chunks)
    if tail:
        out += b"\n(... output cut ...)\n" + b"".join(tail)
    cpu = usage.ru_utime + usage.ru_stime if usage else 0.0
    return Limited(None if fired else p.returncode, out.decode("utf-8", "replace"), time.monotonic() - start, cpu)


def chown_tree(path):
    """path (a job's folder) made its sandbox user's."""
    if os.geteuid() != 0:
        return
    uid = job_uid(path)
    subprocess.run(["chown", "-R", "-h", f"{uid}:{uid}", path], check=True)

