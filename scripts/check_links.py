#!/usr/bin/env python3
"""check_links.py — every relative link and #anchor in the Markdown files of a tree resolves.

    python3 scripts/check_links.py [DIR]     # DIR: the project or a student copy (default: .)
    python3 scripts/check_links.py --unlink-missing COPY N PROJECT   # (exercise.sh) copy of lab N

Looks at every *.md file under DIR (not .git/, build*/, node_modules/, student/, out/): each
inline link or picture [text](target) / ![alt](target) outside code that is not an URL
(http:, mailto:, …) must name a file or folder that exists, relative to the Markdown file;
a #anchor (alone, or after a .md file) must be the slug of one of that file's headings,
computed as the course site (markdown-it-anchor with github-slugger) and GitHub compute it:
the heading's text without its markup, lower-case, punctuation and symbols dropped, spaces
turned into -, and -1, -2, … appended to repeats.
Every row of a table has as many cells as its header (GFM splits a row at each | not written
\\|, inside code spans too, so `|v|` in a cell breaks the table on the site and on GitHub).
Prints one line per broken link or table row (file:line: the target and why) and exits 1 if there is one,
0 if none; 2 on bad input.

--unlink-missing (exercise.sh runs it on the copy it writes): each link or picture whose file is
in PROJECT but not in the copy becomes plain text, marked "(a later lab, not in this copy)" when the path is named
after a lab later than N (the rule of exercise.sh --left-out), a diff "(not in this copy; your student
site shows the diffs of the labs before this one)", else "(instructors' material, not in this
copy)" (site/, docs/solutions/).
"""
import os
import re
import sys
import unicodedata
from urllib.parse import unquote

SKIP_DIRS = {".git", "node_modules", "student", "out"}
FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})")
HEADING = re.compile(r"^ {0,3}(#{1,6})[ \t]+(.*?)[ \t#]*$")
LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^()\s<>]*(?:\([^()\s]*\)[^()\s<>]*)*)>?(?:\s+\"[^\"]*\")?\s*\)")
CODE_SPAN = re.compile(r"(`+)(.+?)\1")


def heading_text(raw):
    """The text markdown-it-anchor slugs: code spans' content, link text, no emphasis or tags."""
    text = CODE_SPAN.sub(lambda m: m.group(2).strip(), raw)
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"<[^>]+>", "", text)
    text = re.sub(r"(\*+|(?<!\w)_+|_+(?!\w))", "", text)
    return text.replace("&amp;", "&").replace("&lt;", "<").replace("&gt;", ">")


def slug(text):
    """github-slugger: lower-case, keep letters, marks, digits (not ², ½), '_', '-' and ' ',
    then ' ' → '-'."""
    kept = "".join(c for c in text.lower()
                   if c in " -_" or unicodedata.category(c)[0] in "LM"
                   or unicodedata.category(c) in ("Nd", "Nl"))
    return kept.replace(" ", "-")


def outside_fences(lines):
    """(line number, line) of Markdown lines outside fenced code blocks (CommonMark: a block
    opened by ``` or ~~~ ends at a fence of the same character at least as long)."""
    fence = None
    for number, line in enumerate(lines, 1):
        line = line.rstrip("\n")
        m = FENCE.match(line)
        if fence:
            if m and m.group(1)[0] == fence[0] and len(m.group(1)) >= len(fence):
                fence = None
            continue
        if m:
            fence = m.group(1)
            continue
        yield number, line


def lines_outside_code(path):
    """(line number, line) of the file outside fenced code blocks."""
    with open(path, encoding="utf-8") as f:
        yield from outside_fences(f)


_anchor_cache = {}


def anchors(path):
    if path not in _anchor_cache:
        seen, result = {}, set()
        for _, line in lines_outside_code(path):
            m = HEADING.match(line)
            if not m:
                continue
            base = slug(heading_text(m.group(2)))
            s = base
            while s in seen:  # github-slugger: the n-th repeat of base gets base-n
                seen[base] += 1
                s = f"{base}-{seen[base]}"
            seen[s] = 0
            result.add(s)
        for _, line in lines_outside_code(path):  # explicit <a id="…"> / <a name="…">
            for m in re.finditer(r"<a\s+(?:id|name)=\"([^\"]+)\"", line):
                result.add(m.group(1))
        _anchor_cache[path] = result
    return _anchor_cache[path]


def markdown_files(top):
    for here, dirs, files in os.walk(top):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith("build"))
        for name in sorted(files):
            if name.endswith(".md"):
                yield os.path.join(here, name)


def broken(md, target, top):
    """Why the link target (as written in Markdown file md) does not resolve; None if it does."""
    if not target or re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):
        return None  # an URL: not checked offline
    file_part, _, anchor = target.partition("#")
    dest = md if not file_part else os.path.normpath(
        os.path.join(os.path.dirname(md), unquote(file_part)))
    if not os.path.exists(dest):
        return "no such file or folder"
    if os.path.relpath(dest, top).startswith(".."):
        return "outside the tree"
    if anchor:
        if not dest.endswith(".md") or os.path.isdir(dest):
            return "an anchor into a file that is not Markdown"
        if unquote(anchor) not in anchors(dest):
            return f"no heading with the anchor #{anchor} in {os.path.relpath(dest, top)}"
    return None


def links(line):
    """The links of a line outside code spans: (match, target)."""
    blanked = CODE_SPAN.sub(lambda m: " " * len(m.group(0)), line)
    return [(m, m.group(1)) for m in LINK.finditer(blanked)]


def table_cells(line):
    """The cells of a table row: GFM splits at every | not escaped as \\|, in code spans too."""
    return len(re.split(r"(?<!\\)\|", line.strip().strip("|")))


def check(top):
    problems = 0
    for md in markdown_files(top):
        shown = os.path.relpath(md, top)
        header = None  # the cell count of the table being read
        for number, line in lines_outside_code(md):
            for _, target in links(line):
                why = broken(md, target, top)
                if why:
                    print(f"{shown}:{number}: broken link ({target}): {why}")
                    problems += 1
            if not line.lstrip().startswith("|"):
                header = None
            elif header is None:
                header = table_cells(line)
            elif table_cells(line) != header:
                print(f"{shown}:{number}: a table row of {table_cells(line)} cells under a header of {header} "
                      "(a | inside a code span splits the cell: write \\| or ‖)")
                problems += 1
    return problems


def later_lab(path, n):
    """Is path named after a lab later than n (lab<K>_… or …_lab<K>_…, K > n)? The rule of
    exercise.sh's later_lab_names."""
    return any(int(k) > n for part in path.split("/")
               for k in re.findall(r"(?:^|_|-)lab([0-9]+)_", part))


# Shared docs that are a later lab's lesson (exercise.sh's left_out leaves them out of earlier copies).
LESSON_DOCS = {"docs/lighting.md": 2}


def unlink_missing(top, n, source):
    """In a student copy of lab n: each link or picture to a path the copy left out (there in the
    project source, not in the copy) becomes plain text, marked as a later lab's or as instructors'
    material. A link that is broken in the project too stays, for the check to report."""
    changed = 0
    for md in markdown_files(top):
        with open(md, encoding="utf-8") as f:
            lines = f.read().split("\n")
        code = {number - 1 for number in range(1, len(lines) + 1)}
        code -= {number - 1 for number, _ in lines_outside_code(md)}
        for i, line in enumerate(lines):
            if i in code:
                continue
            for m, target in reversed(links(line)):
                file_part = target.partition("#")[0]
                if not file_part or re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):
                    continue
                dest = os.path.normpath(os.path.join(os.path.dirname(md), unquote(file_part)))
                where = os.path.relpath(dest, top)
                if os.path.exists(dest) or not os.path.exists(os.path.join(source, where)):
                    continue
                into = max([int(k) for k in re.findall(r"lab([0-9]+)_", where)] or [0])
                mark = ("a later lab, not in this copy" if later_lab(where, n) or LESSON_DOCS.get(where, 0) > n
                        else "this lab's lesson as a diff: instructors' material (it shows this lab's answers)"
                        if where.startswith("docs/diffs") and into == n
                        else "not in this copy; your student site shows the diffs of the labs before this one"
                        if where.startswith("docs/diffs") else "instructors' material, not in this copy")
                text = re.match(r"!?\[(.*)\]\(", m.group(0), re.S).group(1)
                if m.group(0).startswith("!"):
                    plain = f"*(picture: {text or where}; {mark})*"
                else:
                    plain = f"{text} *({mark})*"
                line = line[:m.start()] + plain + line[m.end():]
                changed += 1
            lines[i] = line
        with open(md, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
        _anchor_cache.pop(md, None)
    return changed


def main(argv):
    if len(argv) > 1 and argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0
    if len(argv) > 1 and argv[1] == "--unlink-missing":
        if (len(argv) != 5 or not argv[3].isdigit() or not os.path.isdir(argv[2])
                or not os.path.isdir(argv[4])):
            print("check_links: usage: check_links.py --unlink-missing COPY_DIR LAB_NUMBER PROJECT_DIR",
                  file=sys.stderr)
            return 2
        changed = unlink_missing(argv[2], int(argv[3]), argv[4])
        print(f"check_links: {argv[2]}: {changed} link(s) to left-out paths made plain text")
        return 0
    if len(argv) > 2:
        print("check_links: usage: check_links.py [DIR]", file=sys.stderr)
        return 2
    top = argv[1] if len(argv) == 2 else "."
    if not os.path.isdir(top):
        print(f"check_links: {top}: no such folder", file=sys.stderr)
        return 2
    count = sum(1 for _ in markdown_files(top))
    problems = check(top)
    if problems:
        print(f"check_links: {top}: {problems} broken link(s) or table row(s) in {count} Markdown files")
        return 1
    print(f"check_links: {top}: every relative link and anchor of {count} Markdown files resolves, every table row fits its header")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
