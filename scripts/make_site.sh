#!/usr/bin/env bash
# make_site.sh — build the course site into OUT: site/build.mjs renders the READMEs and docs, the
# lesson diffs, the galleries, the exercises, every lab file and the time-against-error plots into
# static pages with every asset copied in (they open from file:// and from any static server, such
# as `python3 -m http.server`, with no network).
#
#   bash scripts/make_site.sh [OUT]                # the instructors' edition (default OUT build/site)
#   bash scripts/make_site.sh --student N [OUT]    # the student edition of lab N (1..4, lab2, lab2_lighting;
#                                                  # default OUT build/site-student-labN): labs 1..N, lab N's
#                                                  # exercises cut out as in the student copy, no answer
#   bash scripts/run.sh site                       # the instructors' edition after scripts/setup.sh
#
# Needs node and site/node_modules: scripts/setup.sh installs Debian's nodejs and npm and runs
# `npm ci` in site/ (the versions pinned in site/package.json and site/package-lock.json).
# CTest site_browser (site/check.mjs) builds both editions, reads every page's HTML and opens a
# sample of every kind of page in headless Chromium; site_student_no_answers (site/no_answers.mjs) checks no student page holds an answer.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
usage() { awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; }

args=()
case "${1:-}" in
  -h | --help) usage; exit 0 ;;
  --student)
    [ $# -ge 2 ] || { echo "make_site: --student needs a lab (1..4, lab2 or lab2_lighting)" >&2; exit 2; }
    args+=(--student "$2")
    shift 2
    ;;
  -*) echo "make_site: unknown option '$1' (see bash scripts/make_site.sh --help)" >&2; exit 2 ;;
esac
(($# <= 1)) || { echo "make_site: too many arguments: $* (see bash scripts/make_site.sh --help)" >&2; exit 2; }
if (($# == 1)); then args+=(--out "$(realpath -m -- "$1")"); fi

command -v node >/dev/null || { echo "make_site: node is missing: run bash scripts/setup.sh (Debian's nodejs)" >&2; exit 2; }
[ -d "$root/site/node_modules" ] ||
  { echo "make_site: site/node_modules is missing: run bash scripts/setup.sh (npm ci in site/)" >&2; exit 2; }
exec node "$root/site/build.mjs" "${args[@]}"
