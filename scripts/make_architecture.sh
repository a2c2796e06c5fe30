#!/usr/bin/env bash
# make_architecture.sh — the picture of common/'s layers in docs/architecture.md, drawn from the
# build's own dependency graph (cmake --graphviz), so it cannot drift from the CMakeLists.
#
#   bash scripts/make_architecture.sh [BUILD]          # writes docs/images/architecture.{dot,svg,png}
#   bash scripts/make_architecture.sh --check [BUILD]  # exit 1 if the committed pictures are not
#                                                      # today's graph (CTest: architecture_up_to_date)
#
# --check: the .dot must be today's graph, and the .svg and the .png (the one docs/architecture.md
# shows) drawn from that .dot: each records the .dot's hash (an SVG comment, a PNG tEXt chunk),
# and where this machine's graphviz is the version that drew them, drawing the .dot again must give
# the same bytes (dot's output is deterministic; another version lays out differently, then only
# the hashes are compared).
# BUILD: a configured build folder (default: build/). The graph keeps the four layer libraries,
# the labs and the packages the layers link; a dashed edge is a PRIVATE link (not passed on: a lab
# linking lab_app does not see lab_dev).
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
check=0
if [ "${1:-}" = --check ]; then check=1; shift; fi
build="${1:-${LAB_BUILD_DIR:-$root/build}}"
[ -f "$build/CMakeCache.txt" ] || { echo "make_architecture: $build is not a configured build folder (run scripts/setup.sh)" >&2; exit 2; }
build="$(cd "$build" && pwd)"  # cmake --graphviz runs in a temporary folder
command -v dot >/dev/null || { echo "make_architecture: graphviz's dot not found (scripts/setup.sh installs graphviz)" >&2; exit 2; }
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
(cd "$tmp" && cmake --graphviz=graph.dot "$build" >/dev/null)

# cmake writes one edge per line: "nodeA" -> "nodeB" [ style = dotted ] // from -> to
python3 - "$tmp/graph.dot" >"$tmp/architecture.dot" <<'PY'
import re, sys
layers = {"lab_content": "content/", "lab_vulkan": "vulkan/", "lab_dev": "dev/", "lab_app": "app/"}
labs = ["lab1_camera", "lab2_lighting", "lab3_textures", "lab4_shadows"]
packages = {"Vulkan::Vulkan": "Vulkan", "glfw": "GLFW", "PkgConfig::IMGUI": "Dear ImGui", "glm::glm": "GLM",
            "nlohmann_json::nlohmann_json": "nlohmann-json", "tinyobjloader::tinyobjloader": "tinyobjloader",
            "PkgConfig::STB": "stb_image"}
edges = []
for line in open(sys.argv[1]):
    m = re.search(r'->\s*"node\d+"\s*(\[ style = (\w+) \])?\s*// (\S+) -> (\S+)', line)
    if not m:
        continue
    private, a, b = m.group(2) == "dotted", m.group(3), m.group(4)
    if (a in layers or a in labs) and (b in layers or b in packages):
        edges.append((a, b, private))
print("// The layers of common/ and what links them: made by scripts/make_architecture.sh, do not edit.")
print("digraph architecture {")
print('  rankdir=TB; node [fontname="Helvetica", fontsize=11]; edge [color="#555555"];')
print('  subgraph cluster_labs { label="the labs"; style=rounded; color="#888888";')
for lab in labs:
    print(f'    "{lab}" [shape=box, style="rounded,filled", fillcolor="#dbeafe"];')
print('    { rank=same; ' + " -> ".join(f'"{lab}"' for lab in labs) + " [style=invis]; }")
print("  }")
print('  subgraph cluster_common { label="common/"; style=rounded; color="#888888";')
for name, folder in layers.items():
    print(f'    "{name}" [shape=box, style=filled, fillcolor="#fef3c7", label="{name}\\n{folder}"];')
print("  }")
for full, short in packages.items():
    if any(b == full for _, b, _ in edges):
        print(f'  "{full}" [shape=box, style=filled, fillcolor="#eeeeee", fontcolor="#444444", label="{short}"];')
for a, b, private in sorted(set(edges)):
    print(f'  "{a}" -> "{b}"{" [style=dashed]" if private and a not in labs else ""};')
print("}")
PY

dot_file="$root/docs/images/architecture.dot"
images="$root/docs/images"
version="$(dot -V 2>&1)"
# draw DOT OUT_DIR: architecture.svg and architecture.png from DOT, each carrying DOT's hash and
# the graphviz version (an SVG comment; a PNG tEXt chunk, written after IHDR).
draw() {
  local source; source="drawn from architecture.dot $(sha256sum "$1" | cut -c1-16) by $version"
  { dot -Tsvg "$1" | sed "1a <!-- $source -->"; } >"$2/architecture.svg"
  dot -Tpng -Gdpi=110 "$1" | python3 -c '
import struct, sys, zlib
png, text = sys.stdin.buffer.read(), b"Source\0" + sys.argv[1].encode()
chunk = struct.pack(">I", len(text)) + b"tEXt" + text + struct.pack(">I", zlib.crc32(b"tEXt" + text))
end_of_ihdr = 8 + 8 + 13 + 4
sys.stdout.buffer.write(png[:end_of_ihdr] + chunk + png[end_of_ihdr:])' "$source" >"$2/architecture.png"
}
if ((check)); then
  if ! diff -u "$dot_file" "$tmp/architecture.dot"; then
    echo "make_architecture: docs/images/architecture.dot is stale; run bash scripts/make_architecture.sh" >&2
    exit 1
  fi
  hash="drawn from architecture.dot $(sha256sum "$dot_file" | cut -c1-16) by "
  mkdir "$tmp/drawn"; draw "$dot_file" "$tmp/drawn"
  for picture in architecture.svg architecture.png; do
    grep -aq "$hash" "$images/$picture" ||
      { echo "make_architecture: docs/images/$picture was not drawn from the committed .dot; run bash scripts/make_architecture.sh" >&2; exit 1; }
    if grep -aqF "$hash$version" "$images/$picture"; then  # drawn by this graphviz: the same bytes
      cmp -s "$images/$picture" "$tmp/drawn/$picture" ||
        { echo "make_architecture: docs/images/$picture is not what $version draws from the committed .dot; run bash scripts/make_architecture.sh" >&2; exit 1; }
    else
      echo "make_architecture: docs/images/$picture was drawn by another graphviz than $version: only its .dot hash is compared"
    fi
  done
  echo "make_architecture: docs/images/architecture.dot is today's graph, and its .svg and .png are drawn from it"
  exit 0
fi
mkdir -p "$images"
cp "$tmp/architecture.dot" "$dot_file"
draw "$dot_file" "$images"
echo "make_architecture: wrote docs/images/architecture.dot, .svg and .png"
