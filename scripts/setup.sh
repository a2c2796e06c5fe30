#!/usr/bin/env bash
# setup.sh — install the Debian 12 packages the labs need, configure and build.
#
#   bash scripts/setup.sh            # packages (only if missing) + site/node_modules + configure + build
#   bash scripts/setup.sh --no-build # packages and site/node_modules only (scripts/run.sh site)
#   LAB_BUILD_DIR=build-asan LAB_CMAKE_ARGS=-DLAB_SANITIZE=ON bash scripts/setup.sh
#
# Idempotent: apt-get runs only when a package is missing, `npm ci` only when site/node_modules is
# missing or older than site/package-lock.json. Uses sudo when not root.
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAB_BUILD_DIR:-$root/build}"
no_build=0
[ "${1:-}" = --no-build ] && no_build=1

packages=(
  build-essential cmake pkg-config
  patch                        # make_diffs.sh --check applies the instructor diffs
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  vulkan-tools                 # vulkaninfo: scripts/gpu_check.sh packs it for a lent GPU
  libglfw3-dev libglm-dev libstb-dev libimgui-dev nlohmann-json3-dev libtinyobjloader-dev
  libgtest-dev
  assimp-testmodels            # real-world OBJ files for the mesh loader tests
  xvfb xauth                   # window tests run under a virtual X server
  xdotool libx11-dev           # the on-demand window test: pointer and keys, closing the window
  openbox x11-utils            # the window soak (bench/soak.py): a window manager, xprop
  graphviz                     # docs/architecture.md's picture of the layers (scripts/make_architecture.sh)
  python3-matplotlib python3-numpy  # bench/tradeoff.py: time-against-error plots
  chromium                     # the course site's browser test (site/check.mjs, CTest site_browser)
  bubblewrap                   # scripts/grade.sh runs student code in its sandbox (bwrap)
  ccache                       # scripts/grade.sh: the pristine copy's second build reuses the first's objects
)
# Node.js and npm build the course site (scripts/make_site.sh): Debian's, unless a node and an npm
# are already installed (another nodejs package, such as NodeSource's, conflicts with Debian's npm).
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then packages+=(nodejs npm); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}"
else
  echo "setup: all ${#packages[@]} packages present"
fi

# The site's JavaScript tools, exactly as site/package-lock.json pins them. Without the npm registry
# this fails: one line says so, the rest goes on, and the site test (site_browser) skips saying why.
site="$root/site"
if [ ! -d "$site" ]; then
  :  # a student copy (scripts/exercise.sh) has no course site
elif [ ! -f "$site/node_modules/.package-lock.json" ] || [ "$site/package-lock.json" -nt "$site/node_modules/.package-lock.json" ]; then
  if npm_log=$(cd "$site" && npm ci --no-audit --no-fund 2>&1); then
    echo "setup: site/node_modules installed (npm ci)"
  else
    rm -rf "$site/node_modules"  # nothing half-installed: the site test then skips, saying why
    echo "setup: npm ci in site/ failed ($( (grep -m 1 -iE 'npm (err|error)' <<<"$npm_log" || tail -n 1 <<<"$npm_log") | cut -c 1-160)): no course site; site_browser will skip"
  fi
fi
((no_build)) && exit 0

# shellcheck disable=SC2086
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo ${LAB_CMAKE_ARGS:-} >/dev/null
cmake --build "$build" -j"$(nproc)"
echo "setup: built into $build"
