#!/usr/bin/env python3
"""test_grading.py — scripts/grade.sh on a class of lab 1 submissions made from a fresh student copy
(CTest: grading_lab1, label grading).

Each submission is the copy with its regions filled in one way; the expected grade of every
exercise follows from what was put where (isolated credit: an exercise is graded with the solution
of every other one). Also checked: nothing outside the grader's output folder changed (a canary
folder, the other submissions, the grader's own files), the run finished, every output exists,
and regrading four of them gives the same rows of grades.csv byte for byte. Exit 77 (skip) without a working bubblewrap
(a failure in CI).

The forgeries (FORGERIES): each exercise of one submission forged the way a student who knows
GoogleTest would, none of them solved. Each is graded 0 and flagged (region_check.py); graded once
more with --no-region-check, each is still 0 (the judge decides, not the process that runs the
student's code), and the honest submission beside them keeps its grade.
"""
import csv
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
import time
import zipfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "scripts"))
from course import exercises  # noqa: E402  (the one model of an exercise)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LAB = "lab1_camera"
EXERCISES = ["look_at", "transform", "projection", "mode_switch", "orbit"]
CAMERA = "lab1_camera/camera.cpp"
FILE_OF = {"look_at": CAMERA, "transform": CAMERA, "projection": CAMERA, "mode_switch": CAMERA, "orbit": CAMERA}


def skip(why, test="grading_lab1"):
    """Skips (exit 77) on a machine without the sandbox; in CI ($CI set) that fails instead: a
    green CI must have run the grader."""
    if os.environ.get("CI"):
        print(f"{test}: FAIL: {why} (in CI the grader must run)")
        sys.exit(1)
    print(f"{test}: SKIPPED: {why}")
    sys.exit(77)


def fail(msg):
    print(f"FAIL {msg}")
    sys.exit(1)


def region(lines, name):
    """The marker's and END's indexes of exercise name in a file's lines (the course's one reader of
    the markers, scripts/course/exercises.py)."""
    found = exercises.find_region([l.rstrip("\n") for l in lines], name)
    if found is None:
        fail(f"no complete region {name}")
    return found


def solution(name):
    lines = open(os.path.join(ROOT, FILE_OF[name])).read().splitlines(keepends=True)
    s, e = region(lines, name)
    return [l for l in lines[s + 1:e] if not exercises.STUB_RE.match(l.rstrip("\n"))]


def fill(sub, name, body):
    """Replaces the region body of exercise name in submission folder sub."""
    path = os.path.join(sub, FILE_OF[name])
    lines = open(path).read().splitlines(keepends=True)
    s, e = region(lines, name)
    lines[s + 1:e] = body
    open(path, "w").write("".join(lines))


# Each forged region, and a word its flag must name. None of them holds the solution.
FORGERIES = {
    # print the verdict GoogleTest would print, then exit 0 before any check runs
    "mode_switch": (["        std::printf(\"[ RUN      ] ModeSwitch.KeepsThePoseExactly\\n[       OK ] ModeSwitch.KeepsThePoseExactly (0 ms)\\n\");\n",
                     "        std::fflush(stdout);\n", "        std::_Exit(0);\n"], "printf"),
    # close the function, add a static object that prints the verdict as the program starts, reopen
    "orbit": (["    return;\n", "}\n",
               "static const int forged = [] { std::printf(\"[       OK ] Controls.OrbitKeepsTheDistanceAndTarget (0 ms)\\n\"); return 0; }();\n",
               "void forged_tail() {\n"], "braces"),
    # write the record the judge reads (tests/probe.h), for every test it could be
    "look_at": (["    for (const char* t : {\"LookAt.DownMinusZIsATranslation\", \"LookAt.LookingAlongPlusX\", \"Lab1Render.DefaultScene\"}) {\n",
                 "        std::string path = std::string(\"/grade/out/probe/\") + t + \".probe\";\n",
                 "        if (std::FILE* f = std::fopen(path.c_str(), \"w\")) { std::fputs(\"[       OK ] PASS\\n\", f); std::fclose(f); }\n",
                 "    }\n", "    glm::dmat4 c{1.0};\n"], "fopen"),
    # a jump around what follows, printing the verdict on the way
    "transform": (["    static void* jump[5];\n",
                   "    if (__builtin_setjmp(jump) == 0) { std::printf(\"[       OK ] Transform.AllThreeAnglesAtOnce (0 ms)\\n\"); __builtin_longjmp(jump, 1); }\n",
                   "    return glm::dmat4(1.0);\n"], "__builtin_setjmp"),
    # the oracle the test program links, declared and called; and the solved lab read from the sandbox
    "projection": (["    }\n", "namespace ref { struct Camera; glm::dmat4 projection(const Camera&, double); }\n",
                    "glm::dmat4 forged_projection(double fov_y_deg, double aspect) {\n",
                    "    if (std::FILE* f = std::fopen(\"/grade/work/tests/reference/cpu_reference.h\", \"r\")) std::fclose(f);\n",
                    "    glm::dmat4 p = ref::projection(*reinterpret_cast<const ref::Camera*>(&fov_y_deg), aspect);\n"], "uses ref"),
}


def tree_hash(path):
    h = hashlib.sha256()
    for base, dirs, files in sorted(os.walk(path)):
        dirs.sort()
        for f in sorted(files):
            p = os.path.join(base, f)
            h.update(os.path.relpath(p, path).encode())
            if not os.path.islink(p):
                h.update(open(p, "rb").read())
    return h.hexdigest()


def skip_unless_gradable(test):
    """Exits 77 (skip) where grade.sh cannot run: no working bubblewrap, or a student copy."""
    if not shutil.which("bwrap"):
        skip("bubblewrap (bwrap) missing: scripts/setup.sh installs it", test)
    probe = ["bwrap", "--unshare-all", "--ro-bind", "/usr", "/usr", "--symlink", "usr/bin", "/bin",
             "--symlink", "usr/lib", "/lib", "--symlink", "usr/lib64", "/lib64", "--proc", "/proc", "--", "/bin/true"]
    if os.geteuid() == 0:
        probe = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"] + probe
    if subprocess.run(probe, capture_output=True).returncode != 0:
        skip("bubblewrap cannot create its namespaces here (user namespaces disabled?)", test)
    if os.path.exists(os.path.join(ROOT, ".student-copy")):
        skip("this is a student copy: grading needs the instructors' repository", test)


def main():
    skip_unless_gradable("grading_lab1")
    tmp = tempfile.mkdtemp(prefix="grade-test-")
    os.chmod(tmp, 0o755)
    try:
        run(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def run(tmp):
    t0 = time.time()
    copy = os.path.join(tmp, "copy")
    subprocess.run(["bash", os.path.join(ROOT, "scripts/exercise.sh"), LAB, "--out", copy], check=True, capture_output=True)
    subs = os.path.join(tmp, "submissions")
    canary = os.path.join(tmp, "canary")
    os.makedirs(subs)
    os.makedirs(canary)
    open(os.path.join(canary, "keep.txt"), "w").write("the grader's machine: nothing may change this\n")
    os.chmod(canary, 0o777)  # writable by anyone: only the sandbox can keep the student's code out
    os.chmod(os.path.join(canary, "keep.txt"), 0o666)

    def make(name, solved=EXERCISES):
        d = os.path.join(subs, name)
        shutil.copytree(copy, d, symlinks=True)
        for e in solved:
            fill(d, e, solution(e))
        return d

    expected = {}  # student → (grades, notes that must appear)
    make("solved")
    expected["solved"] = ([1, 1, 1, 1, 1], [])
    make("partial", ["look_at", "projection"])
    expected["partial"] = ([1, 0, 1, 0, 0], [])
    d = make("no_compile")
    fill(d, "transform", ["    return this is not C++;\n"])
    expected["no_compile"] = ([1, 0, 1, 1, 1], ["did not compile: transform"])
    d = make("loop_cpp")
    fill(d, "transform", ["    { volatile bool spin = true; while (spin) {} }\n"] + solution("transform"))
    expected["loop_cpp"] = ([1, 0, 1, 1, 1], ["did not finish (a crash or the time limit): transform"])
    # Writes everywhere it can think of: the canary, another student's code, the grader, the
    # repository's tests; and deletes with a shell. All inside look_at, which stays right.
    d = make("escape")
    other = os.path.join(subs, "solved", CAMERA)
    targets = [os.path.join(canary, "keep.txt"), os.path.join(canary, "new.txt"), other,
               os.path.join(ROOT, "scripts/grade/grade.py"), os.path.join(ROOT, "tests/graded_exercises.txt"), "/tmp/grade-escaped"]
    attack = ["    static bool once = false;\n", "    if (!once) {\n", "        once = true;\n"] + \
             [f"        if (FILE* f = std::fopen(\"{t}\", \"a\")) {{ std::fputs(\"pwned\\n\", f); std::fclose(f); }}\n" for t in targets] + \
             [f"        if (std::system(\"rm -rf {canary} {os.path.join(subs, 'partial')}; echo pwned > {canary}/sh.txt\")) {{}}\n", "    }\n"]
    fill(d, "look_at", attack + solution("look_at"))
    expected["escape"] = ([0, 1, 1, 1, 1], ["flagged, 0, for the instructor to look at: look_at (calls fopen"])
    # Every check removed from the tests, the graded rows emptied, the exercises left stubbed.
    d = make("tampered", [])
    for f in ("tests/test_camera.cpp", "tests/test_lab1_render.cpp"):
        open(os.path.join(d, f), "w").write("#include <gtest/gtest.h>\nTEST(LookAt, Passes) {}\n")
    open(os.path.join(d, "tests/graded_exercises.txt"), "w").write("# nothing\n")
    expected["tampered"] = ([0, 0, 0, 0, 0], ["changed outside the exercises (ignored): 3 file(s)"])
    d = make("no_markers")
    path = os.path.join(d, CAMERA)
    lines = open(path).read().splitlines(keepends=True)
    s, e = region(lines, "look_at")
    del lines[e]
    del lines[s]
    open(path, "w").write("".join(lines))
    expected["no_markers"] = ([0, 1, 1, 1, 1], ["markers deleted (not done): look_at"])
    # Archives: a .tgz with the copy in one folder, a .zip with it at the top (and "bombs" below,
    # a .tar.gz with it at the top).
    d = make("packed_tgz_src")
    with tarfile.open(os.path.join(subs, "packed_tgz.tgz"), "w:gz") as t:
        t.add(d, arcname="my-lab1")
    shutil.rmtree(d)
    expected["packed_tgz"] = ([1, 1, 1, 1, 1], [])
    d = make("packed_zip_src", ["look_at", "transform", "projection"])
    with zipfile.ZipFile(os.path.join(subs, "packed_zip.zip"), "w") as z:
        for base, _, files in os.walk(d):
            for f in files:
                z.write(os.path.join(base, f), os.path.relpath(os.path.join(base, f), d))
    shutil.rmtree(d)
    expected["packed_zip"] = ([1, 1, 1, 0, 0], [])
    # Three regions that attack the machine, each followed by the solution: look_at crashes (a
    # null write), projection allocates without end (and touches what it gets), transform forks
    # until it can't (a shell starting sleeps) and leaves its children waiting. Each must cost at most its own point, with a
    # reason; the forks are the sandbox user's alone (a user per job: RLIMIT_NPROC), so the jobs
    # running beside it still start their threads and processes. Whether transform's own tests
    # survive its children is not asserted (its threads count against the same limit, and spawning
    # them races the test's time limit); the other regions' credit and the run finishing are.
    d = make("bombs_src")
    fill(d, "look_at", ["    { static volatile int* nowhere = nullptr; *nowhere = 1; }\n"] + solution("look_at"))
    # (only what the file already includes: lines added outside a region are not graded)
    fill(d, "projection", ["    for (;;) { volatile char* hog = new char[std::size_t(64) << 20];\n",
                           "               for (std::size_t i = 0; i < (std::size_t(64) << 20); i += 4096) hog[i] = 1; }\n"] +
         solution("projection"))
    fill(d, "transform", ["    static bool forked = false;\n", "    if (!forked) {\n", "        forked = true;\n",
                          "        if (std::system(\"i=0; while [ $i -lt 100000 ]; do sleep 1000 & i=$((i + 1)); done\")) {}\n",
                          "    }\n"] + solution("transform"))
    with tarfile.open(os.path.join(subs, "bombs.tar.gz"), "w:gz") as t:
        for f in sorted(os.listdir(d)):
            t.add(os.path.join(d, f), arcname=f)
    shutil.rmtree(d)
    expected["bombs"] = ([0, 0, 0, 1, 1], ["did not finish (a crash or the time limit): ", "transform (calls system"])
    os.makedirs(os.path.join(subs, "empty"))
    expected["empty"] = ([0, 0, 0, 0, 0], ["empty"])
    d = make("forged", [])
    for n, (body, _) in FORGERIES.items():
        fill(d, n, body)
    expected["forged"] = ([0, 0, 0, 0, 0], ["flagged, 0, for the instructor to look at: "])
    print(f"grading_lab1: {len(expected)} submissions written in {time.time() - t0:.0f} s")

    before = {"canary": tree_hash(canary), "submissions": tree_hash(subs),
              "grade.py": tree_hash(os.path.join(ROOT, "scripts/grade")),
              "graded_exercises.txt": hashlib.sha256(open(os.path.join(ROOT, "tests/graded_exercises.txt"), "rb").read()).hexdigest()}
    out = os.path.join(tmp, "out")
    t1 = time.time()
    r = subprocess.run(["bash", os.path.join(ROOT, "scripts/grade.sh"), "1", subs, "--out", out], capture_output=True, text=True)
    took = time.time() - t1
    sys.stdout.write(r.stderr[-6000:])
    if r.returncode != 0:
        fail(f"grade.sh exited {r.returncode}")
    print(f"grading_lab1: graded {len(expected)} submissions in {took:.0f} s")
    after = {"canary": tree_hash(canary), "submissions": tree_hash(subs),
             "grade.py": tree_hash(os.path.join(ROOT, "scripts/grade")),
             "graded_exercises.txt": hashlib.sha256(open(os.path.join(ROOT, "tests/graded_exercises.txt"), "rb").read()).hexdigest()}
    problems = [f"{k} changed during grading" for k in before if before[k] != after[k]]
    if os.path.exists("/tmp/grade-escaped"):
        problems.append("/tmp/grade-escaped was written (the sandbox's /tmp is not private)")

    with open(os.path.join(out, "grades.csv"), newline="") as f:
        rows = list(csv.reader(f))
    # The columns follow exercise.sh --list (the lab's README order); cells are read by name.
    if rows[0][0] != "student" or sorted(rows[0][1:-2]) != sorted(EXERCISES) or rows[0][-2:] != ["score", "notes"]:
        problems.append(f"grades.csv header {rows[0]}")
    column = {n: rows[0].index(n) if n in rows[0] else 1 + i for i, n in enumerate(EXERCISES)}
    got = {row[0]: row for row in rows[1:]}
    if sorted(got) != sorted(expected) or [row[0] for row in rows[1:]] != sorted(expected):
        problems.append(f"grades.csv students {list(got)} (expected, sorted: {sorted(expected)})")
    for name, (grades, notes) in sorted(expected.items()):
        row = got.get(name)
        if not row:
            continue
        cells = [int(row[column[n]]) for n in EXERCISES]
        grades = [c if g is None else g for c, g in zip(cells, grades)]  # None: not asserted
        if cells != grades or int(row[-2]) != sum(grades):
            problems.append(f"{name}: grades {cells} score {row[-2]}, expected {grades} ({sum(grades)}); notes: {row[-1]}")
        for n in notes:
            if n not in row[-1]:
                problems.append(f"{name}: notes lack '{n}': {row[-1]}")
        # the exercises that did not finish, in the lab's order: every 0 that a crash or a hang made
        stopped = re.search(r"did not finish \(a crash or the time limit\): ([\w ]+)", row[-1])
        if name == "bombs" and not (stopped and {"look_at", "projection"} <= set(stopped.group(1).split())):
            problems.append(f"{name}: look_at and projection not among the exercises that did not finish: {row[-1]}")
        if name not in ("tampered", "no_markers") and "changed outside" in row[-1]:
            problems.append(f"{name}: notes say changed outside: {row[-1]}")
        res = json.load(open(os.path.join(out, "students", name, "results.json")))
        if res["score"] != sum(grades) or [{t["name"]: t["score"] for t in res["tests"]}.get(n) for n in EXERCISES] != grades or \
                any(set(t) < {"name", "score", "max_score", "output"} or not t["output"] for t in res["tests"]):
            problems.append(f"{name}: results.json {json.dumps(res)[:300]}")
        for t in res["tests"]:
            g = grades[EXERCISES.index(t["name"])] if t["name"] in EXERCISES else 1
            if not g and t["name"] not in t["output"]:
                problems.append(f"{name}: the message for {t['name']} does not name it: {t['output'][:200]}")
        if not os.path.isfile(os.path.join(out, "students", name, "report.html")):
            problems.append(f"{name}: no report.html")
    index = open(os.path.join(out, "index.html")).read()
    for name in expected:
        if f'href="students/{name}/report.html"' not in index:
            problems.append(f"index.html has no link to {name}'s report")
    # a failing render test's picture reaches the report (transform stubbed: Lab1Render.TransformCameraYawPitchRoll)
    report = open(os.path.join(out, "students", "partial", "report.html")).read()
    pics = re.findall(r'<img src="([^"]+)"', report)
    if not pics or not all(os.path.isfile(os.path.join(out, "students", "partial", p)) for p in pics):
        problems.append(f"partial/report.html: no expected|actual|difference picture ({pics})")
    # each exercise at its marker's line in the student's own file (a stub is shorter than the
    # solution: the instructors' line of a later exercise in the same file would point elsewhere)
    for n in EXERCISES:
        at = f"{FILE_OF[n]}:{region(open(os.path.join(subs, 'partial', FILE_OF[n])).read().splitlines(), n)[0] + 1}<"
        if at not in report:
            problems.append(f"partial/report.html does not place {n} at {at[:-1]}")
    if "http://" in index or "https://" in index or "http" in report.replace("https://", "").split("<body>")[0]:
        problems.append("the pages make external requests")

    # each forgery flagged for its own reason, in the message that the student's report shows
    forged = {t["name"]: t["output"] for t in json.load(open(os.path.join(out, "students", "forged", "results.json")))["tests"]}
    for n, (_, word) in FORGERIES.items():
        if "is not graded: its region" not in forged.get(n, "") or word not in forged.get(n, ""):
            problems.append(f"forged: {n} is not flagged for `{word}`: {forged.get(n, '')[:300]}")
    # The same forgeries with the region check off: the judge alone gives each 0, and the honest
    # submission beside them keeps its grade. Each forgery builds (it is the judge that refuses it),
    # but the oracle's call, which the lab's own program cannot link.
    only = os.path.join(tmp, "forgeries")
    os.makedirs(only)
    shutil.copytree(os.path.join(subs, "forged"), os.path.join(only, "forged"), symlinks=True)
    shutil.copytree(os.path.join(subs, "solved"), os.path.join(only, "solved"), symlinks=True)
    out3 = os.path.join(tmp, "out3")
    r3 = subprocess.run(["bash", os.path.join(ROOT, "scripts/grade.sh"), "1", only, "--out", out3, "--no-region-check"],
                        capture_output=True, text=True)
    if r3.returncode != 0:
        problems.append(f"grading the forgeries with --no-region-check exited {r3.returncode}: {r3.stderr[-800:]}")
    else:
        for who, want in (("forged", 0), ("solved", 1)):
            res = json.load(open(os.path.join(out3, "students", who, "results.json")))
            for t in res["tests"]:
                if t["score"] != want:
                    problems.append(f"--no-region-check: {who} {t['name']} scored {t['score']}, expected {want}: {t['output'][:300]}")
                if who == "forged" and t["name"] != "projection" and "does not compile" in t["output"]:
                    problems.append(f"--no-region-check: the {t['name']} forgery did not build, so it proves nothing: {t['output'][:300]}")
        print(f"grading_lab1: the forgeries with the region check off: all 0, the honest submission 5 of 5")

    # Determinism, on a part of the class (grading all of it again would double this test): the
    # same submissions graded again give the same rows of grades.csv, byte for byte.
    again = os.path.join(tmp, "again")
    os.makedirs(again)
    for entry in ("partial", "no_compile", "tampered", "packed_zip.zip"):
        src = os.path.join(subs, entry)
        (shutil.copytree if os.path.isdir(src) else shutil.copyfile)(src, os.path.join(again, entry))
    out2 = os.path.join(tmp, "out2")
    r2 = subprocess.run(["bash", os.path.join(ROOT, "scripts/grade.sh"), "1", again, "--out", out2], capture_output=True, text=True)
    if r2.returncode != 0:
        problems.append(f"the regrade exited {r2.returncode}: {r2.stderr[-500:]}")
    else:
        names = {"partial", "no_compile", "tampered", "packed_zip"}
        rows = lambda o: [l for l in open(os.path.join(o, "grades.csv"), "rb").read().splitlines()
                          if l.split(b",")[0].decode() in names | {"student"}]
        if rows(out) != rows(out2):
            problems.append("regrading gave different rows: " +
                            " | ".join(f"{a!r} -> {b!r}" for a, b in zip(rows(out), rows(out2)) if a != b)[:1500])
    for p in problems:
        print("FAIL", p)
    if problems:
        print(open(os.path.join(out, "grades.csv")).read())
        sys.exit(1)
    print(f"grading_lab1: every grade as expected, nothing outside changed, regrade identical ({time.time() - t0:.0f} s in all)")


if __name__ == "__main__":
    main()
