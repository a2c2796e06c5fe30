#!/usr/bin/env python3
"""scripts_help.py — every script a person runs answers --help (CTest: scripts_help).

    python3 tests/scripts_help.py [SOURCE_DIR]     default: the folder above tests/

The scripts: scripts/*.sh|*.py, bench/*.sh|*.py and the helper scripts at the top of tests/
(*.sh, *.py). Each one, run with --help (and -h) from an empty temporary folder, must exit 0
within 20 s, print its usage on stdout (text that names the script), and print no stack trace
(a Python traceback, a Node.js "at file:line:col" frame, a bash "line N:" error).

Running a script that ignores --help would do its real work (install packages, build, start a
benchmark), so a script is only run when its code mentions --help (bash: a line that is not a
comment; Python: the same, or argparse, which answers --help by itself); one that does not fails
here unrun, named with its path.
"""
import os
import re
import subprocess
import sys
import tempfile

TRACES = [
    (re.compile(r"Traceback \(most recent call last\)"), "a Python traceback"),
    (re.compile(r"^\s+at .+:\d+:\d+\)?$", re.M), "a Node.js stack frame"),
    (re.compile(r"node:internal"), "a Node.js stack frame"),
    (re.compile(r": line \d+: "), "a bash error"),
    (re.compile(r"unbound variable|command not found"), "a bash error"),
]


def scripts(root):
    found = []
    for folder in ("scripts", "bench", "tests"):
        for name in sorted(os.listdir(os.path.join(root, folder))):
            path = os.path.join(root, folder, name)
            if os.path.isfile(path) and name.endswith((".sh", ".py")):
                found.append(os.path.join(folder, name))
    return found


def mentions_help(path):
    """Whether the script's code (not its comments) handles --help: the gate before running it."""
    python = path.endswith(".py")
    for line in open(path, encoding="utf-8"):
        if line.lstrip().startswith("#"):
            continue
        if "--help" in line or (python and re.search(r"\bargparse\b|\bunittest\.main\b", line)):
            return True
    return False


def check(root, rel, flag, tmp):
    path = os.path.join(root, rel)
    cmd = (["bash", path] if rel.endswith(".sh") else [sys.executable, path]) + [flag]
    env = dict(os.environ, LAB_BUILD_DIR=os.path.join(tmp, "no-build"))
    try:
        run = subprocess.run(cmd, cwd=tmp, env=env, capture_output=True, text=True, timeout=20,
                             stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return "did not exit within 20 s"
    out = run.stdout + run.stderr
    for pattern, what in TRACES:
        if pattern.search(out):
            return f"printed {what}:\n{out.strip()}"
    if run.returncode != 0:
        return f"exit code {run.returncode}:\n{out.strip()}"
    if not run.stdout.strip():
        return "printed no usage on stdout"
    stem = os.path.splitext(os.path.basename(rel))[0]
    if stem not in run.stdout:
        return f"its usage does not name the script ({stem}):\n{run.stdout.strip()}"
    return None


def main(argv):
    if argv[1:2] in (["-h"], ["--help"]):
        print(__doc__.strip())
        return 0
    root = os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    if not os.path.isdir(os.path.join(root, "scripts")):
        print(f"scripts_help: {root}: no scripts/ folder here", file=sys.stderr)
        return 2
    failures = 0
    checked = scripts(root)
    with tempfile.TemporaryDirectory() as tmp:
        for rel in checked:
            if not mentions_help(os.path.join(root, rel)):
                print(f"FAIL {rel}: does not handle --help (no -h/--help in its code; not run)")
                failures += 1
                continue
            for flag in ("--help", "-h"):
                problem = check(root, rel, flag, tmp)
                if problem:
                    print(f"FAIL {rel} {flag}: {problem}")
                    failures += 1
                    break
            if os.listdir(tmp):
                print(f"FAIL {rel}: --help wrote into its working folder: {sorted(os.listdir(tmp))}")
                failures += 1
                for name in os.listdir(tmp):
                    subprocess.run(["rm", "-rf", os.path.join(tmp, name)], check=False)
    print(f"scripts_help: {len(checked) - failures} of {len(checked)} scripts answer --help and -h")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
