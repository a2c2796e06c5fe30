#!/usr/bin/env python3
"""exercise.sh — a student copy of the project, with a lab's exercises cut out and no answers in it.

  bash scripts/exercise.sh LAB [NAME…] [--out DIR]   # write the copy (default DIR: student/<lab>)
  bash scripts/exercise.sh --list [--json] [LAB]      # the exercises, with file, line and tests
                                                      # (--json: a JSON list, for the course site)
  bash scripts/exercise.sh --stub FILE NAME…          # print FILE with those exercises stubbed
  bash scripts/exercise.sh --left-out LAB             # what a copy of LAB leaves out (paths)
  bash scripts/exercise.sh --check-copy DIR LAB       # check a written copy for answers
  bash scripts/exercise.sh --check-copies             # write and check a copy of every lab with
                                                      # exercises (CTest: student_copy_no_answers)
  bash scripts/exercise.sh --check-copy-links         # write a copy of every lab; every link in
                                                      # it resolves (CTest: student_copy_links)
  bash scripts/exercise.sh --prove BUILD_DIR LAB [--rows]  # the grader's own test (CTest:
                                                      # grader_labN; scripts/grade/grade.py --prove)
  bash scripts/exercise.sh --solution-lines [--json] LAB   # the substantive solution lines of LAB's
                                                      # and every later lab's exercises (name US
                                                      # where US code; --json: a JSON list)
  bash scripts/exercise.sh --solution-code LAB [only] # their code as written, stubs too
  bash scripts/exercise.sh --manifest [--copy-root DIR] OUT  # the exercises as JSON for the C++
                                                      # hints and the grader (rewritten only when
                                                      # it changes); DIR: a tree whose lab
                                                      # folders are read instead of this one's

LAB is 1, lab1 or lab1_camera. Without NAMEs every exercise of the lab is cut out.
scripts/exercise.sh runs this file (scripts/exercise.py); scripts/course/exercises.py reads the
markers and tests/graded_exercises.txt for it and for every other tool.

In the labs' sources and shaders an exercise is marked like this:
    // EXERCISE attenuation: what to write, as a hint. Checked by Lab2Render.PointLights.
    // STUB: return 1.0;  // what the copy has instead (one or more STUB lines)
    ...the lab's code...
    // END EXERCISE
In the copy the code between the markers is replaced by the STUB lines under a
"// TODO EXERCISE name: hint" line. The copy builds and runs, with a visibly wrong picture,
and `ctest --test-dir build -L labN` there is the grader: the tests named after "Checked by"
fail until the exercise is done, and say which exercise it is and where.

What the copy of lab N holds: common/, labs 1..N-1 complete (their solutions are not secret
any more once lab N is handed out), lab N with its exercises stubbed, and the tests, scenes,
docs and scripts those labs use. What it leaves out, because it would hand out answers
(--left-out lists it; docs/solutions.md is the instructors' policy):
  - every file or folder named lab<K>_* or *_lab<K>_* with K > N: the later labs (lab N+1
    carries lab N complete), their shaders, scenes, test scenes, gallery pictures, bench scripts;
  - tests/ files that only later labs' tests use (every mention in tests/CMakeLists.txt inside an
    `if(TARGET lab<K>_…)` block, K > N), and scene folders (scenes/<dir>/) only later labs' scene
    files use;
  - docs/diffs/ (the diff lab N-1 → lab N is lab N's solution) and site/ (the course site builds
    pages from those diffs), whole: they are instructor material;
  - in the docs it keeps, every section that names a later lab: the student site's rule, applied
    by the site's own code (node site/student.mjs --trim-later-labs; laterLabText there), so the
    copy and its student site (built from the copy) drop the same sections.
The copy has a .student-copy file (its lab): tests/CMakeLists.txt then disables the tests of the
whole project that a copy cannot pass (the diffs, the site, the architecture picture).
--check-copy checks a copy: nothing above is in it, each cut-out exercise is a TODO, no text
file holds a line of a cut-out solution, and no doc a section about a later lab (see check_copy).

An exercise belongs to the first lab that has it (lab 2 carries lab 1's camera.cpp with its
markers; they are lab 1's exercises).
Exit status: 0 done, 1 a check failed, 2 bad input, 77 skipped (a student copy).
"""
import fcntl
import fnmatch
import glob
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from course import exercises as ex  # noqa: E402 (beside this file)

ROOT = ex.ROOT
PYTHON = sys.executable or "python3"


def die(msg):
    print(f"exercise: {msg}", file=sys.stderr)
    sys.exit(2)


def resolve(want):
    try:
        return ex.resolve_lab(want)
    except LookupError as e:
        die(str(e))


def captured(text):
    """A command's output as $(…) gives it: without its trailing newlines."""
    return text.rstrip("\n")


def run(args, **kw):
    """A helper command, its output to where kw says; the caller's output is flushed first."""
    sys.stdout.flush()
    return subprocess.run(args, **kw)


def helper(args):
    """A step of writing a copy: its output discarded, its failure the copy's (its exit status)."""
    r = run(args, stdout=subprocess.DEVNULL)
    if r.returncode != 0:
        sys.exit(r.returncode)


# ---------------------------------------------------------------- what a copy leaves out
LATER_RE = re.compile(r"(^|_|-)lab[0-9]+_")


def later_lab(path, n):
    """Whether any name of path (not only the last part) is a later lab's than lab n: lab<K>_… or
    …_lab<K>_… with K > n ("lab1_camera-lab2_lighting.diff" is lab 2's). The one rule for the
    later labs' folders, shaders, scenes, test scenes, gallery pictures, trade-off figures and bench
    scripts, so a new file named like them is left out too."""
    for part in path.split("/"):
        rest = part
        while True:
            m = LATER_RE.search(rest)
            if not m:
                break
            if int(re.sub(r"[^0-9]", "", m.group(0))) > n:
                return True
            rest = rest[m.end():]
    return False


def tree_paths(top, prune=False):
    """The files and folders under top, relative to it, parents before children (links not
    followed). prune: without git data, build outputs and student copies (the project's paths a
    copy is written from: .git, build*, out, student at the top)."""
    found = []
    for here, dirs, files in os.walk(top):
        rel = os.path.relpath(here, top)
        names = dirs + files
        if rel == "." and prune:
            keep = lambda d: not (d in (".git", "out", "student") or d.startswith("build"))
            dirs[:] = [d for d in dirs if keep(d)]
            names = [d for d in names if keep(d)]
        prefix = "" if rel == "." else rel.replace(os.sep, "/") + "/"
        found += [prefix + name for name in names]
    return found


def later_test_files(n):
    """tests/ files that only the tests of labs after lab n use: every mention of them in
    tests/CMakeLists.txt is inside an `if(TARGET lab<K>_…)` block with K > n, so a copy without
    those labs configures without them. A file mentioned anywhere else stays (better a harmless
    test file too many than a copy that does not configure); so does a file CMake does not name (a
    header)."""
    later, depth, seen, kept = {}, 0, set(), set()
    token = re.compile(r"[A-Za-z0-9_./${}-]+\.(cpp|h|py|sh|json|obj|cmake)")
    for line in ex.split_lines(ex.read_text("tests/CMakeLists.txt")):
        line = line.split("#", 1)[0]  # CMake comments
        if re.match(r"^[ \t]*if[ \t]*\(", line):
            later[depth + 1] = later.get(depth, False)
            m = re.search(r"TARGET[ \t]+lab[0-9]+_", line)
            if m and int(re.sub(r"[^0-9]", "", m.group(0))) > n:
                later[depth + 1] = True
            depth += 1
        if re.match(r"^[ \t]*(else|elseif)[ \t]*\(", line):
            later[depth] = later.get(depth - 1, False)  # runs without that lab
        if re.match(r"^[ \t]*endif[ \t]*\(", line):
            depth -= 1
            continue
        for m in token.finditer(line):
            tok = re.sub(r"^\$\{CMAKE_CURRENT_SOURCE_DIR\}/", "", m.group(0))
            if "$" in tok:
                continue  # a file outside tests/, or a name made up at configure time
            seen.add(tok)
            if not later.get(depth, False):
                kept.add(tok)
    return [f"tests/{t}" for t in sorted(seen - kept, key=ex.byte_order) if os.path.exists(f"tests/{t}")]


def reference_source():
    """The CPU reference's source and its own tests (hand calculations that are the labs'
    answers): what reference_libs replaces in a copy."""
    return sorted(glob.glob("tests/reference/*.cpp"), key=ex.byte_order) + [
        "tests/test_cpu_reference.cpp", "tests/test_ideal_reference.cpp", "tests/test_cpu_shadow.cpp",
        "tests/test_reference_lighting.cpp", "tests/test_reference_sampling.cpp"]


def topmost(paths):
    """The paths sorted, each once, without those inside another one given (a folder stands for
    its files)."""
    listed = set()
    for path in sorted({p for p in paths if p}, key=ex.byte_order):
        parts = path.split("/")
        if not any("/".join(parts[:i]) in listed for i in range(1, len(parts))):
            listed.add(path)
    return sorted(listed, key=ex.byte_order)


def left_out(n):
    """What a copy of lab n leaves out, one path each (a folder stands for all it holds)."""
    paths = tree_paths(".", prune=True)
    gone = [p for p in paths if later_lab(p, n)]
    gone += ["docs/diffs",  # lab N-1 → lab N is lab N's solution; the earlier ones are instructor material
             "site",  # the course site: its pages show every lab and the diffs
             "docs/solutions",  # the answers the exercises' comments do not give (instructors only)
             "docs/solutions.md"]  # the instructors' policy: where every answer is, what to hand out when
    if n <= 2:  # lab 2's Blinn-Phong whole, a benchmark's fixture (bench/speed_goals.sh): an answer until lab 3
        gone.append("bench/fixtures/minimal_blinn_phong.frag")
    # A later lab's lesson that lives in a shared folder: lab 2's lighting doc (lab 1 has no light).
    # (tests/reference/cpu_shadow.h, lab 4's part of the reference's interface, stays: the copy's
    # tools/lab_reference.cpp includes it.)
    if n <= 1:
        gone.append("docs/lighting.md")
    gone += later_test_files(n)
    # The CPU reference's source and its own tests: a copy gets the reference prebuilt instead
    # (reference_libs, tests/CMakeLists.txt).
    gone += reference_source()
    # A scene folder (models, textures) that only later labs' scene files use: every JSON file that
    # names it ("textures/bricks.png") is left out. A folder no JSON file names stays.
    scene_files = {}
    for p in paths:
        if p.endswith(".json") and os.path.isfile(p):
            with open(p, "rb") as f:
                scene_files[p] = f.read()
    for d in sorted(glob.glob("scenes/*/"), key=ex.byte_order):
        d = d.rstrip("/")
        name = (os.path.basename(d) + "/").encode("utf-8", "surrogateescape")
        users = [p for p, data in scene_files.items() if name in data]
        if users and all(later_lab(u, n) for u in users):
            gone.append(d)
    return topmost(gone)


# ---------------------------------------------------------------- the prebuilt CPU reference
def reference_libs(out, n):
    """Writes the CPU reference, prebuilt, into copy out of lab n: tests/reference/lib/
    libcpu_reference.a, and from lab 3 on libreference_vulkan.a (lab 3's unit tests read the device
    through it); tests/CMakeLists.txt links them where the source is missing. Built here with the
    course's platform's compiler (Debian 12 x86-64: g++ 12) and the project's release flags, without
    debug information, into build/student-reference/<hash of the sources and the compiler>/ (once
    per state of the reference; flock: copies written at the same time share it)."""
    cxx = os.environ.get("CXX") or "c++"
    flags = ["-std=c++17", "-O2", "-DNDEBUG", "-DGLM_FORCE_DEPTH_ZERO_TO_ONE", "-DGLM_FORCE_RADIANS",
             "-I", "tests", "-I", "common/content", "-I", "common/vulkan"]
    key = hashlib.sha256()
    try:
        version = subprocess.run([cxx, "--version"], capture_output=True).stdout.split(b"\n")[0]
    except OSError:
        version = b""
    key.update(version + b"\n" if version else b"")
    key.update((" ".join(flags) + "\n").encode())
    for pattern in ("tests/reference/*", "common/content/*.h", "common/vulkan/*.h"):
        for f in sorted(glob.glob(pattern), key=ex.byte_order):
            if os.path.isfile(f):
                with open(f, "rb") as fh:
                    key.update(fh.read())
    key = key.hexdigest()[:16]
    shared = os.path.join(ROOT, "build", "student-reference")
    cache = os.path.join(shared, key)
    os.makedirs(shared, exist_ok=True)
    with open(os.path.join(shared, "lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not os.path.isfile(os.path.join(cache, "done")):
            shutil.rmtree(cache, ignore_errors=True)
            os.makedirs(cache)
            log = os.path.join(cache, "build.log")
            sources = sorted(glob.glob("tests/reference/*.cpp"), key=ex.byte_order)
            with open(log, "wb") as logf:
                def compile_one(src):
                    obj = os.path.join(cache, os.path.basename(src)[:-len(".cpp")] + ".o")
                    r = subprocess.run([cxx, *flags, "-c", src, "-o", obj], stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
                    logf.write(r.stdout)
                    return r.returncode
                with ThreadPoolExecutor(2) as pool:
                    failed = any(rc != 0 for rc in pool.map(compile_one, sources))
            if failed:
                with open(log, "rb") as f:
                    sys.stderr.buffer.write(f.read())
                die(f"the CPU reference did not compile (see {log})")
            # libreference_vulkan.a: the device side alone; libcpu_reference.a: the rest.
            vulkan = os.path.join(cache, "vulkan_reference.o")
            if run(["ar", "rcs", os.path.join(cache, "libreference_vulkan.a"), vulkan]).returncode:
                die(f"ar failed in {cache}")
            os.remove(vulkan)
            objects = sorted(glob.glob(os.path.join(cache, "*.o")), key=ex.byte_order)
            if run(["ar", "rcs", os.path.join(cache, "libcpu_reference.a"), *objects]).returncode:
                die(f"ar failed in {cache}")
            open(os.path.join(cache, "done"), "w").close()
            # Only the newest state's libraries are kept.
            for other in os.listdir(shared):
                path = os.path.join(shared, other)
                if other != key and os.path.isdir(path) and not os.path.islink(path):
                    shutil.rmtree(path, ignore_errors=True)
        lib = os.path.join(out, "tests", "reference", "lib")
        os.makedirs(lib, exist_ok=True)  # inside the lock: another state's copy may prune this one's
        shutil.copy(os.path.join(cache, "libcpu_reference.a"), lib)
        if n >= 3:
            shutil.copy(os.path.join(cache, "libreference_vulkan.a"), lib)


# ---------------------------------------------------------------- checking a copy
# Lines of a solution that a copy holds on purpose: ("path-glob", "exercise"). Keep it short; each
# entry says why the copy cannot do without that file. A new exercise whose answer turns up in one
# of these files fails the check until someone decides it belongs here.
KNOWN_ANSWERS = (
    # None: the grader's oracle, whose lines were the lab's where a formula has one way to be
    # written (the camera's columns, the light falloff), travels prebuilt (reference_libs), not as
    # source.
)


def text_files(top):
    """The text files under top, relative to it ("./" dropped), sorted: regular files (links not
    followed) with no NUL byte in their first 32 KiB, as grep -rI reads them."""
    for rel in sorted(tree_paths(top), key=ex.byte_order):
        path = os.path.join(top, rel)
        if os.path.islink(path) or not os.path.isfile(path):
            continue
        with open(path, "rb") as f:
            data = f.read()
        if b"\0" not in data[:32768]:
            yield rel, data


def answer_hits(top, answers):
    """(path, line, exercise, where) for each line of a text file under top that holds a solution
    line (answers: solution_lines rows), compared without whitespace, as part of any line."""
    codes = [(name, where, code.encode("utf-8", "surrogateescape")) for name, where, code in answers]
    space = re.compile(rb"[ \t\r]+")
    for rel, data in text_files(top):
        for k, line in enumerate(data.split(b"\n"), 1):
            s = space.sub(b"", line)
            if len(s) < 16:
                continue
            for name, where, code in codes:
                if code in s:
                    yield rel, k, name, where


def check_copy(top, lab):
    """--check-copy DIR LAB: is DIR a copy of lab LAB (written by this script) without answers?
      (a) nothing --left-out lists is there, and no file or folder anywhere is named after a later lab;
      (b) every exercise of the lab is cut out: its file has the "// TODO EXERCISE name:" line;
      (c) no text file holds a solution line (solution_lines) of the lab's or a later lab's
          exercises, compared without whitespace, as part of any line: a doc that quotes the answer,
          a later lab's file, a diff, a bench script with a shader in it all count;
      (d) no comment and no Markdown text names a distinctive token of a solution of the lab (an
          enum, a nested call expression) that the copy's code does not hold anyway
          (scripts/comment_answers.py);
      (e) no declared answer form (scripts/check_answers.py);
      (f) no page of the docs keeps a section that names a later lab, which the student site leaves
          out (node site/student.mjs --check-later-labs).
    Prints one line per problem; returns 1 if there is one, else 0."""
    n = ex.lab_number(lab)
    problems = 0
    if not os.path.isdir(top):
        die(f"--check-copy: no folder {top}")
    if not os.path.isfile(os.path.join(top, ".student-copy")):
        print(f"FAIL {top} has no .student-copy: not written by exercise.sh")
        problems += 1
    for p in left_out(n):
        if os.path.exists(os.path.join(top, p)):
            print(f"FAIL left in the copy: {p}")
            problems += 1
    for p in topmost(p for p in tree_paths(top) if later_lab(p, n)):
        print(f"FAIL a later lab's file in the copy: {p}")
        problems += 1

    own = ex.exercises_of(lab)
    for e in own:
        try:
            with open(os.path.join(top, e.file), "rb") as f:
                cut = f"// TODO EXERCISE {e.name}: ".encode() in f.read()
        except OSError:
            cut = False
        if not cut:
            print(f"FAIL exercise {e.name} is not cut out of {e.file}")
            problems += 1

    answers = ex.solution_lines(lab)
    if not answers:
        print(f"FAIL no solution lines found for {lab}'s exercises: nothing to look for")
        problems += 1
    reported = 0
    for path, at, name, where in answer_hits(top, answers):
        known = [k for k in KNOWN_ANSWERS if fnmatch.fnmatchcase(path, k[0]) and name == k[1]]
        if known:
            print(f"known: {path}:{at} has a line of exercise {name} ({where}), on purpose (KNOWN_ANSWERS)")
            continue
        reported += 1
        if reported <= 20:
            print(f"FAIL answer in the copy: {path}:{at} holds a line of exercise {name} ({where})")
    if reported > 20:
        print(f"… and {reported - 20} more")
    problems += reported

    r = run([PYTHON, os.path.join(ROOT, "scripts", "comment_answers.py"), top, lab], stdout=subprocess.PIPE,
            text=True, errors="surrogateescape")
    comments = captured(r.stdout).split("\n")
    for line in comments:
        if not line.startswith("FAIL"):
            print(line)
    fails = [line for line in comments if line.startswith("FAIL")]
    problems += len(fails)
    for line in fails[:20]:
        print(line)
    # (e) no text file states an answer of the lab's or a later lab's exercises in any of the forms
    #     docs/solutions/answers.json declares (a formula, an enum, a phrase; scripts/check_answers.py).
    r = run([PYTHON, os.path.join(ROOT, "scripts", "check_answers.py"), top, str(n)], stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT, text=True, errors="surrogateescape")
    declared = captured(r.stdout)
    print(declared)
    if r.returncode != 0:
        problems += sum(line.startswith("FAIL") for line in declared.split("\n")) + (r.returncode != 1)
    # (f) the docs trimmed as the student site trims them: no section that names a later lab.
    if not shutil.which("node"):
        print("FAIL node is missing: cannot check the copy's docs for sections about later labs (scripts/setup.sh installs Node.js)")
        problems += 1
    else:
        r = run(["node", os.path.join(ROOT, "site", "student.mjs"), "--check-later-labs", top, str(n)],
                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="surrogateescape")
        if r.returncode != 0:
            later = captured(r.stdout)
            print(later)
            count = sum(line.startswith("FAIL") for line in later.split("\n"))
            problems += count if count else 1  # it failed without naming a page: one problem
    if problems:
        print(f"check-copy: {top}: {problems} problem(s) (a copy of {lab} must hold none of its answers)")
        return 1
    print(f"check-copy: {top}: no later lab, {len(own)} exercises cut out, no answers but the known ones")
    return 0


def copy_links(top, lab):
    """Every relative link and #anchor of the copy's Markdown files resolves (scripts/check_links.py):
    the copy leaves docs/diffs/ and the later labs out, and its links to them must have become text."""
    r = run([PYTHON, os.path.join(ROOT, "scripts", "check_links.py"), top], stdout=subprocess.PIPE,
            text=True, errors="surrogateescape")
    for line in r.stdout.splitlines(keepends=True):
        sys.stdout.write(f"{lab} copy: {line}")
    return r.returncode


def for_each_copy(check):
    """Writes a copy of every lab that has exercises into a temporary folder (no build: seconds) and
    runs check(DIR, LAB) on each; exit 1 if a check fails, 77 inside a student copy (copies are
    written from the complete project). --check-copies (CTest: student_copy_no_answers) runs
    check_copy; --check-copy-links (CTest: student_copy_links) runs copy_links."""
    if os.path.exists(".student-copy"):
        with open(".student-copy") as f:
            which = f.readline().rstrip("\n")
        print(f"exercise: this is a student copy ({which}): copies are written from the complete project (skipped)")
        sys.exit(77)
    failed, count = 0, 0
    tmp = tempfile.mkdtemp()
    try:
        for lab in ex.labs():
            if not ex.exercises_of(lab):
                continue
            count += 1
            copy = os.path.join(tmp, lab)
            if run([PYTHON, os.path.abspath(__file__), lab, "--out", copy], stdout=subprocess.DEVNULL).returncode:
                print(f"FAIL exercise.sh {lab} did not write a copy")
                failed = 1
                continue
            if check(copy, lab):
                failed = 1
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if not count:
        print("FAIL no lab has exercises: nothing checked")
        sys.exit(1)
    sys.exit(failed)


# ---------------------------------------------------------------- writing a copy
def copy_tree(out):
    """The project without build outputs, student copies and git data, into out. In a git
    checkout: the files git tracks or would track (nothing ignored, so no node_modules, no GPU
    bundle, no caches of the instructor's machine)."""
    inside = run(["git", "-C", ROOT, "rev-parse", "--is-inside-work-tree"], capture_output=True).returncode == 0
    sys.stdout.flush()
    if inside:
        listed = run(["git", "-C", ROOT, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                     stdout=subprocess.PIPE, check=True).stdout
        files = [f for f in listed.split(b"\0") if f and os.path.exists(os.path.join(ROOT.encode(), f))]
        pack = subprocess.Popen(["tar", "-C", ROOT, "--null", "-T", "-", "-cf", "-"], stdin=subprocess.PIPE,
                                stdout=subprocess.PIPE)
    else:
        pack = subprocess.Popen(["tar", "-C", ROOT, "--exclude=./build*", "--exclude=./out", "--exclude=./student",
                                 "--exclude=./.git", "-cf", "-", "."], stdin=subprocess.DEVNULL, stdout=subprocess.PIPE)
    unpack = subprocess.Popen(["tar", "-C", out, "-xf", "-"], stdin=pack.stdout)
    pack.stdout.close()
    if inside:
        pack.stdin.write(b"".join(f + b"\0" for f in files))
        pack.stdin.close()
    for rc in (pack.wait(), unpack.wait()):
        if rc:
            sys.exit(rc)


def write_copy(args):
    """LAB [NAME…] [--out DIR]: writes the student copy (see the top of this file)."""
    lab = resolve(args[0])
    out, names, rest = f"student/{lab}", [], args[1:]
    while rest:
        if rest[0] == "--out":
            if len(rest) < 2:
                die("--out needs a folder")
            out, rest = rest[1], rest[2:]
        else:
            names.append(rest.pop(0))
    n = ex.lab_number(lab)

    everything = ex.exercises_of(lab)
    if not everything:
        die(f"{lab} has no exercises")
    known = [e.name for e in everything]
    names = names or known
    for name in names:
        if name not in known:
            die(f"{lab} has no exercise '{name}' (it has: {' '.join(known)}  )")

    # The docs are trimmed by the student site's own rule (site/student.mjs, below): it needs
    # Node.js and the site's code, which only the complete project has.
    if not os.path.isfile(os.path.join(ROOT, "site", "student.mjs")):
        die("site/student.mjs is missing (a student copy?): copies are written from the complete project")
    if not shutil.which("node"):
        die("node is missing: a copy's docs are trimmed by site/student.mjs (scripts/setup.sh installs Node.js)")

    parent = os.path.dirname(out) or "."
    where = (os.path.abspath(parent) if os.path.isdir(parent) else "") + "/" + os.path.basename(out)
    if where == ROOT or where.startswith(ROOT + "/lab") or where.startswith(ROOT + "/shaders"):
        die(f"--out {out} would overwrite the project")
    if os.path.exists(out) and (not os.path.isdir(out) or os.listdir(out)):
        die(f"{out} exists and is not empty: remove it or pass --out DIR")
    os.makedirs(out, exist_ok=True)

    # The project without build outputs, student copies and git data; then without what would hand
    # out answers (left_out: the later labs and the instructor material, see the top of this file).
    copy_tree(out)
    for p in left_out(n):
        path = os.path.join(out, p)
        if os.path.isdir(path) and not os.path.islink(path):
            shutil.rmtree(path)
        elif os.path.lexists(path):
            os.remove(path)
    # The grader's table keeps the copy's labs: a later lab's rows name its tests and exercises.
    table = []
    for line in ex.split_lines(ex.read_text(os.path.join(ROOT, ex.GRADED))):
        if line.startswith(f"# ---- lab {n + 1}"):
            break
        table.append(line)
    with open(os.path.join(out, ex.GRADED), "w", encoding="utf-8", errors="surrogateescape", newline="") as f:
        f.write(ex.join_lines(table))
    reference_libs(out, n)
    # Links to what was left out become plain text, marked as a later lab's or instructors'
    # material, so every link of the copy works (--check-copy-links).
    helper([PYTHON, os.path.join(ROOT, "scripts", "check_links.py"), "--unlink-missing", out, str(n), ROOT])
    # The docs' answer spans (<!-- answer NAME: question -->answer<!-- /answer -->) become their
    # questions for this lab's and later labs' exercises (scripts/check_answers.py --rewrite).
    helper([PYTHON, os.path.join(ROOT, "scripts", "check_answers.py"), "--rewrite", out, str(n)])
    # Last of the Markdown steps: every section of the docs that names a later lab is left out, by
    # the student site's rule and code (site/student.mjs, laterLabText), on the text as the copy has
    # it, so the copy and its student site drop the same sections.
    helper(["node", os.path.join(ROOT, "site", "student.mjs"), "--trim-later-labs", out, str(n)])
    # Marks the copy (tests/CMakeLists.txt: the tests of the whole project are disabled there).
    with open(os.path.join(out, ".student-copy"), "w") as f:
        f.write(f"{lab}\n{' '.join(names)}\n")

    print(f"exercise: {lab}, student copy in {out}")
    chosen = [e for e in everything if e.name in names]
    by_file = {}
    for e in chosen:
        by_file.setdefault(e.file, []).append(e.name)
    for file, cut in by_file.items():
        try:
            text = ex.stub_text(ex.read_text(file), cut)
        except ValueError:
            print(f"exercise: unterminated EXERCISE in {file}", file=sys.stderr)
            sys.exit(3)
        with open(os.path.join(out, file), "w", encoding="utf-8", errors="surrogateescape", newline="") as f:
            f.write(text)
    # Each exercise where the copy has it (a stub is shorter than the code it replaces: the lines of
    # the instructors' files would point below the TODO of a later exercise in the same file).
    for e in chosen:
        lines = ex.split_lines(ex.read_text(os.path.join(out, e.file)))
        at = next((str(k) for k, line in enumerate(lines, 1) if f"// TODO EXERCISE {e.name}: " in line), "")
        print(f"  {e.name:<14} {e.file}:{at}")
    # .exercise-stubs: each cut-out exercise's stub, "file name stub-line", so that the grader
    # (tests/exercise_hints.cpp) sees an exercise as done once its code differs from the stub.
    with open(os.path.join(out, ex.STUBS), "w", encoding="utf-8", errors="surrogateescape", newline="") as f:
        f.write(ex.stubs_file(chosen))
    short = lab.split("_", 1)[0]
    earlier = ", ".join(ex.labs()[:ex.labs().index(lab)])
    print(f"""It holds common/, {f"the earlier labs complete ({earlier}), " if earlier else ""}{lab} with the exercises above cut out,
and the tests, scenes, docs and scripts they use. Left out: the later labs (with their shaders,
scenes, tests and gallery pictures), docs/diffs/ and site/ (bash scripts/exercise.sh --left-out {short}),
and the CPU reference's source: the copy's tests link it prebuilt (tests/reference/lib/, built
here for Debian 12 x86-64), with its headers.
Hand it out only as docs/solutions.md says: a copy of lab N+1 holds lab N's solutions.
Check it: bash scripts/exercise.sh --check-copy {out} {short}
Build and grade it:
  cd {out} && bash scripts/setup.sh
  ctest --test-dir build -L {short} --output-on-failure     # the grader: green when every exercise is done
Each failing test names the first unfinished exercise it needs; build/test_output/ has the pictures
(expected | actual | difference, left to right).""")


# ---------------------------------------------------------------- the other commands
def list_exercises(args):
    """--list [--json] [LAB]: every lab's exercises (or LAB's), with file, line, tests and hint."""
    as_json = "--json" in args
    args = [a for a in args if a != "--json"]
    which = [resolve(args[0])] if args else ex.labs()
    if as_json:
        print(json.dumps([e.listing() for lab in which for e in ex.exercises_of(lab)], ensure_ascii=False, indent=1))
        return
    for lab in which:
        print(f"{lab}:")
        for e in ex.exercises_of(lab):
            print(f"  {e.name:<14} {e.file}:{e.line}  (tests: {' '.join(e.tests) or 'none'})\n      {e.hint}")


def write_manifest(args):
    """--manifest [--copy-root DIR] OUT: the manifest (course.exercises.manifest) into OUT, through a
    temporary file and a rename, and only when it changes (make rebuilds nothing for nothing)."""
    copy_root = None
    if len(args) == 3 and args[0] == "--copy-root":
        copy_root, args = args[1], args[2:]
        if not os.path.isdir(copy_root):
            die(f"--manifest: no folder {copy_root}")
    if len(args) != 1 or args[0].startswith("--"):
        die("usage: exercise.sh --manifest [--copy-root DIR] OUT")
    out = args[0]
    text = ex.manifest_text(ROOT, copy_root and os.path.abspath(copy_root)).encode("utf-8", "surrogateescape")
    try:
        with open(out, "rb") as f:
            if f.read() == text:
                return
    except OSError:
        pass
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(out)), prefix=".manifest-")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(text)
        os.chmod(tmp, 0o644)
        os.replace(tmp, out)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise


def main(argv):
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # output cut short (| head): end quietly, as a shell tool does
    sys.stdout.reconfigure(encoding="utf-8", errors="surrogateescape", line_buffering=True)
    os.chdir(ROOT)  # paths (FILE, DIR, --out) are relative to the project's root
    cmd = argv[0] if argv else ""
    if cmd in ("", "-h", "--help"):
        print(__doc__.strip())
        return 0
    if cmd == "--left-out":
        if len(argv) != 2:
            die("usage: exercise.sh --left-out LAB")
        for p in left_out(ex.lab_number(resolve(argv[1]))):
            print(p)
        return 0
    if cmd == "--check-copy":
        if len(argv) != 3:
            die("usage: exercise.sh --check-copy DIR LAB")
        return check_copy(argv[1], resolve(argv[2]))
    if cmd == "--solution-code":
        if not (len(argv) == 2 or (len(argv) >= 3 and argv[2] == "only")):
            die("usage: exercise.sh --solution-code LAB [only]")
        for row in ex.solution_code(resolve(argv[1]), len(argv) >= 3):
            print("\037".join(row))
        return 0
    if cmd == "--solution-lines":
        as_json = "--json" in argv[1:]
        args = [a for a in argv[1:] if a != "--json"]
        if len(args) != 1:
            die("usage: exercise.sh --solution-lines [--json] LAB")
        rows = ex.solution_lines(resolve(args[0]))
        if as_json:
            print(json.dumps([{"name": n, "where": w, "code": c} for n, w, c in rows], ensure_ascii=False, indent=1))
        else:
            for row in rows:
                print("\037".join(row))
        return 0
    if cmd == "--check-copies":
        if len(argv) != 1:
            die("usage: exercise.sh --check-copies")
        for_each_copy(check_copy)
    if cmd == "--check-copy-links":
        if len(argv) != 1:
            die("usage: exercise.sh --check-copy-links")
        for_each_copy(copy_links)
    if cmd == "--prove":
        if not (len(argv) == 3 or (len(argv) == 4 and argv[3] == "--rows")):
            die("usage: exercise.sh --prove BUILD_DIR LAB [--rows]")
        sys.stdout.flush()
        grade = os.path.join(ROOT, "scripts", "grade", "grade.py")
        os.execvp(PYTHON, [PYTHON, grade, *argv])
    if cmd == "--list":
        list_exercises(argv[1:])
        return 0
    if cmd == "--stub":
        if len(argv) < 3:
            die("usage: exercise.sh --stub FILE NAME…")
        if not os.path.isfile(argv[1]):
            die(f"--stub: no file {argv[1]}")
        try:
            sys.stdout.write(ex.stub_text(ex.read_text(argv[1]), argv[2:]))
        except ValueError:
            print(f"exercise: unterminated EXERCISE in {argv[1]}", file=sys.stderr)
            return 3
        return 0
    if cmd == "--manifest":
        write_manifest(argv[1:])
        return 0
    write_copy(argv)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
