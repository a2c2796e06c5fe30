#!/usr/bin/env python3
"""comment_answers.py — does a student copy's prose (comments, Markdown) name a solution's tokens?

    python3 scripts/comment_answers.py COPY_DIR LAB

exercise.sh --check-copy runs it. Takes the solutions a copy of LAB cuts out, LAB's own exercises'
code and stubs, from this project's markers (scripts/course/exercises.py, solution_code) and
derives each exercise's distinctive tokens:
  - identifiers that look like an API's constants or calls (VK_*, GL_*, names with an upper-case
    letter and an underscore, or an identifier followed by "("),
  - call expressions with a nested call, compared without whitespace (f(x, g(y))),
that the solution holds but neither its stub nor the copy's code outside comments does (a token
the copy's code uses anyway gives nothing away), nor the copy's exercise hints (a hint may name
the API call to read about). Then every comment of the copy's code files
(// … and /* … */ in C++ and GLSL, # … in shell, Python and CMake files) and every line of its
Markdown files outside code blocks is searched for them. Prints one line per hit (file:line, the
token, the exercise) and exits 1 if there is one, 0 if none, 2 on bad input.
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_links import outside_fences  # noqa: E402 (beside this file)
from course import exercises  # noqa: E402

CODE = (".cpp", ".h", ".hpp", ".glsl", ".vert", ".frag", ".comp")
HASH = (".sh", ".py", ".cmake", ".txt")
IDENT = re.compile(r"\b[A-Za-z_][A-Za-z0-9_]*\b")
# Tokens that say nothing about an answer although the copy's code does not hold them.
ALLOW = {
    # Keywords and GLSL/C++ built-ins a comment may name in any lesson.
    "return", "const", "float", "double", "vec2", "vec3", "vec4", "if", "else",
}


def split_code(path):
    """(code outside comments, [(line number, comment or prose text)]) of a file."""
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    prose = []
    if path.endswith(".md"):  # prose: every line outside fenced code (check_links.py's reading)
        return "", list(outside_fences(text.split("\n")))
    code = []
    if path.endswith(HASH) or os.path.basename(path) == "CMakeLists.txt":
        for n, line in enumerate(text.split("\n"), 1):
            m = re.search(r"(^|\s)#(.*)$", line)
            if m and not line.lstrip().startswith("#!"):
                prose.append((n, m.group(2)))
                code.append(line[:m.start()])
            else:
                code.append(line)
        return "\n".join(code), prose
    # C++ / GLSL: strings are not comments; // to the end of the line; /* … */ across lines.
    n, i, out = 1, 0, []
    while i < len(text):
        c = text[i]
        if c == '"':
            j = i + 1
            while j < len(text) and text[j] != '"' and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = len(text) if j < 0 else j
            prose.append((n, text[i + 2:j]))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = len(text) if j < 0 else j
            for k, part in enumerate(text[i + 2:j].split("\n")):
                prose.append((n + k, part))
            n += text[i:j].count("\n")
            out.append("\n" * text[i:j].count("\n"))
            i = j + 2
        else:
            if c == "\n":
                n += 1
            out.append(c)
            i += 1
    return "".join(out), prose


def calls(line):
    """The outermost call expressions with a nested call, without whitespace: f(…g(…)…)."""
    found, i = [], 0
    for m in re.finditer(r"(?:[A-Za-z_][A-Za-z0-9_]*::)*[A-Za-z_][A-Za-z0-9_]*\(", line):
        if m.start() < i:
            continue  # inside the last one found
        depth, j = 0, m.end() - 1
        while j < len(line):
            depth += {"(": 1, ")": -1}.get(line[j], 0)
            if depth == 0:
                break
            j += 1
        inner = line[m.end():j]
        if depth == 0 and re.search(r"[A-Za-z_]\w*\(", inner):
            found.append(re.sub(r"\s+", "", line[m.start():j + 1]))
            i = j + 1
    return found


def suffixes(t):
    """An API enum and the shorter names prose gives it: VK_A_B_C, A_B_C, B_C (the last two or
    more of its parts). (No real enum here: this file travels with the copies, and its own text
    counts as their code.)"""
    parts = t.split("_")
    if not re.match(r"^(VK|GL)_[A-Z0-9_]+$", t):
        return {t}
    return {"_".join(parts[i:]) for i in range(len(parts) - 1)}


def distinctive(line):
    toks = set()
    for m in IDENT.finditer(line):
        t = m.group(0)
        api = re.match(r"^(VK|GL)_[A-Z0-9_]+$", t) or (re.search(r"[A-Z]", t) and "_" in t.strip("_"))
        called = line[m.end():].lstrip().startswith("(")
        if (api or called) and t not in ALLOW:
            toks |= suffixes(t)
    return toks


def main(argv):
    if len(argv) > 1 and argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0
    if len(argv) != 3 or not os.path.isdir(argv[1]):
        print("comment_answers: usage: comment_answers.py COPY_DIR LAB (a folder and a lab: 2, lab2 or lab2_lighting)",
              file=sys.stderr)
        return 2
    top = argv[1]
    try:
        lab = exercises.resolve_lab(argv[2])
    except LookupError as e:
        print(f"comment_answers: {e}", file=sys.stderr)
        return 2
    solution, stub = {}, {}
    for name, kind, _, line in exercises.solution_code(lab, only=True):
        (solution if kind == "solution" else stub).setdefault(name, []).append(line.split("//")[0])
    if not solution:
        print(f"comment_answers: {lab} has no solution lines: nothing to look for", file=sys.stderr)
        return 2

    files = []
    for here, dirs, names in os.walk(top):
        dirs[:] = [d for d in dirs if d not in (".git", "node_modules") and not d.startswith("build")]
        for f in names:
            if f.endswith(CODE + HASH + (".md",)) or f == "CMakeLists.txt":
                files.append(os.path.join(here, f))
    split = {f: split_code(f) for f in sorted(files)}
    code_words = set().union(*(suffixes(t) for t in set(IDENT.findall("\n".join(c for c, _ in split.values())))))
    code_bare = re.sub(r"\s+", "", "\n".join(c for c, _ in split.values()))

    tokens = {}  # token → exercise
    for name, lines in solution.items():
        stub_text = "\n".join(stub.get(name, []))
        stub_words = set().union(*(suffixes(t) for t in IDENT.findall(stub_text)), set())
        stub_bare = re.sub(r"\s+", "", stub_text)
        for line in lines:
            for t in distinctive(line):
                if t not in stub_words and t not in code_words:
                    tokens.setdefault(t, name)
            for e in calls(line):
                if e not in stub_bare and e not in code_bare:
                    tokens.setdefault(e, name)
    # A token the copy's own exercise hints name ("Read vkCmdBlitImage in the spec") is the hint,
    # not the answer: the text of every comment that holds a marker.
    hinted = set()
    for _, prose in split.values():
        for _, text in prose:
            if exercises.MARKER_RE.search("//" + text):
                hinted |= set(IDENT.findall(text)) | {e for e in tokens if e in re.sub(r"\s+", "", text)}
    tokens = {t: n for t, n in tokens.items() if t not in hinted}
    words = {t: n for t, n in tokens.items() if "(" not in t}
    exprs = {t: n for t, n in tokens.items() if "(" in t}

    hits = 0
    for path, (_, prose) in split.items():
        for n, text in prose:
            found = [t for t in IDENT.findall(text) if t in words]
            bare = re.sub(r"\s+", "", text)
            found += [e for e in exprs if e in bare]
            for t in dict.fromkeys(found):
                print(f"FAIL answer in a comment: {os.path.relpath(path, top)}:{n} names {t} "
                      f"(exercise {tokens[t]}'s solution)")
                hits += 1
    print(f"comment_answers: {len(tokens)} distinctive token(s) of the cut-out solutions "
          f"({', '.join(sorted(tokens)[:12])}{' …' if len(tokens) > 12 else ''}); {hits} in comments or docs")
    return 1 if hits else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
