"""model.py — the course as the grader sees it: the repository, its labs, their exercises and
tests/graded_exercises.txt, all read through the one model of an exercise,
scripts/course/exercises.py. No part of the grader reads a marker itself.
"""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from course import exercises as course  # noqa: E402

find_region = course.find_region    # (lines, name) → (marker index, END index) or None
masked = course.masked              # a file's text without its regions' code
stub_text = course.stub_text        # (text, names) → the text with those exercises cut to their stubs
graded_table = course.graded_table  # tests/graded_exercises.txt: .rows_of(e), .prerequisites


def die(msg, code=2):
    print(f"grade: {msg}", file=sys.stderr)
    sys.exit(code)


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def split_lines(text):
    return text.splitlines(keepends=True)


def resolve_lab(want):
    """lab1_camera for 1, lab1 or lab1_camera; exit 2 naming the labs for anything else."""
    try:
        return course.resolve_lab(want, ROOT)
    except LookupError as ex:
        die(str(ex))


def exercises_of(lab, root=ROOT):
    """lab's exercises in the lab's order, as dicts the grader adds to: name, file, line, checked
    (its "Checked by" patterns), stub_lines (its `// STUB:` lines as the file has them), stub (the
    code they stand for) and solution (the region's lines but the STUB lines), lines with their "\\n"."""
    out = []
    for e in course.exercises_of(lab, root):
        lines = course.split_lines(course.read_text(os.path.join(root, e.file)))
        out.append({"name": e.name, "file": e.file, "line": e.line, "checked": list(e.tests),
                    "stub_lines": [lines[k - 1] + "\n" for k, _ in e.stub_code],
                    "stub": [s + "\n" for s in e.stub],
                    "solution": [text + "\n" for _, text in e.solution]})
    return out


def is_student_copy(lab, root=ROOT):
    """A lab of a student copy: the copy's .student-copy file, or one of its markers is a TODO (its
    code cut out; a copy whose student has solved every exercise still has the file)."""
    return os.path.exists(os.path.join(root, ".student-copy")) or any(e.todo for e in course.markers_in(lab, root))


def write_manifest(path, root, copy_root):
    """The exercises' manifest the hints read (tests/exercise_hints.cpp, $LAB_EXERCISE_MANIFEST)
    for a variant: root's table and stubs, the lab folders copy_root has read from copy_root."""
    data = course.manifest_text(root, copy_root).encode("utf-8", "surrogateescape")
    with open(path, "wb") as f:
        f.write(data)
    return path

