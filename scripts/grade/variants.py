"""variants.py — the builds a grade runs tests on.

  * pristine(): the student copy of a lab with its folders replaced by the solved ones, configured
    and built once in the sandbox at WORK, and the judge (the handed-out copy built with the same
    test programs); cached per lab and repository state, the newest CACHE_KEEP kept.
  * VariantCache: identical variants (the same changed files for the same tests) built and run
    once; a result the environment had a say in (a grader error, a timeout, a crash) is not kept.
  * SandboxVariants: a variant of the pristine build: its copy with the changed files written, only
    the targets that compile them rebuilt (each by its build.make: one translation unit or shader
    and a link), its tests probed and judged (runs.run_judged). The class grader's.
  * GradedBuild: a variant built outside the sandbox from a configured build folder's `<target>_graded`
    targets (tests/CMakeLists.txt), whose sources are BUILD/grader/src: a file is written there only
    when it changed, so make recompiles only those, and a shader is compiled only when its folder
    changed. The grader's proof's (its variants are the instructors' own code).
"""
import concurrent.futures as cf
import hashlib
import json
import os
import re
import shutil
import stat
import subprocess
import tempfile
import threading
import time

from model import ROOT, die, exercises_of, find_region, log, write_manifest
from runs import discover_tests, run_judged
from sandbox import WORK, chown_tree, run_limited, sandbox


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


CONFIGURE = ["cmake", "-S", ".", "-B", "build", "-DCMAKE_BUILD_TYPE=RelWithDebInfo",
             "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -DNDEBUG", "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -DNDEBUG"]
# The pristine copy is built twice, solved and as handed out (the judge), and both builds compile
# the same common/ and test files with the same flags at the same path (WORK): ccache, where it is
# installed, compiles each of them once. It keys an object on the preprocessed source and the
# flags, so a stub never gets the solution's object. Submissions' builds never use it.
if shutil.which("ccache"):
    CONFIGURE += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]


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
    write_copy(lab, tmp)
    cache = os.path.join(tmp, "ccache")
    os.makedirs(cache)
    chown_tree(cache)
    tests = build_solved(lab, tmp, jobs, cache)
    build_judge(lab, tmp, tests, jobs, cache)
    shutil.rmtree(cache)
    if os.geteuid() == 0:  # the cache is the grader's: no sandbox may change it
        subprocess.run(["chown", "-R", "-h", "0:0", os.path.join(tmp, "work"), os.path.join(tmp, "judge", "work")], check=True)
    open(os.path.join(tmp, "done"), "w").write(f"built in {time.time() - t0:.0f} s\n")
    try:
        os.rename(tmp, d)
    except OSError:  # another grader finished first
        shutil.rmtree(tmp, ignore_errors=True)
    log(f"grade: pristine {lab} built in {time.time() - t0:.0f} s")
    evict(cache_root, lab, keep=d)
    return d


def write_copy(lab, tmp):
    """tmp/copy: the handed-out copy (scripts/exercise.sh); tmp/work: it with the lab's folders solved."""
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


def build_solved(lab, tmp, jobs, cache):
    """Configures and builds tmp/work in the sandbox (cache: the compiler's); writes and returns its
    tests (tests.json)."""
    work = os.path.join(tmp, "work")
    # The students' build type (scripts/setup.sh), without its -g: GCC makes the same code with and
    # without debug information, and without it every variant copies and links fewer bytes.
    code, out = run_limited(sandbox(tmp, "setup", cpu=3600, compiler_cache=cache) + CONFIGURE, 600)
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
        code, out = run_limited(sandbox(tmp, "setup", cpu=3600, compiler_cache=cache) +
                                ["nice", "-n", "10", "cmake", "--build", "build", f"-j{jobs}", "--target", *attempt], 3600)
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
    return tests


def build_judge(lab, tmp, tests, jobs, cache):
    """The judge: the handed-out copy (every exercise its stub) built with the same test programs. It
    runs the tests on the probe's records (tests/probe.h): no student code, and no solution either,
    so a value that a test takes from the lab without a probe comes from a stub and the solution
    fails its own test there (Grader refuses to start)."""
    judge = os.path.join(tmp, "judge")
    shutil.copytree(os.path.join(tmp, "copy"), os.path.join(judge, "work"), symlinks=True)
    os.makedirs(os.path.join(judge, "work", "build"))
    chown_tree(judge)
    code, out = run_limited(sandbox(judge, "setup", cpu=3600, compiler_cache=cache) + CONFIGURE, 600)
    if code == 0:
        code, out = run_limited(sandbox(judge, "setup", cpu=3600, compiler_cache=cache) + ["nice", "-n", "10", "cmake", "--build", "build", f"-j{jobs}",
                                                                    "--target", *sorted({os.path.basename(b) for b in tests})], 3600)
    if code != 0:
        fail_build(tmp, lab + " (the judge: the handed-out copy)", out)


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


def with_regions(solved, exercises, regions, names, unchanged=()):
    """The solved files {file: lines} with the regions {exercise: lines} of the exercises names in
    them (an exercise without a region: its stub; one in unchanged: left solved): {file: text} of
    the files that changed."""
    files = {}
    for e in exercises:
        if e["name"] not in names or e["name"] in unchanged:
            continue
        lines = files.setdefault(e["file"], list(solved[e["file"]]))
        reg = find_region(lines, e["name"])
        body = regions.get(e["name"], e["stub"])  # markers gone: the stub (not done)
        lines[reg[0] + 1:reg[1]] = e["stub_lines"] + body
    return {f: "".join(ls) for f, ls in files.items()}


# ---------------------------------------------------------------- identical variants
class VariantCache:
    """variant(changes, tests): the result of a variant with changes {file: text} for tests, built
    and run once for the same changes and tests (_run_variant: the build and run of a subclass)."""

    def __init__(self):
        self.lock = threading.Lock()
        self.variants = {}

    def variant(self, changes, tests):
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
        raise NotImplementedError


# ---------------------------------------------------------------- variants in the sandbox
class SandboxVariants(VariantCache):
    """Variants of the pristine copy pdir (pristine()), each a job of its own under scratch.
    Needs limits, judge_limits, after_hang (the tests' wall limits), binary_of (test → program),
    tests ({program: [(name, env)]}), source_dirs and lab: set by the subclass (grade.Grader)."""

    def __init__(self, lab, pdir, scratch):
        super().__init__()
        self.lab, self.pdir, self.scratch = lab, pdir, scratch
        self.copy = os.path.join(pdir, "copy")
        self.work = os.path.join(pdir, "work")
        self.judge_work = os.path.join(pdir, "judge", "work")
        # the folders whose text the judge's hints read (the lab's own, as the variant has them)
        self.source_dirs = [d for d in (lab, os.path.join("shaders", lab)) if os.path.isdir(os.path.join(self.work, d))]
        self.counter = 0
        self.make_dirs = {}

    def subset(self, names):
        out = {}
        for b, ts in self.tests.items():
            for n, env in ts:
                if n in names:
                    out.setdefault(b, []).append((n, env))
        return out

    def run_judged(self, job, tests, limits, judge_limits, start_limit=30.0, after_hang=None):
        """runs.run_judged on job's build, the judge's hints reading job's copy (its manifest)."""
        manifest = write_manifest(os.path.join(job, "exercises.json"), self.copy, os.path.join(job, "work"))
        return run_judged(job, self.subset, tests, limits, judge_limits, self.work, self.judge_work, self.source_dirs,
                          manifest=manifest, start_limit=start_limit, after_hang=after_hang)

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

    def _run_variant(self, changes, tests):
        t0 = time.time()
        job = self.new_job()
        t_copy = time.time() - t0
        t1 = time.time()
        built = self.build(job, changes, tests)
        t_build = time.time() - t1
        if built:
            shutil.rmtree(job, ignore_errors=True)
            return built
        t2 = time.time()
        res, _ = self.run_judged(job, tests, self.limits, self.judge_limits, after_hang=self.after_hang)
        if os.environ.get("GRADE_PROFILE"):
            log(f"    profile {sorted(changes)} {len(tests)} tests: copy {t_copy:.1f} s, build {t_build:.1f} s, tests {time.time() - t2:.1f} s")
        self.keep_pictures(job, res)
        shutil.rmtree(job, ignore_errors=True)
        shutil.rmtree(job + "-judge", ignore_errors=True)
        return {"build": "ok", "tests": res}

    def build(self, job, changes, tests):
        """Writes changes into job's copy and rebuilds what compiles them: None when it built, else
        the variant's result (it does not compile, ran out of time, or the build itself failed)."""
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
        if dirs and all(self.make_dirs_of(f) for f in changes):
            script = " && ".join(f"make -s -f {d}/build.make {d}/build" for d in dirs)
            code, out = run_limited(sandbox(job, "build", cpu=600, shared=self.work) + ["sh", "-c", "cd build && " + script], 600)
        else:
            targets = sorted({os.path.basename(self.binary_of[n]) for n in tests} | {self.lab})
            code, out = run_limited(sandbox(job, "build", cpu=600, shared=self.work) + ["cmake", "--build", "build", "-j1", "--target", *targets], 600)
        if code == 0:
            return None
        # "does not compile" only on the compiler's word; a build that stopped without one
        # (killed for memory, a full disk) is the environment's failure
        compiled = code is not None and re.search(r"\berror\b", out)
        return {"build": "timeout" if code is None else "failed" if compiled else "error",
                "log": out if compiled or code is None else "grader error: the build stopped without a compiler error:\n" + out[-2000:],
                "tests": {}}

    def keep_pictures(self, job, res):
        """The failing tests' pictures, kept (plain PNG files only) before the job's copy goes."""
        pics = os.path.join(self.scratch, "pictures", os.path.basename(job))
        for t, r in res.items():
            kept = []
            for pic in r.get("pictures", []) if r["status"] != "ok" else []:
                os.makedirs(pics, exist_ok=True)
                dst = os.path.join(pics, f"{len(os.listdir(pics))}.png")
                if copy_png(os.path.join(r.get("pictures_dir", os.path.join(job, "out")), pic), dst):
                    kept.append((pic, dst))
            r["pictures"] = kept
            r.pop("pictures_dir", None)


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


# ---------------------------------------------------------------- variants from BUILD's _graded targets
def write_text(path, text):
    """text written byte for byte as read (UTF-8, undecodable bytes kept as surrogate escapes)."""
    with open(path, "w", encoding="utf-8", errors="surrogateescape", newline="") as f:
        f.write(text)


def read_env_file(path):
    """KEY=value and KEY="value" lines (BUILD/grader/LAB.env, written by tests/CMakeLists.txt)."""
    env = {}
    for line in open(path):
        m = re.match(r'^([A-Z_][A-Z0-9_]*)=(.*)$', line.rstrip("\n"))
        if m:
            v = m.group(2)
            env[m.group(1)] = v[1:-1] if len(v) >= 2 and v[0] == v[-1] == '"' else v
    return env


class GradedBuild:
    """The lab built from BUILD's `<target>_graded` targets with its files as a variant has them.
    One build at a time (BUILD/grader/src is one folder); build(sources, into) mirrors sources
    ({path relative to the repository: text}, the lab's and its shaders' files) into
    BUILD/grader/src, builds, and copies what it built into `into` (bin/, shaders/LAB/, src/)."""

    def __init__(self, build, lab, log_path):
        self.build_dir, self.lab = build, lab
        self.g = os.path.join(build, "grader")
        self.conf = read_env_file(os.path.join(self.g, f"{lab}.env"))
        self.targets = [t for t in self.conf.get("GRADED_TARGETS", "").split(";") if t]
        self.shader_variants = [v for v in self.conf.get("SHADER_VARIANTS", "").split(";") if v]
        self.glslang = self.conf.get("GLSLANG", "glslangValidator")
        self.cmake = self.conf.get("CMAKE", "cmake")
        self.log_path = log_path
        self.lock = threading.Lock()
        self.first = True

    def _log(self, text):
        with open(self.log_path, "a") as f:
            f.write(text)

    def mirror(self, sources):
        """Writes each file into BUILD/grader/src where its text differs (make rebuilds only what changed)."""
        changed = False
        for rel, text in sorted(sources.items()):
            path = os.path.join(self.g, "src", rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            try:
                with open(path, encoding="utf-8", errors="surrogateescape", newline="") as f:
                    if f.read() == text:
                        continue
            except OSError:
                pass
            write_text(path, text)
            changed = True
        return changed

    def shaders(self):
        """Compiles the mirrored shaders whose folder changed since their last compile, and the
        lab's shader variants (lab_add_shaders … VARIANT src name DEFINE: src with -DDEFINE)."""
        src = os.path.join(self.g, "src", "shaders", self.lab)
        out = os.path.join(self.g, "shaders", self.lab)
        os.makedirs(out, exist_ok=True)
        if not os.path.isdir(src):
            return None
        newest = max((os.path.getmtime(os.path.join(src, f)) for f in os.listdir(src)), default=0)
        jobs = []
        for f in sorted(os.listdir(src)):
            if f.endswith((".vert", ".frag", ".comp")):
                jobs.append((os.path.join(src, f), os.path.join(out, f + ".spv"), []))
        for v in self.shader_variants:
            name, define, source = v.split(":", 2)
            jobs.append((os.path.join(src, os.path.basename(source)), os.path.join(out, name + ".spv"), ["-D" + define]))
        for source, spv, defines in jobs:
            # Unchanged since its last compile: no source of the folder (its includes) is newer.
            if os.path.exists(spv) and os.path.getmtime(spv) > newest:
                continue
            r = subprocess.run([self.glslang, "-V", "--target-env", "vulkan1.1", *defines, "-o", spv, source],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            self._log(r.stdout)
            if r.returncode:
                return f"{source.replace(self.g + '/src/', '')}{' with ' + defines[0][2:] if defines else ''} does not compile"
        return None

    def build(self, sources, into):
        """None when built (into/bin, into/shaders/LAB, into/src), else why not. seconds: the
        last build's."""
        with self.lock:
            t0 = time.time()
            self.mirror(sources)
            why = self.shaders()
            if why:
                return why
            targets = self.targets + (["exercise_hint"] if self.first else [])
            r = run_limited([self.cmake, "--build", self.build_dir, "--target", *targets, "-j2"], 1800)
            self._log(r.output)
            if r.code != 0:
                return f"building {' '.join(self.targets)} failed"
            self.first = False
            shutil.rmtree(into, ignore_errors=True)
            os.makedirs(os.path.join(into, "shaders"))
            shutil.copytree(os.path.join(self.g, "bin"), os.path.join(into, "bin"))
            shutil.copytree(os.path.join(self.g, "shaders", self.lab), os.path.join(into, "shaders", self.lab))
            for rel, text in sources.items():
                path = os.path.join(into, "src", rel)
                os.makedirs(os.path.dirname(path), exist_ok=True)
                write_text(path, text)
            self.seconds = time.time() - t0
            return None
