#!/usr/bin/env python3
"""check_includes.py — no #include in common/, the labs or their shaders reaches into another
folder by a path (CTest: no_relative_includes).

    python3 tests/check_includes.py [SOURCE_DIR]     default: the folder above tests/

Each layer of common/ sees only the headers its CMake target lists (docs/architecture.md), and the
layers_* tests prove that an include the wrong way does not build. A path in the include itself
gets around that: `#include "../app/cli.h"` in common/vulkan/ is found next to the file, whatever
the target says; and a lab that includes `../lab3_textures/…` breaks the student copy of an
earlier lab. So an include whose path has a `..` part or is absolute is reported, one line each:
FILE:LINE: the include. Exit code 1 when there is one, 0 when there is none.
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*["<]([^">]+)[">]')
SUFFIXES = (".h", ".hpp", ".cpp", ".cc", ".inl", ".glsl", ".vert", ".frag", ".comp", ".geom")


def folders(root):
    """common/, every lab folder (labN_name/) and shaders/ (the labs' and common's GLSL)."""
    names = ["common", "shaders"] + sorted(d for d in os.listdir(root) if re.match(r"lab\d+_", d))
    return [os.path.join(root, d) for d in names if os.path.isdir(os.path.join(root, d))]


def escapes(path):
    return path.startswith("/") or ".." in re.split(r"[\\/]", path)


def main(argv):
    if argv[1:2] in (["-h"], ["--help"]):
        print(__doc__.strip())
        return 0
    root = os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    if not os.path.isdir(os.path.join(root, "common")):
        print(f"check_includes: {root}: no common/ folder here", file=sys.stderr)
        return 2
    found, scanned = 0, 0
    for top in folders(root):
        for dirpath, dirnames, filenames in os.walk(top):
            dirnames.sort()
            for name in sorted(filenames):
                if not name.endswith(SUFFIXES):
                    continue
                path = os.path.join(dirpath, name)
                scanned += 1
                with open(path, encoding="utf-8", errors="replace") as f:
                    for number, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if m and escapes(m.group(1)):
                            print(f"{os.path.relpath(path, root)}:{number}: {line.strip()}  "
                                  f"(a path out of the file's folder: include by name, through the target's include directories)")
                            found += 1
    if found:
        print(f"check_includes: {found} include(s) by a relative or absolute path in {scanned} files")
        return 1
    print(f"check_includes: {scanned} files, every include by name")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
