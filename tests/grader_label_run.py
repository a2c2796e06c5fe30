#!/usr/bin/env python3
"""grader_label_run.py — one lab's whole CTest label run against the grader's build of a stubbed lab.

    python3 tests/grader_label_run.py BUILD LAB GRADER_DIR OUT [--jobs N] [--only NAME,...]

scripts/exercise.sh --prove (CTest grader_labN) builds the lab with some exercises stubbed into
GRADER_DIR (bin/: the lab's binary and the unit tests compiled from its files; shaders/LAB/: its
compiled shaders; src/: the stubbed sources) and runs this: every test of label labN that
`ctest --show-only=json-v1` lists in BUILD (its gtests, render tests, smoke runs, windows, soaks,
random scenes, gallery; not the grader itself), each with its own command, environment, working
folder, timeout and skip code, but seeing the stubbed lab:
  - the gtests' runners read LAB_EXE_DIR, LAB_SHADER_DIR (tests/lab_runner.h) and the hints read
    LAB_EXERCISE_SOURCES (tests/exercise_hints.cpp);
  - a unit test compiled from the lab's files runs as GRADER_DIR/bin's build of it;
  - every other command sees BUILD through GRADER_DIR/build-LAB: links to BUILD's files, but the lab's
    binary there is a script that runs GRADER_DIR/bin's with --dev-shader-dir (same process).
The proof runs the label once per exercise, so two heavy tests run shorter there: the random scenes
5 seeds a shard instead of 40-50 (--count 5; the regression seeds all: a stub that breaks them
breaks the first seeds), and a soak 30 s instead of 1-2 min, its crash, hang and validation checks
kept but not its memory gate (SOAK_MEMORY_GATE=0: a stub changes what is drawn, not what is kept;
the label's own soak gates memory).
Writes OUT/results.tsv (name, passed|failed|skipped, the exercise its message names first or
"done" or "-", seconds) and OUT/logs/NAME.log. --only: those tests alone (names or fnmatch patterns). Exit 0 (results in the file).
"""
import concurrent.futures
import json
import fnmatch
import os
import re
import shutil
import subprocess
import sys
import time

RANDOM_SEEDS = 5  # seeds per random-scene shard in the proof (the label runs 40-50)
SOAK_MINUTES = "0.5"  # a soak's length in the proof (the label's: 1, lab 4's 2)


def usage(code):
    print(__doc__.strip())
    sys.exit(code)


def tests_of(build, short):
    """The label's tests, without the graders and without the fixture that brings BUILD up to date
    (build_is_current: the prover builds the stubbed lab itself, BUILD is the solved one)."""
    out = subprocess.run(["ctest", "--test-dir", build, "--show-only=json-v1", "-L", "^%s$" % short,
                          "-E", "^grader_", "-FA", "^lab_build$"], capture_output=True, text=True, check=True).stdout
    return json.loads(out)["tests"]


def props(test):
    return {p["name"]: p["value"] for p in test.get("properties", [])}


def fake_build(build, lab, grader):
    """GRADER_DIR/build-LAB: a link to every entry of BUILD, but BUILD/LAB/LAB (the lab's binary) is a
    script that runs the stubbed one with its stubbed shaders."""
    fake = os.path.join(grader, "build-" + lab)
    if os.path.isdir(fake) and not os.path.islink(fake):
        shutil.rmtree(fake)  # links and the script only: rmtree removes links, never what they point to
    os.makedirs(os.path.join(fake, lab))
    for entry in os.listdir(build):
        link = os.path.join(fake, entry)
        if entry in (lab, "shaders", "grader"):
            continue
        os.symlink(os.path.join(build, entry), link)
    for entry in os.listdir(os.path.join(build, lab)):
        link = os.path.join(fake, lab, entry)
        if entry != lab:
            os.symlink(os.path.join(build, lab, entry), link)
    # Its shaders too (make_gallery.sh passes --dev-shader-dir BUILD/shaders/LAB itself).
    shaders = os.path.join(fake, "shaders")
    os.makedirs(shaders)
    for entry in os.listdir(os.path.join(build, "shaders")):
        link = os.path.join(shaders, entry)
        os.symlink(os.path.join(grader, "shaders", lab) if entry == lab else os.path.join(build, "shaders", entry), link)
    exe = os.path.join(fake, lab, lab)
    with open(exe, "w") as f:
        f.write("#!/bin/sh\nexec '%s' --dev-shader-dir '%s' \"$@\"\n" % (
            os.path.join(grader, "bin", lab), os.path.join(grader, "shaders", lab)))
    os.chmod(exe, 0o755)
    return fake


def to_fake(arg, build, fake):
    """BUILD in a command's argument (a path, --build BUILD, LAB_BUILD_DIR=BUILD) → the fake build."""
    if "/grader/" in arg:
        return arg
    return re.sub(r"(^|=)" + re.escape(build) + r"(?=/|$)", lambda m: m.group(1) + fake, arg)


NEEDS = re.compile(r"^\[ exercise \] this test needs `([a-z0-9_]+)`", re.M)
DONE = re.compile(r"^\[ exercise \] (every exercise|the exercise) this test needs is done", re.M)


def main(argv):
    if any(a in ("-h", "--help") for a in argv):
        usage(0)
    jobs, only, pos = 2, None, []
    i = 0
    while i < len(argv):
        if argv[i] == "--jobs" and i + 1 < len(argv):
            jobs, i = int(argv[i + 1]), i + 2
        elif argv[i] == "--only" and i + 1 < len(argv):
            only, i = set(filter(None, argv[i + 1].split(","))), i + 2
        else:
            pos.append(argv[i])
            i += 1
    if len(pos) != 4:
        print("grader_label_run.py: usage: grader_label_run.py BUILD LAB GRADER_DIR OUT [--jobs N] [--only NAME,...]",
              file=sys.stderr)
        sys.exit(2)
    build, lab, grader, out = (os.path.abspath(p) if k != 1 else p for k, p in enumerate(pos))
    short = re.match(r"lab[0-9]+", lab).group(0)
    fake = fake_build(build, lab, grader)
    graded_bin = os.path.join(grader, "bin")
    graded = {n for n in os.listdir(graded_bin)} if os.path.isdir(graded_bin) else set()
    os.makedirs(os.path.join(out, "logs"), exist_ok=True)

    todo = []
    for t in tests_of(build, short):
        # A parameterized gtest's CTest name ends in "  # GetParam() = …": its gtest name is before.
        t["name"] = t["name"].split("  # ")[0]
        # --only: names or fnmatch patterns (a graded_exercises.txt row's, "Lab4Shadows.*")
        if only is not None and not any(fnmatch.fnmatchcase(t["name"], pat) for pat in only):
            continue
        p = props(t)
        cmd = list(t.get("command") or [])
        if not cmd or p.get("DISABLED"):
            continue
        # A unit test compiled from the lab's files: the grader's build of it. Every other path into
        # BUILD: through the fake build (the lab's binary there is the stubbed one).
        if os.path.basename(cmd[0]) in graded and os.path.dirname(cmd[0]).startswith(build):
            cmd[0] = os.path.join(graded_bin, os.path.basename(cmd[0]))
        cmd = [to_fake(a, build, fake) for a in cmd]
        if t["name"].startswith(short + "_random_scenes") and "--count" in cmd:
            k = cmd.index("--count") + 1
            cmd[k] = str(min(int(cmd[k]), RANDOM_SEEDS))
        env = dict(os.environ)
        for kv in p.get("ENVIRONMENT", []):
            k, _, v = kv.partition("=")
            env[k] = v.replace(build, fake) if k == "LAB_BUILD_DIR" else v
        soak = [k for k, a in enumerate(cmd) if a.endswith("/bench/soak.py")]
        if soak and t["name"].endswith("_soak"):
            cmd[soak[0] + 1] = SOAK_MINUTES
            env.update(SOAK_MEMORY_GATE="0", SOAK_MIN_SAMPLES="1")
        env.update(LAB_EXE_DIR=graded_bin, LAB_SHADER_DIR=os.path.join(grader, "shaders", lab),
                   LAB_EXERCISE_SOURCES=os.path.join(grader, "src"),
                   LAB_TEST_OUTPUT=os.path.join(out, "test_output", re.sub(r"[^A-Za-z0-9_.-]", "_", t["name"])))
        todo.append((t["name"], cmd, env, p))
    # The long ones first (random scenes, soaks), so that two run side by side to the end.
    todo.sort(key=lambda x: -float(x[3].get("TIMEOUT", 300)))

    def run(item):
        name, cmd, env, p = item
        start = time.time()
        try:
            r = subprocess.run(cmd, cwd=p.get("WORKING_DIRECTORY") or build, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, timeout=float(p.get("TIMEOUT", 300)))
            code, text = r.returncode, r.stdout.decode(errors="replace")
        except subprocess.TimeoutExpired as e:
            code, text = -1, (e.stdout or b"").decode(errors="replace") + "\n(timed out)\n"
        seconds = time.time() - start
        passed = code == 0
        if "PASS_REGULAR_EXPRESSION" in p:
            passed = any(re.search(rx, text) for rx in p["PASS_REGULAR_EXPRESSION"])
        if p.get("WILL_FAIL"):
            passed = not passed
        state = "passed" if passed else "failed"
        if code != 0 and p.get("SKIP_RETURN_CODE") is not None and code == int(p["SKIP_RETURN_CODE"]):
            state = "skipped"
        m = NEEDS.search(text)
        named = m.group(1) if m else ("done" if DONE.search(text) else "-")
        with open(os.path.join(out, "logs", re.sub(r"[^A-Za-z0-9_.-]", "_", name) + ".log"), "w") as f:
            f.write(" ".join(cmd) + "\n" + text)
        return name, state, named, seconds

    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        results = list(pool.map(run, todo))
    with open(os.path.join(out, "results.tsv"), "w") as f:
        for name, state, named, seconds in sorted(results):
            f.write("%s\t%s\t%s\t%.1f\n" % (name, state, named, seconds))


if __name__ == "__main__":
    main(sys.argv[1:])
