#!/usr/bin/env bash
# exercise.sh — a student copy of the project, with a lab's exercises cut out and no answers in it.
#
#   bash scripts/exercise.sh LAB [NAME…] [--out DIR]   # write the copy (default DIR: student/<lab>)
#   bash scripts/exercise.sh --list [LAB]               # the exercises, with file, line and tests
#   bash scripts/exercise.sh --stub FILE NAME…          # print FILE with those exercises stubbed
#   bash scripts/exercise.sh --left-out LAB             # what a copy of LAB leaves out (paths)
#   bash scripts/exercise.sh --check-copy DIR LAB       # check a written copy for answers
#   bash scripts/exercise.sh --check-copies             # write and check a copy of every lab with
#                                                       # exercises (CTest: student_copy_no_answers)
#   bash scripts/exercise.sh --check-copy-links         # write a copy of every lab; every link in
#                                                       # it resolves (CTest: student_copy_links)
#   bash scripts/exercise.sh --prove BUILD_DIR LAB [--rows]  # the grader's own test (CTest:
#                                                       # grader_labN); --rows: the measured blame
#   bash scripts/exercise.sh --solution-lines LAB       # the substantive solution lines of LAB's and
#                                                       # every later lab's exercises (name US where US code)
#   bash scripts/exercise.sh --solution-code LAB [only] # their code as written, stubs too (for
#                                                       # scripts/comment_answers.py)
#
# LAB is 1, lab1 or lab1_camera. Without NAMEs every exercise of the lab is cut out.
#
# In the labs' sources and shaders an exercise is marked like this:
#     // EXERCISE attenuation: what to write, as a hint. Checked by Lab2Render.PointLights.
#     // STUB: return 1.0;  // what the copy has instead (one or more STUB lines)
#     ...the lab's code...
#     // END EXERCISE
# In the copy the code between the markers is replaced by the STUB lines under a
# "// TODO EXERCISE name: hint" line. The copy builds and runs, with a visibly wrong picture,
# and `ctest --test-dir build -L labN` there is the grader: the tests named after "Checked by"
# fail until the exercise is done, and say which exercise it is and where.
#
# What the copy of lab N holds: common/, labs 1..N-1 complete (their solutions are not secret
# any more once lab N is handed out), lab N with its exercises stubbed, and the tests, scenes,
# docs and scripts those labs use. What it leaves out, because it would hand out answers
# (--left-out lists it; docs/solutions.md is the instructors' policy):
#   - every file or folder named lab<K>_* or *_lab<K>_* with K > N: the later labs (lab N+1
#     carries lab N complete), their shaders, scenes, test scenes, gallery pictures, bench scripts;
#   - tests/ files that only later labs' tests use (every mention in tests/CMakeLists.txt inside an
#     `if(TARGET lab<K>_…)` block, K > N), and scene folders (scenes/<dir>/) only later labs' scene
#     files use;
#   - docs/diffs/ (the diff lab N-1 → lab N is lab N's solution) and site/ (the course site builds
#     pages from those diffs), whole: they are instructor material;
#   - in the docs it keeps, every section that names a later lab: the student site's rule, applied
#     by the site's own code (node site/student.mjs --trim-later-labs; laterLabText there), so the
#     copy and its student site (built from the copy) drop the same sections.
# The copy has a .student-copy file (its lab): tests/CMakeLists.txt then disables the tests of the
# whole project that a copy cannot pass (the diffs, the site, the architecture picture).
# --check-copy checks a copy: nothing above is in it, each cut-out exercise is a TODO, no text
# file holds a line of a cut-out solution, and no doc a section about a later lab (see check_copy below).
#
# An exercise belongs to the first lab that has it (lab 2 carries lab 1's camera.cpp with its
# markers; they are lab 1's exercises).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
export LC_ALL=C

mapfile -t labs < <(for d in lab[0-9]*_*; do [ -f "$d/CMakeLists.txt" ] && echo "$d"; done | sort -V)

die() { echo "exercise: $*" >&2; exit 2; }

resolve_lab() {  # 1 | lab1 | lab1_camera → lab1_camera
  local want="$1" candidate
  [[ "$want" == lab* ]] || want="lab$want"
  for candidate in "${labs[@]}"; do
    if [ "$candidate" = "$want" ] || [ "${candidate%%_*}" = "$want" ]; then echo "$candidate"; return; fi
  done
  die "no lab '$1' here; the labs are: ${labs[*]}"
}

# Every marker of lab folder $1 (its folder and shader folder): name US file US line US hint US tests.
markers_in() {
  local files
  files=$({ [ -d "$1" ] && find "$1" -type f ! -name README.md; [ -d "shaders/$1" ] && find "shaders/$1" -type f; } | sort)
  [ -n "$files" ] || return 0
  # shellcheck disable=SC2086
  awk '
    match($0, /\/\/ (TODO )?EXERCISE [a-z0-9_]+: /) {
      text = substr($0, RSTART, RLENGTH); sub(/^\/\/ (TODO )?EXERCISE /, "", text); sub(/: $/, "", text)
      hint = substr($0, RSTART + RLENGTH)
      tests = ""
      if (match(hint, / Checked by [^ ].*\.$/)) {
        tests = substr(hint, RSTART + 12); sub(/\.$/, "", tests); gsub(/,/, "", tests)
        hint = substr(hint, 1, RSTART - 1)
      }
      printf "%s\037%s\037%d\037%s\037%s\n", text, FILENAME, FNR, hint, tests
    }' $files
}

# The exercises of lab $1: its markers whose name no earlier lab has, in the order the lab's README
# numbers them (tests/graded_exercises.txt's "!order name…" rows; the grader's hints and the course
# site follow it too), then any the order does not name, by path and line.
exercises_of() {
  local lab="$1" earlier="" l
  for l in "${labs[@]}"; do
    [ "$l" = "$lab" ] && break
    earlier+=" $(markers_in "$l" | cut -d $'\037' -f1 | tr '\n' ' ')"
  done
  markers_in "$lab" | while IFS=$'\037' read -r name file line hint tests; do
    [[ " $earlier " == *" $name "* ]] && continue
    printf '%s\037%s\037%s\037%s\037%s\n' "$name" "$file" "$line" "$hint" "$tests"
  done | awk -F '\037' '
    FNR == NR { sub(/#.*/, ""); if ($1 ~ /^!order[ \t]/) { n = split($1, w, /[ \t]+/); for (i = 2; i <= n; i++) rank[w[i]] = ++r } next }
    { printf "%06d\037%06d\037%s\n", ($1 in rank ? rank[$1] : 999999), FNR, $0 }' \
    "$( [ -f "$root/tests/graded_exercises.txt" ] && echo "$root/tests/graded_exercises.txt" || echo /dev/null)" - | sort -t $'\037' -k1,1 -k2,2 | cut -d $'\037' -f3-
}

# FILE with the exercises NAMEs replaced by their stubs, on stdout.
stub_file() {  # file names…
  local file="$1"
  shift
  awk -v names=" $* " '
    function flush_stub() { for (i = 1; i <= nstub; i++) print stub[i]; nstub = 0 }
    {
      if (!inside && match($0, /\/\/ EXERCISE [a-z0-9_]+: /)) {
        name = substr($0, RSTART + 12, RLENGTH - 14)
        if (index(names, " " name " ")) {
          inside = 1; nstub = 0; line = $0
          sub(/\/\/ EXERCISE /, "// TODO EXERCISE ", line)
          print line
          next
        }
      }
      if (inside) {
        if ($0 ~ /^[ \t]*\/\/ STUB: /) {
          code = $0; indent = $0
          sub(/\/\/ STUB: .*/, "", indent); sub(/^[ \t]*\/\/ STUB: /, "", code)
          stub[++nstub] = indent code
          next
        }
        if ($0 ~ /^[ \t]*\/\/ END EXERCISE[ \t]*$/) {
          flush_stub(); print; inside = 0; next
        }
        next  # the lab code the student writes
      }
      print
    }
    END { if (inside) { print "exercise: unterminated EXERCISE in " FILENAME > "/dev/stderr"; exit 3 } }' "$file"
}

# ---------------------------------------------------------------- what a copy leaves out
# The number of lab folder $1: lab2_lighting → 2.
lab_number() { local n="${1%%_*}"; echo "${n#lab}"; }

# Reads paths on stdin and prints those whose name (any name, not only the last part) is a later
# lab's than lab $1 (a number): lab<K>_… or …_lab<K>_… with K > $1 ("lab1_camera-lab2_lighting.diff"
# is lab 2's). The one rule for the later labs' folders, shaders, scenes, test scenes, gallery
# pictures, trade-off figures and bench scripts, so a new file named like them is left out too.
# With a second argument "keep", prints the others instead.
later_lab_names() {
  awk -v n="$1" -v keep="${2:-}" -F/ '{
    later = 0
    for (i = 1; i <= NF && !later; i++) {
      rest = $i
      while (!later && match(rest, /(^|_|-)lab[0-9]+_/)) {
        k = substr(rest, RSTART, RLENGTH); gsub(/[^0-9]/, "", k)
        later = (k + 0 > n)
        rest = substr(rest, RSTART + RLENGTH)
      }
    }
    if (later != (keep == "keep")) print
  }'
}

# The project's files and folders, relative to the root, parents before children; without git
# data, build outputs and student copies (what a copy is written from).
project_paths() {
  find . \( -path ./.git -o -path './build*' -o -path ./out -o -path ./student \) -prune -o -print |
    sed -n 's|^\./||p'
}

# tests/ files that only the tests of labs after lab $1 (a number) use: every mention of them in
# tests/CMakeLists.txt is inside an `if(TARGET lab<K>_…)` block with K > $1, so a copy without those
# labs configures without them. A file mentioned anywhere else stays (better a harmless test file
# too many than a copy that does not configure); so does a file CMake does not name (a header).
later_test_files() {
  awk -v n="$1" '
    { sub(/#.*/, "") }  # CMake comments
    /^[ \t]*if[ \t]*\(/ {
      later[depth + 1] = later[depth]
      if (match($0, /TARGET[ \t]+lab[0-9]+_/)) {
        k = substr($0, RSTART, RLENGTH); gsub(/[^0-9]/, "", k)
        if (k + 0 > n) later[depth + 1] = 1
      }
      depth++
    }
    /^[ \t]*(else|elseif)[ \t]*\(/ { later[depth] = later[depth - 1] }  # runs without that lab
    /^[ \t]*endif[ \t]*\(/ { depth--; next }
    {
      line = $0
      while (match(line, /[A-Za-z0-9_.\/${}-]+\.(cpp|h|py|sh|json|obj|cmake)/)) {
        tok = substr(line, RSTART, RLENGTH); line = substr(line, RSTART + RLENGTH)
        sub(/^\$\{CMAKE_CURRENT_SOURCE_DIR\}\//, "", tok)
        if (tok ~ /\$/) continue  # a file outside tests/, or a name made up at configure time
        seen[tok] = 1
        if (!later[depth]) kept[tok] = 1
      }
    }
    END { for (t in seen) if (!(t in kept)) print "tests/" t }' tests/CMakeLists.txt |
    sort | while read -r f; do if [ -e "$f" ]; then echo "$f"; fi; done
}

# What a copy of lab $1 (a number) leaves out, one path a line (a folder stands for all it holds).
left_out() {
  local n="$1" d users scene_files
  scene_files=$(project_paths | grep '\.json$')
  {
    project_paths | later_lab_names "$n"
    echo docs/diffs  # lab N-1 → lab N is lab N's solution; the earlier ones are instructor material
    echo site        # the course site: its pages show every lab and the diffs
    echo docs/solutions  # the answers the exercises' comments do not give (instructors only)
    echo docs/solutions.md  # the instructors' policy: where every answer is, what to hand out when
    # lab 2's Blinn-Phong whole, a benchmark's fixture (bench/speed_goals.sh): an answer until lab 3
    if ((n <= 2)); then echo bench/fixtures/minimal_blinn_phong.frag; fi
    # A later lab's lesson that lives in a shared folder: lab 2's lighting doc (lab 1 has no light).
    # (tests/reference/cpu_shadow.h, lab 4's part of the reference's interface, stays: the copy's
    # tools/lab_reference.cpp includes it.)
    if ((n <= 1)); then echo docs/lighting.md; fi
    later_test_files "$n"
    # The CPU reference's source and its own tests (hand calculations that are the labs' answers):
    # a copy gets the reference prebuilt instead (reference_libs, tests/CMakeLists.txt).
    reference_source
    # A scene folder (models, textures) that only later labs' scene files use: every JSON file that
    # names it ("textures/bricks.png") is left out. A folder no JSON file names stays.
    for d in scenes/*/; do
      d="${d%/}"
      users=$(while read -r f; do
        if grep -qF "$(basename "$d")/" "$f"; then echo "$f"; fi
      done <<<"$scene_files")
      if [ -n "$users" ] && [ -z "$(later_lab_names "$n" keep <<<"$users")" ]; then echo "$d"; fi
    done
  } | topmost
}

# The oracle's source and its own tests, one path a line: what reference_libs replaces.
reference_source() {
  ls tests/reference/*.cpp
  echo tests/test_cpu_reference.cpp; echo tests/test_ideal_reference.cpp; echo tests/test_cpu_shadow.cpp
  echo tests/test_reference_lighting.cpp; echo tests/test_reference_sampling.cpp
}

# Writes the CPU reference, prebuilt, into copy $1 of lab $2 (a number): tests/reference/lib/
# libcpu_reference.a, and from lab 3 on libreference_vulkan.a (lab 3's unit tests read the device
# through it); tests/CMakeLists.txt links them where the source is missing. Built here with the
# course's platform's compiler (Debian 12 x86-64: g++ 12) and the project's release flags, without
# debug information, into build/student-reference/<hash of the sources and the compiler>/ (once
# per state of the reference; flock: copies written at the same time share it).
reference_libs() {
  local out="$1" n="$2" cxx="${CXX:-c++}" key cache f
  local -a flags=(-std=c++17 -O2 -DNDEBUG -DGLM_FORCE_DEPTH_ZERO_TO_ONE -DGLM_FORCE_RADIANS -I tests -I common/content -I common/vulkan)
  key=$( { "$cxx" --version | head -n 1; echo "${flags[*]}"; cat tests/reference/* common/content/*.h common/vulkan/*.h; } | sha256sum | cut -c1-16)
  cache="$root/build/student-reference/$key"
  mkdir -p "$root/build/student-reference"
  (
    flock 9
    if [ ! -f "$cache/done" ]; then
      rm -rf "$cache"; mkdir -p "$cache"
      for f in tests/reference/*.cpp; do echo "$f"; done |
        xargs -P 2 -I{} sh -c '"$0" "$@" -c {} -o "'"$cache"'/$(basename {} .cpp).o"' "$cxx" "${flags[@]}" \
        >"$cache/build.log" 2>&1 || { cat "$cache/build.log" >&2; die "the CPU reference did not compile (see $cache/build.log)"; }
      ar rcs "$cache/libreference_vulkan.a" "$cache/vulkan_reference.o"
      rm "$cache/vulkan_reference.o"
      ar rcs "$cache/libcpu_reference.a" "$cache"/*.o
      touch "$cache/done"
      # Only the newest state's libraries are kept.
      find "$root/build/student-reference" -mindepth 1 -maxdepth 1 -type d ! -name "$key" -exec rm -rf {} +
    fi
    mkdir -p "$out/tests/reference/lib"  # inside the lock: another state's copy may prune this one's
    cp "$cache/libcpu_reference.a" "$out/tests/reference/lib/"
    if ((n >= 3)); then cp "$cache/libreference_vulkan.a" "$out/tests/reference/lib/"; fi
  ) 9>"$root/build/student-reference/lock"
}

# Paths on stdin, sorted, without those inside another one given (a folder stands for its files).
topmost() {
  grep . | sort -u | awk '{
    path = $0; covered = 0
    while (!covered && sub(/\/[^\/]*$/, "", path)) covered = (path in listed)
    if (!covered) { listed[$0] = 1; print }
  }'
}

# ---------------------------------------------------------------- checking a copy
# Lines of a solution that a copy holds on purpose: "path-glob exercise". Keep it short; each
# entry says why the copy cannot do without that file. A new exercise whose answer turns up in one
# of these files fails the check until someone decides it belongs here.
known_answers=(
  # None: the grader's oracle, whose lines were the lab's where a formula has one way to be written
  # (the camera's columns, the light falloff), travels prebuilt (reference_libs), not as source.
)

# The solution lines of the exercises of lab $1 (a folder) and of every later lab, taken from this
# (complete) project: name US file:line US the line without any whitespace. Only "substantive"
# lines: 16 or more non-space characters. Shorter lines (braces, `return 1.0;`, `} else {`,
# `float d = 0.0;` is 12) are everywhere in the project and say nothing about the answer, while
# a line of 16 is already specific (`vec3 Q = normalize(P - E);` is 22). A line that is also one
# of the exercise's STUB lines, or part of one (a function's signature the stub keeps), is no
# answer: the copy has it on purpose. Nor is boilerplate: a line
# the project's own code also holds outside every exercise (common/, and the labs' files with their
# exercises cut), such as `for (int i = 0; i < 3; ++i) {` or a render pass's dependency field that
# common/ sets the same way. Trailing // comments are left out of both sides.
solution_lines() {
  local lab="$1" l from=0 name file line hint tests
  for l in "${labs[@]}"; do
    [ "$l" = "$lab" ] && from=1
    ((from)) || continue
    exercises_of "$l" | while IFS=$'\037' read -r name file line hint tests; do
      awk -v name="$name" -v first="$line" '
        function bare(s) { sub(/[ \t]*\/\/.*$/, "", s); gsub(/[ \t\r]+/, "", s); return s }
        FNR < first { next }
        FNR == first { next }  # the marker itself: the copy has its hint too
        /^[ \t]*\/\/ END EXERCISE[ \t]*$/ { exit }
        /^[ \t]*\/\/ STUB: / { s = $0; sub(/^[ \t]*\/\/ STUB: /, "", s); stub[bare(s)] = 1; next }
        { code[++n] = bare($0); where[n] = FILENAME ":" FNR }
        END {
          for (i = 1; i <= n; i++)
            if (length(code[i]) >= 16 && !in_stub(code[i])) printf "%s\037%s\037%s\n", name, where[i], code[i]
        }
        function in_stub(c,   t) { for (t in stub) if (index(t, c)) return 1; return 0 }' "$file"
    done
  done | awk -F '\037' '
    FNR == NR { boilerplate[$0] = 1; next }  # boilerplate_lines, below
    !($3 in boilerplate)' <(boilerplate_lines) -
}

# The code of the exercises of lab $1 (a folder) and of every later lab, as written:
# name US solution|stub US file:line US the line (stub lines without "// STUB: "). For
# scripts/comment_answers.py, which derives each solution's distinctive tokens from it.
solution_code() {  # LAB [only]: with "only", lab LAB's exercises alone
  local lab="$1" only="${2:-}" l from=0 name file line hint tests
  for l in "${labs[@]}"; do
    [ "$l" = "$lab" ] && from=1
    ((from)) || continue
    [ -n "$only" ] && [ "$l" != "$lab" ] && continue
    exercises_of "$l" | while IFS=$'\037' read -r name file line hint tests; do
      awk -v name="$name" -v first="$line" '
        FNR <= first { next }
        /^[ \t]*\/\/ END EXERCISE[ \t]*$/ { exit }
        /^[ \t]*\/\/ STUB: / { s = $0; sub(/^[ \t]*\/\/ STUB: /, "", s); printf "%s\037stub\037%s:%d\037%s\n", name, FILENAME, FNR, s; next }
        { printf "%s\037solution\037%s:%d\037%s\n", name, FILENAME, FNR, $0 }' "$file"
    done
  done
}

# Every line of the project's own code outside the exercises, without whitespace or trailing //
# comments: common/ and the labs' folders and shader folders with every exercise cut (marker to
# END EXERCISE, the STUB lines included).
boilerplate_lines() {
  { find common -type f \( -name "*.cpp" -o -name "*.h" -o -name "*.vert" -o -name "*.frag" -o -name "*.glsl" \)
    for l in "${labs[@]}"; do find "$l" "shaders/$l" -type f ! -name "*.md" 2>/dev/null; done; } |
    sort | xargs awk '
      FNR == 1 { inside = 0 }
      /\/\/ EXERCISE [a-z0-9_]+: / { inside = 1; next }
      inside && /^[ \t]*\/\/ END EXERCISE[ \t]*$/ { inside = 0; next }
      inside { next }
      { s = $0; sub(/[ \t]*\/\/.*$/, "", s); gsub(/[ \t\r]+/, "", s); if (length(s) >= 16) print s }' | sort -u
}

# --check-copy DIR LAB: is DIR a copy of lab LAB (written by this script) without answers?
#   (a) nothing --left-out lists is there, and no file or folder anywhere is named after a later lab;
#   (b) every exercise of the lab is cut out: its file has the "// TODO EXERCISE name:" line;
#   (c) no text file holds a solution line (solution_lines) of the lab's or a later lab's
#       exercises, compared without whitespace, as part of any line: a doc that quotes the answer,
#       a later lab's file, a diff, a bench script with a shader in it all count;
#   (d) no comment and no Markdown text names a distinctive token of a solution of the lab (an
#       enum, a nested call expression) that the copy's code does not hold anyway
#       (scripts/comment_answers.py);
#   (e) no declared answer form (scripts/check_answers.py, below);
#   (f) no page of the docs keeps a section that names a later lab, which the student site leaves
#       out (node site/student.mjs --check-later-labs).
# Prints one line per problem; exit 1 if there is one.
check_copy() {
  local dir="$1" lab="$2" n problems=0 p name file line hint tests
  n=$(lab_number "$lab")
  [ -d "$dir" ] || die "--check-copy: no folder $dir"
  [ -f "$dir/.student-copy" ] || { echo "FAIL $dir has no .student-copy: not written by exercise.sh"; problems=$((problems + 1)); }

  while read -r p; do
    if [ -e "$dir/$p" ]; then echo "FAIL left in the copy: $p"; problems=$((problems + 1)); fi
  done < <(left_out "$n")
  while read -r p; do
    echo "FAIL a later lab's file in the copy: $p"; problems=$((problems + 1))
  done < <(cd "$dir" && find . -print | sed -n 's|^\./||p' | later_lab_names "$n" | topmost)

  while IFS=$'\037' read -r name file line hint tests; do
    if ! grep -qF "// TODO EXERCISE $name: " "$dir/$file" 2>/dev/null; then
      echo "FAIL exercise $name is not cut out of $file"; problems=$((problems + 1))
    fi
  done < <(exercises_of "$lab")

  local answers hits=""
  answers=$(mktemp)
  solution_lines "$lab" >"$answers"
  if [ ! -s "$answers" ]; then
    echo "FAIL no solution lines found for $lab's exercises: nothing to look for"; problems=$((problems + 1))
  fi
  # Every text file (grep -I: binary files such as the PNGs are no text), hidden ones too.
  [ -s "$answers" ] && hits=$(cd "$dir" && grep -rIl --null '' . | xargs -0 -r awk -F '\037' '
    FNR == NR { name[NR] = $1; where[NR] = $2; code[NR] = $3; n = NR; next }
    {
      s = $0; gsub(/[ \t\r]+/, "", s)
      if (length(s) < 16) next
      for (i = 1; i <= n; i++)
        if (index(s, code[i])) printf "%s\037%d\037%s\037%s\n", substr(FILENAME, 3), FNR, name[i], where[i]
    }' "$answers")
  rm -f "$answers"
  local path at where known reported=0
  while IFS=$'\037' read -r path at name where; do
    [ -n "$path" ] || continue
    for known in "${known_answers[@]}"; do
      # shellcheck disable=SC2053
      if [[ "$path" == ${known%% *} && "$name" == "${known#* }" ]]; then
        echo "known: $path:$at has a line of exercise $name ($where), on purpose (known_answers)"
        continue 2
      fi
    done
    reported=$((reported + 1))
    ((reported <= 20)) && echo "FAIL answer in the copy: $path:$at holds a line of exercise $name ($where)"
  done <<<"$hits"
  ((reported > 20)) && echo "… and $((reported - 20)) more"
  problems=$((problems + reported))
  local comments
  comments=$(solution_code "$lab" only | python3 "$root/scripts/comment_answers.py" "$dir") || true
  echo "$comments" | grep -v '^FAIL' || true
  problems=$((problems + $(echo "$comments" | grep -c '^FAIL' || true)))
  echo "$comments" | grep '^FAIL' | head -n 20 || true
  # (e) no text file states an answer of the lab's or a later lab's exercises in any of the forms
  #     docs/solutions/answers.json declares (a formula, an enum, a phrase; scripts/check_answers.py).
  local declared rc=0
  declared=$(python3 "$root/scripts/check_answers.py" "$dir" "$n" 2>&1) || rc=$?
  echo "$declared"
  ((rc == 0)) || problems=$((problems + $(echo "$declared" | grep -c '^FAIL' || true) + (rc != 1)))
  # (f) the docs trimmed as the student site trims them: no section that names a later lab.
  local later
  if ! command -v node >/dev/null; then
    echo "FAIL node is missing: cannot check the copy's docs for sections about later labs (scripts/setup.sh installs Node.js)"
    problems=$((problems + 1))
  elif ! later=$(node "$root/site/student.mjs" --check-later-labs "$dir" "$n" 2>&1); then
    echo "$later"
    problems=$((problems + $(echo "$later" | grep -c '^FAIL' || true)))
    echo "$later" | grep -q '^FAIL' || problems=$((problems + 1))  # it failed without naming a page
  fi
  if ((problems)); then
    echo "check-copy: $dir: $problems problem(s) (a copy of $lab must hold none of its answers)"
    return 1
  fi
  echo "check-copy: $dir: no later lab, $(exercises_of "$lab" | wc -l) exercises cut out, no answers but the known ones"
}

# Writes a copy of every lab that has exercises into a temporary folder (no build: seconds) and
# runs CHECK DIR LAB on each; exit 1 if a check fails, 77 inside a student copy (copies are
# written from the complete project). --check-copies (CTest: student_copy_no_answers) runs
# check_copy; --check-copy-links (CTest: student_copy_links) runs copy_links.
for_each_copy() {
  local check="$1" tmp l failed=0 count=0
  if [ -f .student-copy ]; then
    echo "exercise: this is a student copy ($(head -n 1 .student-copy)): copies are written from the complete project (skipped)"
    exit 77
  fi
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  for l in "${labs[@]}"; do
    [ -n "$(exercises_of "$l")" ] || continue
    count=$((count + 1))
    bash "$root/scripts/exercise.sh" "$l" --out "$tmp/$l" >/dev/null || { echo "FAIL exercise.sh $l did not write a copy"; failed=1; continue; }
    "$check" "$tmp/$l" "$l" || failed=1
  done
  ((count)) || { echo "FAIL no lab has exercises: nothing checked"; exit 1; }
  exit "$failed"
}

# Every relative link and #anchor of the copy's Markdown files resolves (scripts/check_links.py):
# the copy leaves docs/diffs/ and the later labs out, and its links to them must have become text.
copy_links() {
  python3 "$root/scripts/check_links.py" "$1" | sed "s|^|$2 copy: |"
}

# --prove BUILD LAB [--rows] (the CTest test grader_labN): the grader's blame is measured, not
# declared. For each exercise e of LAB, the lab is built with only e stubbed (the others solved;
# one build, only the stubbed files recompiled) and the lab's whole CTest label runs against it
# (tests/grader_label_run.py: the unit and render tests, smoke runs, windows, soaks, the random
# scenes with 5 seeds a shard, the gallery; two at a time). Then:
#   (a) at least one test fails, and every failing test's message names e first (the gtests'
#       hint, tests/exercise_hints.cpp, or tests/with_exercise_hint.sh's for the others);
#   (b) every row of tests/graded_exercises.txt that lists e matches only tests that failed:
#       the table says what was measured, no more;
#   (c) with only e solved (every other exercise stubbed, but the prerequisites that
#       tests/graded_exercises.txt gives e's own code: "@e x y") one of e's own tests ("Checked
#       by") that failed in (a) passes: the test isolates e.
# Prints per exercise how many tests failed and whether each named it; writes the measurement to
# BUILD/grader/LAB.measured. --rows prints, instead of judging, the rows that say what was measured
# (each failing test → the exercises whose stub fails it), for tests/graded_exercises.txt;
# PROVE_ONLY=NAME with --rows measures that exercise alone (its rows to merge by hand).
prove() {
  local build="$1" lab="$2" rows="${3:-}"
  build="$(cd "$build" && pwd)"
  local g="$build/grader"
  local conf="$g/$lab.env"
  [ -f "$conf" ] || die "$conf is missing: configure $build first (scripts/setup.sh)"
  # shellcheck disable=SC1090
  source "$conf"
  mapfile -t all < <(exercises_of "$lab")
  if ((${#all[@]} == 0)); then
    echo "grader: $lab has no exercises (skipped)"
    exit 77
  fi
  if grep -rq --exclude=README.md "// TODO EXERCISE" "$lab" "shaders/$lab" 2>/dev/null; then
    echo "grader: this is a student copy of $lab (TODO EXERCISE markers): the grader's proof runs on the complete lab (skipped)"
    exit 77
  fi
  local python="${LAB_PYTHON:-python3}"
  command -v "$python" >/dev/null || { echo "grader: SKIPPED: python3 missing (scripts/setup.sh installs it)"; exit 77; }
  local log="$g/$lab.log" short="${lab%%_*}"
  : >"$log"
  local -a graded_targets
  IFS=';' read -r -a graded_targets <<<"$GRADED_TARGETS"
  local -a variants=()
  IFS=';' read -r -a variants <<<"${SHADER_VARIANTS:-}"
  local failures=0 names=()
  local entry name file line hint tests
  for entry in "${all[@]}"; do names+=("${entry%%$'\037'*}"); done

  # The lab's files in $g/src with the exercises NAMEs stubbed, written only where they differ
  # (make rebuilds only what changed).
  mirror() {  # [name…]
    local f
    for f in $( { find "$lab" -type f; find "shaders/$lab" -type f 2>/dev/null; } | sort); do
      mkdir -p "$g/src/$(dirname "$f")"
      if (($#)) && grep -q "// EXERCISE " "$f"; then
        stub_file "$f" "$@" >"$g/tmp"
      else
        cp "$f" "$g/tmp"
      fi
      cmp -s "$g/tmp" "$g/src/$f" || cp "$g/tmp" "$g/src/$f"
    done
  }
  compile() {
    local s newest
    mkdir -p "$g/shaders/$lab"
    newest=$(ls -t "$g/src/shaders/$lab"/* 2>/dev/null | head -n 1)
    for s in "$g/src/shaders/$lab"/*.vert "$g/src/shaders/$lab"/*.frag "$g/src/shaders/$lab"/*.comp; do
      [ -e "$s" ] || continue
      # Unchanged since its last compile: no source of the folder (its includes) is newer.
      [ "$g/shaders/$lab/$(basename "$s").spv" -nt "$newest" ] && continue
      "$GLSLANG" -V --target-env vulkan1.1 -o "$g/shaders/$lab/$(basename "$s").spv" "$s" >>"$log" 2>&1 ||
        { echo "grader: $s does not compile (see $log)"; return 1; }
    done
    local variant vname vdefine vsrc
    for variant in "${variants[@]}"; do  # lab_add_shaders(... VARIANT src name DEFINE): src with -DDEFINE
      IFS=: read -r vname vdefine vsrc <<<"$variant"
      s="$g/src/shaders/$lab/$(basename "$vsrc")"
      "$GLSLANG" -V --target-env vulkan1.1 "-D$vdefine" -o "$g/shaders/$lab/$vname.spv" "$s" >>"$log" 2>&1 ||
        { echo "grader: $s with $vdefine does not compile (see $log)"; return 1; }
    done
    "$CMAKE" --build "$build" --target "${graded_targets[@]}" exercise_hint -j2 >>"$log" 2>&1 ||
      { echo "grader: building ${graded_targets[*]} failed (see $log)"; return 1; }
  }
  # The label run against the build of the mirror: $g/runs/$1/results.tsv
  # (name, passed|failed|skipped, the exercise named first | done | -, seconds).
  label_run() {  # run-name [--only a,b]
    local dir="$g/runs/$1"
    shift
    rm -rf "$dir"
    "$python" tests/grader_label_run.py "$build" "$lab" "$g" "$dir" --jobs 2 "$@" >>"$log" 2>&1 ||
      { echo "grader: tests/grader_label_run.py failed (see $log)"; return 1; }
  }
  # The tests a graded_exercises.txt row lists exercise $1 for: its patterns, one a line.
  rows_of() { awk -v e="$1" '{ sub(/#.*/, "") } NF >= 2 && $1 !~ /^[@!]/ { for (i = 2; i <= NF; i++) if ($i == e) print $1 }' tests/graded_exercises.txt; }
  prerequisites() { awk -v e="@$1" '{ sub(/#.*/, "") } $1 == e { for (i = 2; i <= NF; i++) print $i }' tests/graded_exercises.txt 2>/dev/null; }

  local start=$SECONDS
  echo "grader: $lab, ${#all[@]} exercises, each stubbed alone against every test of label $short; building in $g"
  local -A own=() failed_of=()
  local measured="$g/$lab.measured" t state named secs pat
  : >"$measured"
  for entry in "${all[@]}"; do
    IFS=$'\037' read -r name file line hint tests <<<"$entry"
    own[$name]="$tests"
    # PROVE_ONLY=e (with --rows): measure that one exercise, e.g. after a change to what its stub breaks.
    [ -n "${PROVE_ONLY:-}" ] && [ "$name" != "$PROVE_ONLY" ] && continue
    mirror "$name"
    compile || { failures=$((failures + 1)); continue; }
    if [ "${GRADER_SCOPE:-label}" = own ]; then
      # GRADER_SCOPE=own (by hand, a quicker look; CI runs the whole label): only the tests that e's "Checked
      # by" and its graded_exercises.txt rows name run. With measured rows those are the tests that
      # fail; a test failing outside them is what only the whole label (the default) finds.
      label_run "$name" --only "$(set -f; printf '%s,' ${tests} $(rows_of "$name"))" || { failures=$((failures + 1)); continue; }
    else
      label_run "$name" || { failures=$((failures + 1)); continue; }
    fi
    local n_failed=0 n_wrong=0 ran=0 wrong=""
    failed_of[$name]=""
    while IFS=$'\t' read -r t state named secs; do
      ran=$((ran + 1))
      [ "$state" = failed ] || continue
      n_failed=$((n_failed + 1))
      failed_of[$name]+="$t "
      printf '%s\t%s\t%s\n' "$name" "$t" "$named" >>"$measured"
      if [ "$named" != "$name" ]; then
        n_wrong=$((n_wrong + 1))
        case "$named" in
          -) wrong+="       $t names no exercise"$'\n' ;;
          done) wrong+="       $t says every exercise it needs is done"$'\n' ;;
          *) wrong+="       $t names $named"$'\n' ;;
        esac
      fi
    done <"$g/runs/$name/results.tsv"
    if [ -n "$rows" ]; then
      echo "     $name: $n_failed of $ran tests fail"
      continue
    fi
    if ((n_failed == 0)); then
      echo "FAIL $name ($file:$line): stubbed alone, none of the $ran tests of $short fails"
      failures=$((failures + 1))
    elif ((n_wrong)); then
      echo "FAIL $name: stubbed alone, $n_failed of $ran tests fail and $n_wrong of them do not name it (tests/graded_exercises.txt):"
      printf '%s' "$wrong" | head -n 20
      failures=$((failures + 1))
    else
      echo "ok   $name: stubbed alone, $n_failed of $ran tests fail, every one naming it ($((SECONDS - start)) s so far)"
    fi
    # (b) every row listing e matches only tests that failed.
    while read -r pat; do
      [ -n "$pat" ] || continue
      while IFS=$'\t' read -r t state named secs; do
        # shellcheck disable=SC2053
        [[ "$t" == $pat ]] || continue
        [[ " ${failed_of[$name]} " == *" $t "* ]] && continue
        echo "FAIL $name: tests/graded_exercises.txt lists it for $pat, but $t $state with it stubbed"
        failures=$((failures + 1))
      done <"$g/runs/$name/results.tsv"
    done < <(rows_of "$name")
  done
  if [ -n "$rows" ]; then
    mirror
    compile >/dev/null || true
    echo "# ---- $short: measured by scripts/exercise.sh --prove BUILD $short --rows"
    awk -F '\t' '{ ex[$2] = ex[$2] " " $1 } END { for (t in ex) print t ex[t] }' "$measured" | sort
    exit 0
  fi
  # (c) only e (and its code's prerequisites) solved: one of its own failing tests passes.
  local -a table=() others
  local iso pre checked
  for name in "${names[@]}"; do
    checked=""
    for t in ${failed_of[$name]:-}; do
      for pat in ${own[$name]}; do
        # shellcheck disable=SC2053
        if [[ "$t" == $pat ]]; then checked+="$t,"; break; fi
      done
    done
    if [ -z "$checked" ]; then
      [ -n "${failed_of[$name]:-}" ] && { echo "FAIL $name: none of its own tests (${own[$name]}) fails with it stubbed"; failures=$((failures + 1)); }
      continue
    fi
    pre=$(prerequisites "$name" | tr '\n' ' ')
    pre="${pre% }"
    others=()
    for t in "${names[@]}"; do
      [[ "$t" == "$name" || " $pre " == *" $t "* ]] || others+=("$t")
    done
    mirror "${others[@]}"
    compile || { failures=$((failures + 1)); continue; }
    label_run "only-$name" --only "$checked" || { failures=$((failures + 1)); continue; }
    iso=$(awk -F '\t' '$2 == "passed" { print $1; exit }' "$g/runs/only-$name/results.tsv")
    if [ -z "$iso" ]; then
      echo "FAIL $name: solved with every other exercise of $lab stubbed${pre:+ but $pre}, none of ${checked%,} passes"
      failures=$((failures + 1))
    else
      table+=("$(printf '%-18s %s%s' "$name" "$iso" "${pre:+ (with the prerequisites of its code solved: $pre)}")")
    fi
  done
  mirror  # back to the complete lab
  compile >/dev/null || true
  if ((${#table[@]})); then
    echo "isolation (exercise → one of its own tests that passes with only it solved):"
    printf '  %s\n' "${table[@]}"
  fi
  echo "grader: $((SECONDS - start)) s; the failing tests of each run: $measured, their logs: $g/runs/"
  if ((failures)); then
    echo "grader: $failures problem(s); build log: $log"
    exit 1
  fi
  echo "grader: every exercise of $lab stubbed alone fails tests of $short that all name it, and a test isolates it"
}

case "${1:-}" in
  --left-out)
    [ $# -eq 2 ] || die "usage: exercise.sh --left-out LAB"
    lab=$(resolve_lab "$2")  # on its own line: a bad LAB must stop here (exit 2)
    left_out "$(lab_number "$lab")"
    exit 0
    ;;
  --check-copy)
    [ $# -eq 3 ] || die "usage: exercise.sh --check-copy DIR LAB"
    lab=$(resolve_lab "$3")
    check_copy "$2" "$lab"
    exit $?
    ;;
  --solution-code)
    [ $# -eq 2 ] || [ "${3:-}" = only ] || die "usage: exercise.sh --solution-code LAB [only]"
    lab=$(resolve_lab "$2")
    solution_code "$lab" "${3:-}"
    exit 0
    ;;
  --solution-lines)
    [ $# -eq 2 ] || die "usage: exercise.sh --solution-lines LAB"
    lab=$(resolve_lab "$2")
    solution_lines "$lab"
    exit 0
    ;;
  --check-copies)
    [ $# -eq 1 ] || die "usage: exercise.sh --check-copies"
    for_each_copy check_copy
    ;;
  --check-copy-links)
    [ $# -eq 1 ] || die "usage: exercise.sh --check-copy-links"
    for_each_copy copy_links
    ;;
  --prove)
    [ $# -eq 3 ] || { [ $# -eq 4 ] && [ "$4" = --rows ]; } || die "usage: exercise.sh --prove BUILD_DIR LAB [--rows]"
    lab=$(resolve_lab "$3")
    prove "$2" "$lab" "${4:-}"
    exit 0
    ;;
  "" | -h | --help)
    awk 'NR > 1 && !/^#/ { exit } NR > 1' "$0" | sed 's/^# \{0,1\}//'  # the header comment
    exit 0
    ;;
  --list)
    shift
    list=("${labs[@]}")
    [ $# -gt 0 ] && list=("$(resolve_lab "$1")")
    for lab in "${list[@]}"; do
      echo "$lab:"
      exercises_of "$lab" | while IFS=$'\037' read -r name file line hint tests; do
        printf '  %-14s %s:%s  (tests: %s)\n      %s\n' "$name" "$file" "$line" "${tests:-none}" "$hint"
      done
    done
    exit 0
    ;;
  --stub)
    shift
    [ $# -ge 2 ] || die "usage: exercise.sh --stub FILE NAME…"
    stub_file "$@"
    exit 0
    ;;
esac

lab=$(resolve_lab "$1")
shift
out="student/$lab"
names=()
while (($#)); do
  case "$1" in
    --out) [ $# -ge 2 ] || die "--out needs a folder"; out="$2"; shift 2 ;;
    *) names+=("$1"); shift ;;
  esac
done

mapfile -t all < <(exercises_of "$lab")
((${#all[@]})) || die "$lab has no exercises"
known=" $(printf '%s\n' "${all[@]}" | cut -d $'\037' -f1 | tr '\n' ' ') "
if ((${#names[@]} == 0)); then
  read -r -a names <<<"$known"
fi
for n in "${names[@]}"; do
  [[ "$known" == *" $n "* ]] || die "$lab has no exercise '$n' (it has:$known)"
done

# The docs are trimmed by the student site's own rule (site/student.mjs, below): it needs Node.js
# and the site's code, which only the complete project has.
[ -f "$root/site/student.mjs" ] || die "site/student.mjs is missing (a student copy?): copies are written from the complete project"
command -v node >/dev/null || die "node is missing: a copy's docs are trimmed by site/student.mjs (scripts/setup.sh installs Node.js)"

case "$(cd "$(dirname "$out")" 2>/dev/null && pwd)/$(basename "$out")" in
  "$root" | "$root/"lab* | "$root/shaders"*) die "--out $out would overwrite the project" ;;
esac
if [ -e "$out" ] && [ -n "$(ls -A "$out")" ]; then
  die "$out exists and is not empty: remove it or pass --out DIR"
fi
mkdir -p "$out"

# The project without build outputs, student copies and git data; then without what would hand
# out answers (left_out: the later labs and the instructor material, see the top of this file).
# In a git checkout: the files git tracks or would track (nothing ignored, so no node_modules, no
# GPU bundle, no caches of the instructor's machine).
if git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  git -C "$root" ls-files -z --cached --others --exclude-standard |
    while IFS= read -r -d '' f; do [ -e "$root/$f" ] && printf '%s\0' "$f"; done |
    tar -C "$root" --null -T - -cf - | tar -C "$out" -xf -
else
  tar -C "$root" --exclude='./build*' --exclude=./out --exclude=./student --exclude=./.git -cf - . | tar -C "$out" -xf -
fi
mapfile -t gone < <(left_out "$(lab_number "$lab")")
for p in "${gone[@]}"; do rm -rf "${out:?}/$p"; done
# The grader's table keeps the copy's labs: a later lab's rows name its tests and exercises.
awk -v last="# ---- lab $(($(lab_number "$lab") + 1))" 'index($0, last) == 1 { exit } { print }' \
  "$root/tests/graded_exercises.txt" >"$out/tests/graded_exercises.txt"
reference_libs "$out" "$(lab_number "$lab")"
# Links to what was left out become plain text, marked as a later lab's or instructors' material,
# so every link of the copy works (--check-copy-links).
python3 "$root/scripts/check_links.py" --unlink-missing "$out" "$(lab_number "$lab")" "$root" >/dev/null
# The docs' answer spans (<!-- answer NAME: question -->answer<!-- /answer -->) become their
# questions for this lab's and later labs' exercises (scripts/check_answers.py --rewrite).
python3 "$root/scripts/check_answers.py" --rewrite "$out" "$(lab_number "$lab")" >/dev/null
# Last of the Markdown steps: every section of the docs that names a later lab is left out, by the
# student site's rule and code (site/student.mjs, laterLabText), on the text as the copy has it, so
# the copy and its student site drop the same sections.
node "$root/site/student.mjs" --trim-later-labs "$out" "$(lab_number "$lab")" >/dev/null
# Marks the copy (tests/CMakeLists.txt: the tests of the whole project are disabled there).
printf '%s\n%s\n' "$lab" "${names[*]}" >"$out/.student-copy"

echo "exercise: $lab, student copy in $out"
declare -A done_files=()
for entry in "${all[@]}"; do
  IFS=$'\037' read -r name file line hint tests <<<"$entry"
  [[ " ${names[*]} " == *" $name "* ]] || continue
  done_files[$file]+=" $name"
done
for file in "${!done_files[@]}"; do
  # shellcheck disable=SC2086
  stub_file "$file" ${done_files[$file]} >"$out/$file"
done
# Each exercise where the copy has it (a stub is shorter than the code it replaces: the lines of
# the instructors' files would point below the TODO of a later exercise in the same file).
for entry in "${all[@]}"; do
  IFS=$'\037' read -r name file line hint tests <<<"$entry"
  [[ " ${names[*]} " == *" $name "* ]] || continue
  line=$(grep -n -m1 -F "// TODO EXERCISE $name: " "$out/$file" | cut -d: -f1)
  printf '  %-14s %s:%s\n' "$name" "$file" "$line"
done
# .exercise-stubs: each cut-out exercise's stub, "file name stub-line", so that the grader
# (tests/exercise_hints.cpp) sees an exercise as done once its code differs from the stub, whether
# or not the student keeps the TODO marker line.
{
  echo "# written by scripts/exercise.sh: the stubs of this copy's exercises (tests/exercise_hints.cpp)"
  for file in $(printf '%s\n' "${!done_files[@]}" | sort); do
    # shellcheck disable=SC2086
    awk -v names=" ${done_files[$file]} " -v file="$file" '
      match($0, /\/\/ EXERCISE [a-z0-9_]+: /) { name = substr($0, RSTART + 12, RLENGTH - 14); inside = index(names, " " name " ") > 0; next }
      inside && /^[ \t]*\/\/ END EXERCISE/ { inside = 0; next }
      inside && /^[ \t]*\/\/ STUB: / { s = $0; sub(/^[ \t]*\/\/ STUB: /, "", s); print file, name, s }
      inside && /^[ \t]*\/\/ STUB:$/ { print file, name }' "$file"
  done
} >"$out/.exercise-stubs"
short="${lab%%_*}"
earlier=""
for l in "${labs[@]}"; do [ "$l" = "$lab" ] && break; earlier+="${earlier:+, }$l"; done
cat <<EOF
It holds common/, ${earlier:+the earlier labs complete ($earlier), }$lab with the exercises above cut out,
and the tests, scenes, docs and scripts they use. Left out: the later labs (with their shaders,
scenes, tests and gallery pictures), docs/diffs/ and site/ (bash scripts/exercise.sh --left-out $short),
and the CPU reference's source: the copy's tests link it prebuilt (tests/reference/lib/, built
here for Debian 12 x86-64), with its headers.
Hand it out only as docs/solutions.md says: a copy of lab N+1 holds lab N's solutions.
Check it: bash scripts/exercise.sh --check-copy $out $short
Build and grade it:
  cd $out && bash scripts/setup.sh
  ctest --test-dir build -L $short --output-on-failure     # the grader: green when every exercise is done
Each failing test names the first unfinished exercise it needs; build/test_output/ has the pictures
(expected | actual | difference, left to right).
EOF

