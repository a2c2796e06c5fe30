#!/usr/bin/env bash
# exercise.sh — a student copy of the project, with a lab's exercises cut out.
#
#   bash scripts/exercise.sh LAB [NAME…] [--out DIR]   # write the copy (default DIR: student/<lab>)
#   bash scripts/exercise.sh --list [LAB]               # the exercises, with file, line and tests
#   bash scripts/exercise.sh --stub FILE NAME…          # print FILE with those exercises stubbed
#   bash scripts/exercise.sh --prove BUILD_DIR LAB      # the grader's own test (CTest: grader_labN)
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

# The exercises of lab $1: its markers whose name no earlier lab has.
exercises_of() {
  local lab="$1" earlier="" l
  for l in "${labs[@]}"; do
    [ "$l" = "$lab" ] && break
    earlier+=" $(markers_in "$l" | cut -d $'\037' -f1 | tr '\n' ' ')"
  done
  markers_in "$lab" | while IFS=$'\037' read -r name file line hint tests; do
    [[ " $earlier " == *" $name "* ]] && continue
    printf '%s\037%s\037%s\037%s\037%s\n' "$name" "$file" "$line" "$hint" "$tests"
  done
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

# --prove BUILD LAB (the CTest test grader_labN): the grader really grades. With the complete lab
# every test an exercise names passes; with each exercise alone cut out, at least one of them
# fails and its output names the exercise. Reuses BUILD (see the end of tests/CMakeLists.txt).
prove() {
  local build="$1" lab="$2"
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
  local log="$g/$lab.log"
  : >"$log"
  local -a graded_targets runners graded_bins
  IFS=';' read -r -a graded_targets <<<"$GRADED_TARGETS"
  IFS=';' read -r -a runners <<<"$RUNNER_BINARIES"
  IFS=';' read -r -a graded_bins <<<"$GRADED_BINARIES"
  local -a variants=()
  IFS=';' read -r -a variants <<<"${SHADER_VARIANTS:-}"
  local f failures=0

  # The lab's files in $g/src, written only where they differ (make rebuilds only what changed).
  mirror() {  # [file name…]: that file with those exercises stubbed
    local stubbed_file="${1:-}"
    shift || true
    local f
    for f in $( { find "$lab" -type f; find "shaders/$lab" -type f 2>/dev/null; } | sort); do
      mkdir -p "$g/src/$(dirname "$f")"
      if [ "$f" = "$stubbed_file" ]; then
        stub_file "$f" "$@" >"$g/tmp"
      else
        cp "$f" "$g/tmp"
      fi
      cmp -s "$g/tmp" "$g/src/$f" || cp "$g/tmp" "$g/src/$f"
    done
  }
  compile() {
    local s
    mkdir -p "$g/shaders/$lab"
    for s in "$g/src/shaders/$lab"/*.vert "$g/src/shaders/$lab"/*.frag "$g/src/shaders/$lab"/*.comp; do
      [ -e "$s" ] || continue
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
    "$CMAKE" --build "$build" --target "${graded_targets[@]}" -j2 >>"$log" 2>&1 ||
      { echo "grader: building ${graded_targets[*]} failed (see $log)"; return 1; }
  }
  # Runs the tests matching $1 (gtest patterns, space-separated) in every test binary of the lab;
  # sets ran / failed and leaves the output in $g/out.
  run_tests() {
    local filter="${1// /:}" out_dir="$g/test_output/$2" bin
    : >"$g/out"
    ran=0 failed=0
    for bin in "${runners[@]}" "${graded_bins[@]}"; do
      [ -n "$bin" ] || continue
      if LAB_EXE_DIR="$LAB_EXE_DIR" LAB_SHADER_DIR="$g/shaders/$lab" LAB_TEST_OUTPUT="$out_dir" \
           "$bin" --gtest_filter="$filter" >"$g/one" 2>&1; then :; fi
      cat "$g/one" >>"$g/out"
      ran=$((ran + $(sed -nE 's/^\[==========\] ([0-9]+) tests? from .* ran\..*/\1/p' "$g/one" | head -n 1 | grep . || echo 0)))
      failed=$((failed + $(sed -nE 's/^\[  FAILED  \] ([0-9]+) tests?, listed below:.*/\1/p' "$g/one" | head -n 1 | grep . || echo 0)))
    done
  }

  echo "grader: $lab, ${#all[@]} exercises; building the graded copy in $g"
  mirror
  compile || exit 1
  local entry name file line hint tests
  for entry in "${all[@]}"; do
    IFS=$'\037' read -r name file line hint tests <<<"$entry"
    if [ -z "$tests" ]; then
      echo "FAIL $name ($file:$line): its marker names no test (\"Checked by Suite.Test.\")"
      failures=$((failures + 1))
      continue
    fi
    run_tests "$tests" "complete"
    if ((ran == 0 || failed > 0)); then
      echo "FAIL $name: with the complete lab, $failed of $ran tests named by the exercise ($tests) fail"
      grep -E '^\[  FAILED  \]' "$g/out" | head -n 5
      failures=$((failures + 1))
    else
      echo "ok   $name: complete lab passes all $ran tests ($tests)"
    fi
  done
  for entry in "${all[@]}"; do
    IFS=$'\037' read -r name file line hint tests <<<"$entry"
    [ -n "$tests" ] || continue
    mirror "$file" "$name"
    compile || { failures=$((failures + 1)); continue; }
    run_tests "$tests" "$name"
    if ((failed == 0)); then
      echo "FAIL $name ($file:$line): with it stubbed all $ran tests ($tests) still pass: no test grades it"
      failures=$((failures + 1))
    elif ! grep -q "grades exercise \`$name\`" "$g/out"; then
      echo "FAIL $name: $failed of $ran tests fail, but none names the exercise"
      failures=$((failures + 1))
    else
      echo "ok   $name: stubbed, $failed of $ran tests fail and name it ($(grep -E '^\[  FAILED  \] [A-Za-z]' "$g/out" | sed -E 's/^\[  FAILED  \] ([^ ]+).*/\1/' | sort -u | head -n 3 | tr '\n' ' '))"
    fi
  done
  mirror  # back to the complete lab
  if ((failures)); then
    echo "grader: $failures problem(s); build log: $log"
    exit 1
  fi
  echo "grader: every exercise of $lab is graded by a test that can fail"
}

case "${1:-}" in
  --prove)
    [ $# -eq 3 ] || die "usage: exercise.sh --prove BUILD_DIR LAB"
    prove "$2" "$(resolve_lab "$3")"
    exit 0
    ;;
  "" | -h | --help)
    sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'
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

case "$(cd "$(dirname "$out")" 2>/dev/null && pwd)/$(basename "$out")" in
  "$root" | "$root/"lab* | "$root/shaders"*) die "--out $out would overwrite the project" ;;
esac
if [ -e "$out" ] && [ -n "$(ls -A "$out")" ]; then
  die "$out exists and is not empty: remove it or pass --out DIR"
fi
mkdir -p "$out"

# The project without build outputs, student copies and git data.
tar -C "$root" --exclude='./build*' --exclude=./out --exclude=./student --exclude=./.git -cf - . | tar -C "$out" -xf -

echo "exercise: $lab, student copy in $out"
declare -A done_files=()
for entry in "${all[@]}"; do
  IFS=$'\037' read -r name file line hint tests <<<"$entry"
  [[ " ${names[*]} " == *" $name "* ]] || continue
  printf '  %-14s %s:%s\n' "$name" "$file" "$line"
  done_files[$file]+=" $name"
done
for file in "${!done_files[@]}"; do
  # shellcheck disable=SC2086
  stub_file "$file" ${done_files[$file]} >"$out/$file"
done
short="${lab%%_*}"
cat <<EOF
Build and grade it:
  cd $out && bash scripts/setup.sh
  ctest --test-dir build -L $short --output-on-failure     # the grader: green when every exercise is done
Each failing test names its exercise; build/test_output/ has the pictures (actual | expected | difference).
EOF
