#!/usr/bin/env bash
# make_diffs.sh — the instructor diffs: one file per consecutive pair of labs,
# code and shaders, in docs/diffs/<labA>-<labB>.diff.
#   bash scripts/make_diffs.sh          # regenerate
#   bash scripts/make_diffs.sh --check  # fail (exit 1) if docs/diffs/ is stale (a CTest test)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
labs=(lab1_camera lab2_lighting lab3_textures lab4_shadows)

# diff -ruN, without timestamps so the output depends only on the files.
pair_diff() {
  diff -ruN "$1" "$2" | sed -E 's/^(---|\+\+\+) ([^\t]*)\t.*/\1 \2/' || true
}

generate() {  # into folder $1
  local out="$1"
  mkdir -p "$out"
  for ((i = 0; i + 1 < ${#labs[@]}; i++)); do
    local a=${labs[i]} b=${labs[i + 1]}
    [ -d "$a" ] && [ -d "$b" ] && [ -f "$b/CMakeLists.txt" ] || continue
    { pair_diff "$a" "$b"; pair_diff "shaders/$a" "shaders/$b"; } >"$out/$a-$b.diff"
  done
}

if [ "${1:-}" = "--check" ]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  generate "$tmp"
  mkdir -p docs/diffs
  if ! diff -r -x README.md "$tmp" docs/diffs >/dev/null; then
    echo "docs/diffs is stale: run scripts/make_diffs.sh and commit the result" >&2
    diff -rq -x README.md "$tmp" docs/diffs >&2 || true
    exit 1
  fi
  echo "docs/diffs up to date ($(ls "$tmp" | wc -l) diffs)"
else
  rm -f docs/diffs/*.diff
  generate docs/diffs
  for f in docs/diffs/*.diff; do
    [ -e "$f" ] || continue
    echo "$f: $(grep -c '^[+-][^+-]' "$f") changed lines"
  done
fi
