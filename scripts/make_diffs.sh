#!/usr/bin/env bash
# make_diffs.sh — the instructor diffs: one file per consecutive pair of labs,
# docs/diffs/<labA>-<labB>.diff, holding exactly the lesson in reading order.
#
#   bash scripts/make_diffs.sh            # regenerate docs/diffs/*.diff
#   bash scripts/make_diffs.sh --check    # exit 1 if a committed diff is stale (CTest: diffs_up_to_date)
#   bash scripts/make_diffs.sh --lessons  # exit 1 if a lab changes a file the manifest does not list
#                                         # (CTest: lessons_only)
#   bash scripts/make_diffs.sh --shares [MIN% [LAB]]  # each diff's non-blank changed lines by
#                                         # category; exit 1 if the lesson share of a diff into LAB or
#                                         # a later lab (default: every diff) is under MIN%
#                                         # (CTest: lesson_share)
#
# What goes into a diff, and in which order, comes from the manifest docs/diffs/lessons.md: for
# each lab, the files it adds or changes, in reading order, each with what it teaches (the reading
# guide at the top of the diff) and, for a file that grew out of another one, that file
# ("lit.vert ← unlit.vert": the diff shows the change, not a new file). The labs' README.md files
# are left out. The labs are the folders lab<N>_<name>/ with a CMakeLists.txt, in order of N.
#
# --check does not compare diff output text (another diffutils version may lay hunks out
# differently): it checks that the reading guide and the list of files match the manifest, and
# that applying each committed diff to the earlier lab in a temporary folder gives the later lab.
set -euo pipefail
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
manifest=docs/diffs/lessons.md
export LC_ALL=C

# The labs, in order of their number.
mapfile -t labs < <(for d in lab[0-9]*_*; do [ -f "$d/CMakeLists.txt" ] && echo "$d"; done | sort -V)

# The manifest's entries for lab $1, one per line: path US from US what-it-teaches (US = \\037: read splits on it even between empty fields).
entries() {
  awk -v lab="$1" '
    /^## / { in_lab = ($2 == lab); next }
    in_lab && /^[0-9]+\. `/ {
      line = $0; sub(/^[0-9]+\. `/, "", line)
      path = line; sub(/`.*/, "", path)
      rest = line; sub(/^[^`]*`/, "", rest)
      from = ""
      if (rest ~ /^ ← `/) { sub(/^ ← `/, "", rest); from = rest; sub(/`.*/, "", from); sub(/^[^`]*`/, "", rest) }
      sub(/^ — /, "", rest)
      printf "%s\037%s\037%s\n", path, from, rest
    }' "$manifest"
}
has_section() { grep -q "^## $1\$" "$manifest"; }

# The files of lab $1 that lessons are about: its folder and its shader folder, without README.md.
lab_files() {
  { [ -d "$1" ] && find "$1" -type f; [ -d "shaders/$1" ] && find "shaders/$1" -type f; } |
    grep -v '/README\.md$' | sort || true
}

# What `path` (a file of lab $b) is compared with in lab $a: the manifest's "from", or the
# same name in the previous lab.
source_of() {  # a b path from
  if [ -n "$4" ]; then echo "$4"; else echo "${3/$2/$1}"; fi
}

# A unified diff of $1 → $2 with stable labels (a/PATH, b/PATH; /dev/null for none).
file_diff() {
  local old="$1" new="$2" old_label="a/$1" new_label="b/$2"
  [ -e "$old" ] || { old=/dev/null; old_label=/dev/null; }
  [ -e "$new" ] || { new=/dev/null; new_label=/dev/null; }
  diff -u --label "$old_label" --label "$new_label" "$old" "$new" || [ $? -eq 1 ]
}

# What the diff $a → $b spends its changed lines on, by the category its manifest entry gives each
# file: "UI only:" (panels), "Plumbing:" (build files, the frame loop's wiring), "Noise:" (changes
# that teach nothing), "Lesson 2:" (a lab's second lesson: lab 4's translucency), else the lesson.
# Counted: the non-blank +/− lines of the lab folder and its shaders (the scene files are data, not
# code, and are left out). Prints "lesson lesson2 ui plumbing noise" (lesson includes lesson2).
line_counts() {  # a b
  local a="$1" b="$2" path from what line c
  local -A category=() n=([lesson]=0 [lesson2]=0 [ui]=0 [plumbing]=0 [noise]=0)
  while IFS=$'\037' read -r path from what; do
    case "$what" in
      "UI only:"*) category[$path]=ui ;;
      "Plumbing:"*) category[$path]=plumbing ;;
      "Noise:"*) category[$path]=noise ;;
      "Lesson 2:"*) category[$path]=lesson2 ;;
      *) category[$path]=lesson ;;
    esac
    [[ "$path" == scenes/* ]] && continue
    while IFS= read -r line; do
      case "$line" in "--- "* | "+++ "*) continue ;; esac
      [[ "$line" =~ ^[-+].*[^[:space:]] ]] || continue
      c="${category[$path]}"
      n[$c]=$((n[$c] + 1))
    done < <(file_diff "$(source_of "$a" "$b" "$path" "$from")" "$path")
  done < <(entries "$b")
  echo "$((n[lesson] + n[lesson2])) ${n[lesson2]} ${n[ui]} ${n[plumbing]} ${n[noise]}"
}

# The reading guide of $a → $b (also what --check compares with the committed diff's top).
guide() {  # a b
  local a="$1" b="$2" n=0 path from text
  echo "# $a → $b: the lesson, in reading order."
  echo "# Generated by scripts/make_diffs.sh from docs/diffs/lessons.md. Every other file of $b/ and"
  echo "# shaders/$b/ is $a's, byte for byte (CTest: lessons_only); $b/README.md explains in prose."
  local lesson lesson2 ui plumbing noise total
  read -r lesson lesson2 ui plumbing noise < <(line_counts "$a" "$b")
  total=$((lesson + ui + plumbing + noise))
  if ((total)); then
    printf '# Changed lines (non-blank, lab folder and shaders): %d, the lesson %d (%d %%' "$total" "$lesson" $((100 * lesson / total))
    ((lesson2)) && printf ': first lesson %d, second lesson %d' $((lesson - lesson2)) "$lesson2"
    printf '), UI %d, plumbing %d, noise %d.\n' "$ui" "$plumbing" "$noise"
  fi
  echo "#"
  while IFS=$'\037' read -r path from text; do
    n=$((n + 1))
    from=$(source_of "$a" "$b" "$path" "$from")
    if [ ! -e "$from" ]; then
      printf '# %2d. %s (new): %s\n' "$n" "$path" "$text"
    elif [ "$from" != "${path/$b/$a}" ]; then
      printf '# %2d. %s (from %s): %s\n' "$n" "$path" "$from" "$text"
    else
      printf '# %2d. %s: %s\n' "$n" "$path" "$text"
    fi
  done < <(entries "$b")
  for gone in $(removed "$a" "$b"); do
    n=$((n + 1))
    printf '# %2d. %s: removed\n' "$n" "$gone"
  done
  echo
}

# Files of lab $a with no counterpart in lab $b (they must be deleted by the diff).
removed() {  # a b
  local f
  for f in $(lab_files "$1"); do [ -e "${f/$1/$2}" ] || echo "$f"; done
}

generate_one() {  # a b → stdout
  local a="$1" b="$2" path from text gone
  guide "$a" "$b"
  while IFS=$'\037' read -r path from text; do
    file_diff "$(source_of "$a" "$b" "$path" "$from")" "$path"
  done < <(entries "$b")
  for gone in $(removed "$a" "$b"); do file_diff "$gone" "${gone/$a/$b}"; done
}

# --- checks --------------------------------------------------------------------------------

problems=0
problem() { echo "$*" >&2; problems=$((problems + 1)); }

# Every file of lab $b not in the manifest is byte-identical to lab $a's; every listed file
# exists and differs from what it is compared with.
check_lessons() {  # a b
  local a="$1" b="$2" path from text f
  if ! has_section "$b"; then
    problem "$manifest: no section '## $b': list the files $b adds or changes (see the top of that file)"
    return
  fi
  local -A listed=()
  while IFS=$'\037' read -r path from text; do
    listed[$path]=1
    from=$(source_of "$a" "$b" "$path" "$from")
    if [ ! -e "$path" ]; then
      problem "$manifest: $b lists $path, which does not exist"
    elif [ -e "$from" ] && cmp -s "$from" "$path"; then
      problem "$manifest: $b lists $path, but it is identical to $from (not part of the lesson?)"
    fi
  done < <(entries "$b")
  for f in $(lab_files "$b"); do
    [ -n "${listed[$f]:-}" ] && continue
    local prev="${f/$b/$a}"
    if [ ! -e "$prev" ]; then
      problem "$f: new in $b but not listed in $manifest"
    elif ! cmp -s "$prev" "$f"; then
      problem "$f differs from $prev but is not part of $b's lesson ($manifest): a fix to a file both labs carry goes into both"
    fi
  done
}

# Applies the committed diff of $a → $b to lab $a in a temporary folder and compares the result
# with lab $b (and each listed file outside the lab folders, e.g. the default scene).
check_applies() {  # a b committed tmp
  local a="$1" b="$2" committed="$3" tmp="$4"
  local work="$tmp/apply-$b"
  mkdir -p "$work/sections"
  # Split the diff into one section per file: a "--- " line followed by a "+++ " line.
  awk -v dir="$work/sections" '
    { lines[NR] = $0 }
    END {
      n = 0
      for (i = 1; i <= NR; i++) {
        if (lines[i] ~ /^--- (a\/|\/dev\/null)/ && i < NR && lines[i + 1] ~ /^\+\+\+ (b\/|\/dev\/null)/) {
          if (n) close(out)
          n++; out = sprintf("%s/%04d", dir, n)
        }
        if (n) print lines[i] > out
      }
    }' "$committed"
  # Lab $a's files under lab $b's names, then every section applied on top.
  local f
  for f in $(lab_files "$a"); do
    mkdir -p "$work/tree/$(dirname "${f/$a/$b}")"
    cp "$f" "$work/tree/${f/$a/$b}"
  done
  local section old new
  for section in "$work"/sections/*; do
    [ -e "$section" ] || continue
    old=$(head -n 1 "$section" | sed -E 's/^--- (a\/)?//')
    new=$(sed -n 2p "$section" | sed -E 's/^\+\+\+ (b\/)?//')
    local src="$work/empty"
    : >"$src"
    if [ "$old" != /dev/null ]; then src="$old"; fi
    if [ "$new" = /dev/null ]; then
      rm -f "$work/tree/${old/$a/$b}"
      continue
    fi
    mkdir -p "$work/tree/$(dirname "$new")"
    if ! patch -s -f -o "$work/tree/$new.patched" "$src" <"$section" >"$work/patch.log" 2>&1; then
      problem "$committed: the part for $new does not apply to $old: $(head -n 1 "$work/patch.log")"
      continue
    fi
    mv "$work/tree/$new.patched" "$work/tree/$new"
    if [[ "$new" != "$b/"* && "$new" != "shaders/$b/"* ]] && ! cmp -s "$work/tree/$new" "$new"; then
      problem "$committed: applied to $old it does not give $new"
    fi
  done
  local d
  for d in "$b" "shaders/$b"; do
    [ -d "$d" ] || continue
    if ! diff -rq -x README.md "$work/tree/$d" "$d" >"$work/tree.log" 2>&1; then
      problem "$committed: applied to $a it does not give $b: $(head -n 1 "$work/tree.log")"
    fi
  done
}

mode="${1:-}"
case "$mode" in
  --check)
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    expected_files=()
    for ((i = 0; i + 1 < ${#labs[@]}; i++)); do
      a=${labs[i]} b=${labs[i + 1]}
      committed="docs/diffs/$a-$b.diff"
      expected_files+=("$committed")
      if [ ! -f "$committed" ]; then problem "$committed is missing"; continue; fi
      # The guide and the list of files must be the manifest's (independent of diff's layout).
      generate_one "$a" "$b" >"$tmp/$b.diff"
      if ! cmp -s <(sed '/^--- /,$d' "$committed") <(sed '/^--- /,$d' "$tmp/$b.diff"); then
        problem "$committed: the reading guide differs from $manifest"
      fi
      if ! cmp -s <(grep -E '^(---|\+\+\+) (a/|b/|/dev/null)' "$committed") \
                  <(grep -E '^(---|\+\+\+) (a/|b/|/dev/null)' "$tmp/$b.diff"); then
        problem "$committed: the files or their order differ from $manifest"
      fi
      check_applies "$a" "$b" "$committed" "$tmp"
    done
    for f in docs/diffs/*.diff; do
      [ -e "$f" ] || continue
      [[ " ${expected_files[*]} " == *" $f "* ]] || problem "$f belongs to no pair of consecutive labs"
    done
    if ((problems)); then
      echo "docs/diffs is stale: run bash scripts/make_diffs.sh and commit the result" >&2
      exit 1
    fi
    echo "docs/diffs up to date (${#expected_files[@]} diffs; each applied to the earlier lab gives the later one)"
    ;;
  --lessons)
    for ((i = 0; i + 1 < ${#labs[@]}; i++)); do check_lessons "${labs[i]}" "${labs[i + 1]}"; done
    if ((problems)); then exit 1; fi
    echo "each lab changes only its lesson (${#labs[@]} labs, manifest $manifest)"
    ;;
  --shares)
    # What each diff spends its changed lines on (line_counts, above).
    min="${2:-0}" judged_from="${3:-}"
    skipping=1  # diffs before LAB are shown, not judged
    [ -z "$judged_from" ] && skipping=0  # no LAB: every diff is judged
    printf '%-42s %7s %5s %9s %6s %7s\n' diff lesson UI plumbing noise "lesson%"
    for ((i = 0; i + 1 < ${#labs[@]}; i++)); do
      a=${labs[i]} b=${labs[i + 1]}
      read -r lesson lesson2 ui plumbing noise < <(line_counts "$a" "$b")
      total=$((lesson + ui + plumbing + noise))
      share=$((total ? 1000 * lesson / total : 1000))
      printf '%-42s %7d %5d %9d %6d %5d.%d\n' "$a-$b" "$lesson" "$ui" "$plumbing" "$noise" $((share / 10)) $((share % 10))
      [[ "$b" == "$judged_from"* ]] && skipping=0
      ((skipping || share >= 10 * min)) || problem "$a-$b: the lesson is ${share%?}.${share: -1} % of the changed lines, under $min %"
    done
    if ((problems)); then exit 1; fi
    ;;
  "")
    rm -f docs/diffs/*.diff
    for ((i = 0; i + 1 < ${#labs[@]}; i++)); do
      a=${labs[i]} b=${labs[i + 1]}
      has_section "$b" || echo "make_diffs: warning: $manifest has no section for $b: its diff is empty" >&2
      generate_one "$a" "$b" >"docs/diffs/$a-$b.diff"
      f="docs/diffs/$a-$b.diff"
      echo "$f: $(grep -vE '^(---|\+\+\+) (a/|b/|/dev/null)' "$f" | grep -c '^[+-]') changed lines"
    done
    ;;
  *)
    echo "usage: bash scripts/make_diffs.sh [--check | --lessons | --shares [MIN% [LAB]]]" >&2
    exit 2
    ;;
esac
