#!/usr/bin/env bash
# make_site.sh — build the course site into OUT (default build/site/): site/build.mjs renders the
# READMEs and docs, the lesson diffs, the galleries, the exercises and the time-against-error plots
# into static pages with every asset copied in (they open from file:// and from any static server,
# such as `python3 -m http.server`, with no network).
#
#   bash scripts/make_site.sh [OUT]
#   bash scripts/run.sh site          # the same after scripts/setup.sh, then prints where to open it
#
# Needs node and site/node_modules: scripts/setup.sh installs Debian's nodejs and npm and runs
# `npm ci` in site/ (the versions pinned in site/package.json and site/package-lock.json).
# CTest site_browser (site/check.mjs) builds the site and checks every page in headless Chromium.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/build/site}")"

command -v node >/dev/null || { echo "make_site: node is missing: run bash scripts/setup.sh (Debian's nodejs)" >&2; exit 1; }
[ -d "$root/site/node_modules" ] ||
  { echo "make_site: site/node_modules is missing: run bash scripts/setup.sh (npm ci in site/)" >&2; exit 1; }
node "$root/site/build.mjs" --out "$out"
