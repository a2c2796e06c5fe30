"""course.exercises — the labs' exercises, read from their markers, and tests/graded_exercises.txt.

The one reader of both: scripts/exercise.py (the student copies, --list, the manifest), the answer
checks (scripts/check_answers.py, scripts/comment_answers.py), the course site (through
`exercise.py --list --json`), the grader and the C++ hints (through the manifest, manifest()) and
tests/exercise_tools_agree.py all take the exercises from here.

In the labs' sources and shaders (lab<N>_*/ without README.md, shaders/lab<N>_*/) an exercise is
marked like this:

    // EXERCISE attenuation: the hint. Checked by Lab2Render.PointLights, Suite.*.
    // STUB: return 1.0;      (one or more STUB lines; "// STUB:" alone is an empty line)
    ...the lab's code, the solution...
    // END EXERCISE

A student copy has "// TODO EXERCISE name: …" and the stub code in place of the solution, without
STUB lines (the copy's .exercise-stubs file keeps them). The rules, each written once below:
  - a marker is "// EXERCISE name: " or "// TODO EXERCISE name: " anywhere on a line (MARKER_RE),
    the name of lower-case letters, digits and "_"; what follows is the hint, and a hint that ends
    in " Checked by A.B, C.*." names the tests written to check the exercise (GoogleTest names,
    fnmatch patterns), which are not part of the hint;
  - the exercise's code runs to the first "// END EXERCISE" line after the marker (END_RE: the
    words alone on their line); a STUB line (STUB_RE) is "// STUB: code" alone on its line, and
    what the stub keeps is its indentation and its code;
  - lines are compared without their trailing // comment and without any whitespace (bare());
  - an exercise belongs to the first lab that has it (lab 2 carries lab 1's camera.cpp with its
    markers: they are lab 1's exercises); a lab's own exercises come in the order of the
    "!order" rows of tests/graded_exercises.txt (the order the lab's README numbers them), then
    the ones no row names, by path and line.
tests/graded_exercises.txt holds, besides the "!order" rows, "PATTERN exercise…" rows (a test that
matches PATTERN needs those exercises) and "@exercise x…" rows (the exercise's own code needs x…);
graded_table() reads it.

Everything here is a function of the files it reads: no state is kept between calls. Files are
read as bytes decoded with UTF-8 (undecodable bytes kept as surrogate escapes) and split into lines
at "\\n" alone, as awk and std::getline split them.
"""
import fnmatch
import json
import os
import re
from dataclasses import dataclass
from types import MappingProxyType
from typing import Mapping, Optional, Tuple

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
"""The root of the project (or student copy) this file is in."""

GRADED = os.path.join("tests", "graded_exercises.txt")
STUBS = ".exercise-stubs"
STUBS_HEADER = "# written by scripts/exercise.sh: the stubs of this copy's exercises (tests/exercise_hints.cpp)"

MARKER_RE = re.compile(r"// (TODO )?EXERCISE ([a-z0-9_]+): ")
"""A marker, either form: group 1 is "TODO " in a student copy's form, group 2 the name."""
SOLVED_RE = re.compile(r"// EXERCISE ([a-z0-9_]+): ")
"""A marker of the complete project's form only (not "TODO EXERCISE")."""
END_RE = re.compile(r"^[ \t]*// END EXERCISE[ \t]*$")
STUB_RE = re.compile(r"^([ \t]*)// STUB:(?: (.*))?$")
"""A STUB line: group 1 its indentation, group 2 its code (None for "// STUB:" alone)."""
CHECKED_RE = re.compile(r" Checked by [^ ].*\.$")
"""The end of a hint that names the exercise's tests."""
SECTION_RE = re.compile(r"^# ---- lab ?(\d+)\b")
"""A section header of tests/graded_exercises.txt: the rows below it are lab N's."""

_SPACE = re.compile(r"[ \t\n\r\v\f]+")  # what C's isspace() calls whitespace


# ---------------------------------------------------------------- text
def read_text(path):
    """The text of a file, byte for byte (undecodable bytes as surrogate escapes, no newline
    translation)."""
    with open(path, encoding="utf-8", errors="surrogateescape", newline="") as f:
        return f.read()


def split_lines(text):
    """The lines of a text as awk reads them: split at "\\n", a last line without one counted."""
    lines = text.split("\n")
    if lines[-1] == "":
        lines.pop()
    return lines


def join_lines(lines):
    """Lines written back as awk prints them: each followed by "\\n"."""
    return "".join(line + "\n" for line in lines)


def bare(line):
    """A line without its trailing // comment and without any whitespace: how a stub and a
    solution line are compared (the rule of exercise.sh's awk and exercise_hints.cpp's bare())."""
    cut = line.find("//")
    return _SPACE.sub("", line if cut < 0 else line[:cut])


def byte_length(s):
    """The length of a string in bytes of UTF-8 (what awk counts under LC_ALL=C)."""
    return len(s.encode("utf-8", "surrogateescape"))


def byte_order(s):
    """A sort key that orders strings as `sort` does under LC_ALL=C: by their bytes."""
    return s.encode("utf-8", "surrogateescape")


# ---------------------------------------------------------------- the labs
def _version_key(name):
    """`sort -V` for lab folder names: digit runs compared as numbers (lab2_x before lab10_y)."""
    return [(0, int(p)) if p.isdigit() else (1, p) for p in re.split(r"(\d+)", name) if p]


def labs(root=ROOT):
    """The lab folders of root (lab<N>_* with a CMakeLists.txt), in `sort -V` order."""
    try:
        names = os.listdir(root)
    except OSError:
        return []
    return sorted((d for d in names if re.match(r"^lab[0-9].*_", d) and os.path.isfile(os.path.join(root, d, "CMakeLists.txt"))),
                  key=_version_key)


def resolve_lab(want, root=ROOT):
    """1 | lab1 | lab1_camera → "lab1_camera"; LookupError("no lab 'x' here; the labs are: …")."""
    found = labs(root)
    w = want if want.startswith("lab") else "lab" + want
    for lab in found:
        if lab == w or lab.split("_", 1)[0] == w:
            return lab
    raise LookupError(f"no lab '{want}' here; the labs are: {' '.join(found)}")


def lab_number(folder):
    """The N of lab folder lab<N>_…: "lab2_lighting" → 2 (also of a path in it, shaders/ too)."""
    if folder.startswith("shaders/"):
        folder = folder[len("shaders/"):]
    m = re.match(r"lab(\d+)", folder)
    if not m:
        raise ValueError(f"{folder} is not a lab folder")
    return int(m.group(1))


def lab_files(lab, root=ROOT):
    """The files of lab folder lab that may hold markers, relative to root, sorted: the folder's
    regular files but its README.md, and those of shaders/<lab>/."""
    files = []
    for top in (lab, os.path.join("shaders", lab)):
        for here, dirs, names in os.walk(os.path.join(root, top)):
            for name in names:
                path = os.path.join(here, name)
                if os.path.isfile(path) and not os.path.islink(path) and not (top == lab and name == "README.md"):
                    files.append(os.path.relpath(path, root).replace(os.sep, "/"))
    return sorted(files, key=byte_order)


# ---------------------------------------------------------------- regions of a file
def regions(lines):
    """Each marker of a file's lines: (name, start, end, todo), start the marker's index, end that
    of the first END EXERCISE line after it (None: there is none), todo whether it reads
    "// TODO EXERCISE". A marker inside another region is yielded too (find_region refuses it)."""
    for i, line in enumerate(lines):
        m = MARKER_RE.search(line)
        if not m:
            continue
        end = next((j for j in range(i + 1, len(lines)) if END_RE.match(lines[j])), None)
        yield m.group(2), i, end, m.group(1) is not None


def find_region(lines, name):
    """(start, end): the indexes of the marker (either form) and END lines of exercise name's
    first marker, or None when it has no END line or another marker comes before it."""
    for n, start, end, _ in regions(lines):
        if n != name:
            continue
        if end is None or any(MARKER_RE.search(lines[j]) for j in range(start + 1, end)):
            return None
        return start, end
    return None


def stub_text(text, names):
    """The text of a file with the exercises `names` cut out, as a student copy has it: each
    marker "// EXERCISE name: hint" becomes "// TODO EXERCISE name: hint", the code up to
    END EXERCISE is replaced by the STUB lines (their indentation and code, without "// STUB: "),
    and the END line stays. Only the complete form of a marker is cut (a TODO marker stays as it
    is). ValueError when a cut-out exercise has no END line."""
    names = set(names)
    out, stub, inside = [], [], False
    for line in split_lines(text):
        if not inside:
            m = SOLVED_RE.search(line)
            if m and m.group(1) in names:
                inside, stub = True, []
                out.append(line.replace("// EXERCISE ", "// TODO EXERCISE ", 1))
                continue
            out.append(line)
            continue
        s = STUB_RE.match(line)
        if s:
            stub.append(s.group(1) + (s.group(2) or ""))
        elif END_RE.match(line):
            out.extend(stub)
            out.append(line)
            inside = False
        # else: the lab's code, which the student writes
    if inside:
        raise ValueError("unterminated EXERCISE")
    return join_lines(out)


def masked(text):
    """A file's text without its exercise regions' code, each marker in the complete form: what
    stays the same whatever a student writes in the regions (the grader compares it)."""
    out, inside = [], False
    for line in text.splitlines(keepends=True):
        if MARKER_RE.search(line):
            out.append(line.replace("// TODO EXERCISE ", "// EXERCISE "))
            inside = True
        elif inside and END_RE.match(line):
            out.append(line)
            inside = False
        elif not inside:
            out.append(line)
    return "".join(out)


# ---------------------------------------------------------------- exercises
@dataclass(frozen=True)
class Exercise:
    """One marker of one file, with what its region holds."""
    name: str
    lab: str                 # the lab folder the file is in (lab2_lighting)
    file: str                # relative to the root
    line: int                # the marker's line, 1-based
    end: Optional[int]       # the END EXERCISE line, 1-based (None: there is none)
    hint: str                # the text after "name: ", without " Checked by …."
    tests: Tuple[str, ...]   # the Checked-by patterns
    stub: Tuple[str, ...]    # the STUB lines as a copy has them: indentation and code
    stub_code: Tuple[Tuple[int, str], ...]  # (line, code after "// STUB: ") of each STUB line
    solution: Tuple[Tuple[int, str], ...]   # (line, text) between marker and END, STUB lines excluded
    todo: bool               # the marker reads "// TODO EXERCISE"

    @property
    def number(self):
        """The lab's number (2 for lab2_lighting)."""
        return lab_number(self.lab)

    def listing(self):
        """What `exercise.py --list --json` gives of it."""
        return {"name": self.name, "lab": self.lab, "file": self.file, "line": self.line,
                "hint": self.hint, "tests": list(self.tests)}


def _parse(lines, lab, rel):
    """The exercises of one file's lines (every marker, in line order)."""
    found = []
    for name, start, end, todo in regions(lines):
        marker = lines[start]
        hint = marker[MARKER_RE.search(marker).end():]
        tests = ()
        checked = CHECKED_RE.search(hint)
        if checked:
            tests = tuple(hint[checked.start() + len(" Checked by "):-1].replace(",", " ").split())
            hint = hint[:checked.start()]
        stub, stub_code, solution = [], [], []
        for k in range(start + 1, len(lines) if end is None else end):
            s = STUB_RE.match(lines[k])
            if s:
                stub.append(s.group(1) + (s.group(2) or ""))
                stub_code.append((k + 1, s.group(2) or ""))
            else:
                solution.append((k + 1, lines[k]))
        found.append(Exercise(name, lab, rel, start + 1, None if end is None else end + 1, hint, tests,
                              tuple(stub), tuple(stub_code), tuple(solution), todo))
    return found


def scan_file(rel, root=ROOT, lab=None):
    """Every marker of file rel (relative to root), in line order; lab: its lab folder (default:
    the one its path names)."""
    if lab is None:
        parts = rel.split("/")
        lab = parts[1] if parts[0] == "shaders" else parts[0]
    return _parse(split_lines(read_text(os.path.join(root, rel))), lab, rel)


def markers_in(lab, root=ROOT):
    """Every marker of lab folder lab (its folder and shader folder), by path and line: the lab's
    own exercises and those it carries from earlier labs."""
    return [e for rel in lab_files(lab, root) for e in scan_file(rel, root, lab)]


def _own(root, upto=None):
    """lab → its own exercises (ordered), for every lab of root up to lab upto."""
    ranks = graded_table(root).ranks
    earlier, own = set(), {}
    for lab in labs(root):
        markers = markers_in(lab, root)
        mine = [e for e in markers if e.name not in earlier]
        # The order: the "!order" rank, then path and line (markers_in's order; sorted is stable).
        own[lab] = sorted(mine, key=lambda e: ranks.get(e.name, 999999))
        earlier |= {e.name for e in markers}
        if lab == upto:
            break
    return own


def exercises_of(lab, root=ROOT):
    """The exercises of lab folder lab: its markers whose name no earlier lab has, in the order of
    tests/graded_exercises.txt's "!order" rows, then path and line (`exercise.py --list LAB`)."""
    return _own(root, lab).get(lab, [])


def all_exercises(root=ROOT):
    """Every lab's own exercises, lab by lab, each lab's in exercises_of's order."""
    return [e for mine in _own(root).values() for e in mine]


def labs_from(lab, root=ROOT, only=False):
    """Lab folder lab and every later one (only: lab alone); none when lab is not a lab of root."""
    found = labs(root)
    if lab not in found:
        return []
    return [lab] if only else found[found.index(lab):]


# ---------------------------------------------------------------- tests/graded_exercises.txt
@dataclass(frozen=True)
class Table:
    """tests/graded_exercises.txt: what each graded test needs besides the exercises it grades."""
    order: Mapping[str, Tuple[str, ...]]           # "lab1" → the "!order" names of its section
    rows: Tuple[Tuple[str, Tuple[str, ...]], ...]  # (test pattern, exercises), in the file's order
    prerequisites: Mapping[str, Tuple[str, ...]]   # "@e x y" rows: e → (x, y)
    ranks: Mapping[str, int]                       # exercise → its place in the "!order" rows (1…)

    def rows_of(self, exercise):
        """The patterns of the rows that list exercise."""
        return tuple(pattern for pattern, names in self.rows if exercise in names)

    def needs(self, test):
        """The exercises the rows whose pattern matches test (fnmatch, as the C++ hints match)
        list, in the rows' order, each once."""
        found = []
        for pattern, names in self.rows:
            if fnmatch.fnmatchcase(test, pattern):
                found += [n for n in names if n not in found]
        return tuple(found)


def graded_table(root=ROOT):
    """The Table of root's tests/graded_exercises.txt (an empty one where it is missing). A "#"
    starts a comment; "# ---- lab N" starts lab N's section, and the "!order" rows in it are
    lab N's order (keyed "labN"; a row before any section under ""). An exercise named in two
    "!order" rows takes its later place."""
    path = os.path.join(root, GRADED)
    order, rows, prerequisites, ranks = {}, [], {}, {}
    section, placed = "", 0
    text = read_text(path) if os.path.isfile(path) else ""
    for raw in split_lines(text):
        header = SECTION_RE.match(raw)
        if header:
            section = f"lab{int(header.group(1))}"
        words = raw.split("#", 1)[0].split()
        if not words:
            continue
        if words[0] == "!order":
            order[section] = order.get(section, ()) + tuple(words[1:])
            for name in words[1:]:
                placed += 1
                ranks[name] = placed
        elif words[0].startswith("@"):
            prerequisites[words[0][1:]] = prerequisites.get(words[0][1:], ()) + tuple(words[1:])
        elif not words[0].startswith("!"):
            rows.append((words[0], tuple(words[1:])))
    return Table(MappingProxyType(order), tuple(rows), MappingProxyType(prerequisites), MappingProxyType(ranks))


# ---------------------------------------------------------------- the solutions
def boilerplate_lines(root=ROOT):
    """Every line of the project's own code outside the exercises, bare() and 16 bytes or longer,
    sorted and each once: common/ (*.cpp *.h *.vert *.frag *.glsl) and the labs' folders and shader
    folders (but *.md) with every exercise cut (marker to END EXERCISE, the STUB lines included)."""
    files = []
    for here, _, names in os.walk(os.path.join(root, "common")):
        files += [os.path.join(here, n) for n in names if n.endswith((".cpp", ".h", ".vert", ".frag", ".glsl"))]
    for lab in labs(root):
        for top in (lab, os.path.join("shaders", lab)):
            for here, _, names in os.walk(os.path.join(root, top)):
                files += [os.path.join(here, n) for n in names if not n.endswith(".md")]
    found = set()
    for path in files:
        if not os.path.isfile(path) or os.path.islink(path):
            continue
        inside = False
        for line in split_lines(read_text(path)):
            if SOLVED_RE.search(line):
                inside = True
            elif inside:
                inside = not END_RE.match(line)
            else:
                s = bare(line)
                if byte_length(s) >= 16:
                    found.add(s)
    return sorted(found, key=byte_order)


def solution_lines(lab, root=ROOT):
    """The substantive solution lines of lab folder lab's exercises and every later lab's, from
    this (complete) project: (name, "file:line", the line bare()).

    Only lines of 16 or more bytes without whitespace count. Shorter lines (braces, `return 1.0;`,
    `} else {`, `float d = 0.0;` is 12) are everywhere in the project and say nothing about the
    answer, while a line of 16 is already specific (`vec3 Q = normalize(P - E);` is 22). A line
    that is also one of the exercise's STUB lines, or part of one (a function's signature the stub
    keeps), is no answer: the copy has it on purpose. Nor is boilerplate (boilerplate_lines): a
    line the project's own code also holds outside every exercise, such as
    `for (int i = 0; i < 3; ++i) {` or a render pass's dependency field that common/ sets the same
    way. Trailing // comments are left out of both sides."""
    found = []
    for later in labs_from(lab, root):
        for e in exercises_of(later, root):
            stubs = [bare(code) for _, code in e.stub_code]
            for k, text in e.solution:
                code = bare(text)
                if byte_length(code) >= 16 and not any(code in s for s in stubs):
                    found.append((e.name, f"{e.file}:{k}", code))
    if not found:
        return found
    boilerplate = set(boilerplate_lines(root))
    return [row for row in found if row[2] not in boilerplate]


def solution_code(lab, only=False, root=ROOT):
    """The code of lab folder lab's exercises and every later lab's (only: lab's alone), as
    written, line by line: (name, "solution" or "stub", "file:line", the line; a STUB line's code
    without "// STUB: "). scripts/comment_answers.py derives each solution's distinctive tokens
    from it."""
    rows = []
    for later in labs_from(lab, root, only):
        for e in exercises_of(later, root):
            lines = [(k, "stub", code) for k, code in e.stub_code] + [(k, "solution", text) for k, text in e.solution]
            rows += [(e.name, kind, f"{e.file}:{k}", text) for k, kind, text in sorted(lines)]
    return rows


def stubs_file(chosen):
    """The text of a copy's .exercise-stubs for the cut-out exercises chosen: "file name code"
    per STUB line ("file name" for an empty one), the files sorted, each file's in line order, under
    a comment line. tests/exercise_hints.cpp (through the manifest) takes a copy's exercise as done
    once its code differs from this stub, whether or not the student keeps the TODO marker line."""
    lines = [STUBS_HEADER]
    for e in sorted(chosen, key=lambda e: (byte_order(e.file), e.line)):
        lines += [f"{e.file} {e.name} {code}" if code else f"{e.file} {e.name}" for _, code in e.stub_code]
    return join_lines(lines)


def copy_stubs(root=ROOT):
    """The stubs of a student copy's .exercise-stubs: "file name" → the stub, bare() and joined."""
    stubs = {}
    path = os.path.join(root, STUBS)
    if not os.path.isfile(path):
        return stubs
    for line in split_lines(read_text(path)):
        if not line or line[0] == "#":
            continue
        m = re.match(r"\s*(\S+)\s+(\S+)(.*)$", line)
        if m:
            key = f"{m.group(1)} {m.group(2)}"
            stubs[key] = stubs.get(key, "") + bare(m.group(3))
    return stubs


# ---------------------------------------------------------------- the manifest
def manifest(root=ROOT, copy_root=None):
    """What the C++ hints (tests/exercise_hints.cpp) and the grader read, as a JSON-ready dict:

    {"exercises": [{"name", "lab" (N), "file", "line", "hint", "tests": [...], "stub", "code",
                    "todo", "complete"}, …],
     "rows": [{"pattern", "exercises": [...]}, …],
     "order": {"lab1": [...], …}, "prerequisites": {"e": [...], …}}

    "exercises" holds every marker of every lab folder once per file (a lab that carries an earlier
    lab's file has its markers again), ordered by lab, "!order" rank, path and line. "code" is the
    region's code bare() and joined (STUB lines left out), "stub" the stub's: the marker's own STUB
    lines, or for a TODO marker without any, those of the complete marker of the same file and
    name in root, or the copy's .exercise-stubs ("file name" entries). "complete": such a stub was
    found (the marker has STUB lines, or one of the others has it). The hints take an exercise as
    unfinished, where complete, while it is a TODO or its stub is not empty, and its code is still
    the stub; where not complete, while it is a TODO marker (a copy without .exercise-stubs: the
    marker is taken at its word). In the complete project none is unfinished.

    copy_root: a tree whose lab folders (those it has) are read instead of root's (the grader's and
    the prover's variant of a lab); the table, .exercise-stubs and the complete markers stay root's.
    """
    table = graded_table(root)
    root_files = [(lab, rel) for lab in labs(root) for rel in lab_files(lab, root)]
    complete = [e for lab, rel in root_files for e in scan_file(rel, root, lab)]
    if copy_root:
        mirrored = [(lab, rel) for lab in labs(copy_root) for rel in lab_files(lab, copy_root)]
        replaced = {lab for lab, _ in mirrored}
        markers = [e for lab, rel in root_files if lab not in replaced for e in scan_file(rel, root, lab)]
        markers += [e for lab, rel in mirrored for e in scan_file(rel, copy_root, lab)]
    else:
        markers = complete
    stubs = copy_stubs(root)
    solved = {(c.file, c.name): c for c in reversed(complete) if not c.todo}  # the first one wins
    rank = lambda name: table.ranks.get(name, len(table.ranks) + 1)
    markers = sorted(markers, key=lambda e: (e.number, rank(e.name), e.file.startswith("shaders/"),
                                             byte_order(e.file), e.line))
    entries = []
    for e in markers:
        stub = "".join(bare(code) for _, code in e.stub_code)
        known = bool(e.stub_code)  # a STUB line that is all comment is a stub too: an empty one
        if not known and e.todo and (e.file, e.name) in solved:
            stub, known = "".join(bare(code) for _, code in solved[(e.file, e.name)].stub_code), True
        if not known and e.todo and f"{e.file} {e.name}" in stubs:
            stub, known = stubs[f"{e.file} {e.name}"], True
        entries.append({"name": e.name, "lab": e.number, "file": e.file, "line": e.line, "hint": e.hint,
                        "tests": list(e.tests), "stub": stub, "code": "".join(bare(t) for _, t in e.solution),
                        "todo": e.todo, "complete": known})
    return {"exercises": entries,
            "rows": [{"pattern": p, "exercises": list(names)} for p, names in table.rows],
            "order": {k: list(v) for k, v in table.order.items()},
            "prerequisites": {k: list(v) for k, v in table.prerequisites.items()}}


def manifest_text(root=ROOT, copy_root=None):
    """manifest() as the file holds it: JSON, one key a line where it helps a reader, UTF-8."""
    return json.dumps(manifest(root, copy_root), ensure_ascii=False, indent=1) + "\n"
