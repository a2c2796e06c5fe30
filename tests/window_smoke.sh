#!/usr/bin/env bash
# window_smoke.sh LAB_EXE [FRAMES] — the lab in a real window under xvfb-run: FRAMES frames
# (default 30) with --validate. Judged on the lab's own exit code, written to a file by the shell
# that ran it inside xvfb-run (xvfb-run's exit code and its messages about starting or stopping
# the X server are not the lab's), and on its status file (--dev-status-file, common/dev/status_file.h):
# the last line must say that frame FRAMES was drawn.
# Pass: exit code 0 (the lab exits 1 after any validation message), no "validation" in its output,
# FRAMES frames drawn.
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
exe="$1"
frames="${2:-30}"
name="$(basename "$exe")"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT

# Inside xvfb-run: the lab, then its exit code into a file.
inner="'$exe' --validate --dev-status-file '$dir/status' --frames $frames >'$dir/out.txt' 2>&1; echo \$? >'$dir/exit'"
xvfb_code=0
xvfb-run -a -s "-screen 0 1280x800x24" sh -c "$inner" >"$dir/xvfb.txt" 2>&1 || xvfb_code=$?

fail() {
  echo "FAIL: $name: $*"
  echo "--- $name output:"; cat "$dir/out.txt" 2>/dev/null || true
  echo "--- xvfb-run (exit code $xvfb_code):"; cat "$dir/xvfb.txt"
  exit 1
}
[ -s "$dir/exit" ] || fail "the lab did not run to the end (no exit code written)"
code="$(cat "$dir/exit")"
[ "$code" = 0 ] || fail "exit code $code"
! grep -qi "validation" "$dir/out.txt" || fail "a validation message"
last="$(cat "$dir/status" 2>/dev/null || true)"
[[ "$last" =~ ^frame=([0-9]+) ]] || fail "no frame drawn (status file: '$last')"
[ "${BASH_REMATCH[1]}" = "$frames" ] || fail "drew ${BASH_REMATCH[1]} frames, not $frames"
echo "$name: exit code 0, $frames frames drawn ($last), validation clean (xvfb-run exit code $xvfb_code)"
