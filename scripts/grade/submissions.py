"""submissions.py — a student's submission: opened (a folder, or an archive unpacked with bounds),
its exercises' regions read (only those count), and the files it changed outside them listed.
"""
import os
import re
import shutil
import stat
import tarfile
import zipfile

import region_check
from model import find_region, masked, split_lines

IGNORED_TOP = re.compile(r"^(build[^/]*|out|student|\.git|\.cache|\.vscode|\.idea)$")
EXT_ARCHIVE = (".tar.gz", ".tgz", ".zip")
MAX_EXTRACT_BYTES = 512 << 20
MAX_EXTRACT_FILES = 20000
MAX_REGION_BYTES = 256 << 10


class Submission:
    def __init__(self, name):
        self.name = name
        self.notes = []
        self.grades = {}
        self.messages = {}
        self.isolated = {}   # exercise → variant result
        self.whole = None
        self.outside = []
        self.region = {}     # exercise → "code" | "missing" | "stub" | "solution"
        self.fatal = None
        self.kept = {}       # (exercise, test) → pictures next to the report
        self.code = {}       # exercise → the student's region, as handed in
        self.flagged = {}    # exercise → why its region is not graded (region_check.py)
        self.line = {}       # exercise → the line of its marker in the student's own file
        self.bodies = {}     # exercise → the region's lines, as graded


def student_name(entry):
    n = os.path.basename(entry.rstrip("/"))
    for ext in EXT_ARCHIVE:
        if n.lower().endswith(ext):
            return n[: -len(ext)]
    return n


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


def read_regions(s, root, exercises, trust_regions=False):
    """Reads each exercise's region from the student's copy at root into s: bodies, code, line,
    region ("code", "stub", "solution" or "missing") and flagged (region_check.py's reasons)."""
    strip = lambda ls: [l.rstrip() for l in ls if l.strip()]
    for e in exercises:
        n = e["name"]
        text = read_student_file(root, e["file"])
        lines = split_lines(text) if text is not None else []
        reg = find_region(lines, n) if text is not None else None
        if reg is None:
            s.region[n] = "missing"
            continue
        body = lines[reg[0] + 1:reg[1]]
        if sum(map(len, body)) > MAX_REGION_BYTES:
            s.region[n] = "missing"
            s.notes.append(f"{n}: region over 256 KiB, ignored")
            continue
        if body and not body[-1].endswith("\n"):
            body[-1] += "\n"
        s.bodies[n] = body
        s.line[n] = reg[0] + 1
        s.code[n] = "".join(body)
        s.region[n] = ("solution" if strip(body) == strip(e["solution"]) else
                       "stub" if strip(body) == strip(e["stub"]) or strip(body) == strip(e["stub_lines"]) else "code")
        why_not = None if trust_regions else region_check.problems("".join(body))
        if why_not:
            s.flagged[n] = why_not


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
    """The files of the student's copy root that differ from the handed-out copy outside the
    exercises' regions (added, deleted, a link, or other text)."""
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
