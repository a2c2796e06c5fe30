#!/usr/bin/env bash
# setup.sh — install the Debian 12 packages the labs need, configure and build.
#
#   bash scripts/setup.sh            # packages (only if missing) + configure + build
#   LAB_BUILD_DIR=build-asan LAB_CMAKE_ARGS=-DLAB_SANITIZE=ON bash scripts/setup.sh
#
# Idempotent: apt-get runs only when a package is missing. Uses sudo when not root.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAB_BUILD_DIR:-$root/build}"

packages=(
  build-essential cmake pkg-config
  patch                        # make_diffs.sh --check applies the instructor diffs
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libglfw3-dev libglm-dev libstb-dev libimgui-dev nlohmann-json3-dev libtinyobjloader-dev
  libgtest-dev
  assimp-testmodels            # real-world OBJ files for the mesh loader tests
  xvfb xauth                   # window tests run under a virtual X server
  xdotool libx11-dev           # the on-demand window test: pointer and keys, closing the window
  openbox x11-utils            # the window soak (bench/soak.py): a window manager, xprop
  graphviz                     # docs/architecture.md's picture of the layers (scripts/make_architecture.sh)
  python3-matplotlib python3-numpy  # bench/tradeoff.py: time-against-error plots
)

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

# shellcheck disable=SC2086
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo ${LAB_CMAKE_ARGS:-} >/dev/null
cmake --build "$build" -j"$(nproc)"
echo "setup: built into $build"
