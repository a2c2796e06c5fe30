#!/bin/bash
# gpu_check.sh [BUILD_DIR] — prepare a run of the headless tests on a real GPU lent by the `device` tool.
#
# It packs the build with ../shared/tools/gpu_bundle.sh, adds CTest (the GPU machine has no CMake) and
# writes .gpu/check.sh. Then call the device tool:
#     run(command="bash .gpu/check.sh", carry=[".gpu"])
# check.sh prints the device and its texture precision limits, renders every lab headless with
# --validate, runs `--benchmark 300`, and runs CTest without the tests that need what the GPU machine
# lacks (Xvfb for window tests and soaks, matplotlib for tradeoff_quick, glslang/CMake for the grader,
# gallery and test_labels), then lab 4's random scenes 7300..7699 (CTest runs 0..299). Logs and
# failing tests' diff images come back under $OUT.
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root=$(git rev-parse --show-toplevel); cd "$root"
build=$(cd "${1:-build}" && pwd)
bundle=${GPU_BUNDLE:-$root/../shared/tools/gpu_bundle.sh}
[[ -f $bundle ]] || { echo "gpu_check: $bundle not found (the course's shared tools)" >&2; exit 2; }
bash "$bundle" "$build" >/dev/null
# CTest and the libraries it needs that a bare machine may lack (compressed: the carry limit is 64 MiB).
st=$(mktemp -d); mkdir -p "$st/ctestlib"
cp /usr/bin/ctest .gpu/
ldd /usr/bin/ctest | awk '/=> \//{print $3}' | grep -vE '/(libc|libm|libdl|libpthread|librt|libgcc_s|libstdc\+\+)\.so' |
  xargs -I{} cp -L {} "$st/ctestlib/"
tar czf .gpu/ctestlibs.tar.gz -C "$st" ctestlib; rm -rf "$st"
cat > .gpu/check.sh <<RUN
#!/bin/bash
set -u
G=\$(cd "\$(dirname "\$0")" && pwd)
tar xzf "\$G/bundle.tar.gz" -C /
export LD_LIBRARY_PATH=/opt/labgpu/lib VK_LAYER_PATH=/opt/labgpu/layers
for f in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json; do
  [ -f "\$f" ] && { export VK_DRIVER_FILES=\$f; break; }; done
if command -v ctest >/dev/null; then CT=ctest; else
  mkdir -p /opt/labgpu && tar xzf "\$G/ctestlibs.tar.gz" -C /opt/labgpu
  # ctest alone gets the carried libraries (through the loader), not the programs it starts.
  CT="/lib64/ld-linux-x86-64.so.2 --library-path /opt/labgpu/ctestlib:/opt/labgpu/lib \$G/ctest"; fi
vi=/opt/labgpu/bin/vulkaninfo
{ \$vi --summary 2>&1 | grep -E "deviceName|driverInfo|apiVersion" | head -3
  \$vi 2>&1 | grep -E "subTexelPrecisionBits|mipmapPrecisionBits|maxImageDimension2D" | head -3; } | tee \$OUT/device.txt
for lab in \$(ls -d $build/lab*_*/); do n=\$(basename "\$lab")
  "\$lab/\$n" --headless --validate --out \$OUT/\$n.png 2>&1 | tail -1; "\$lab/\$n" --benchmark 300 2>&1 | grep -E '^(benchmark|gpu_passes) '
done | tee \$OUT/labs.txt
cd $build && \$CT -j16 --output-on-failure -E 'window|soak|tradeoff_quick|grader|gallery|test_labels' > \$OUT/ctest.log 2>&1
grep -E "tests passed|compare \]" \$OUT/ctest.log; sed -n '/The following tests/,\$p' \$OUT/ctest.log
find $build/test_output -name '*_diff.png' | tar czf \$OUT/diffs.tgz -T - 2>/dev/null
# Lab 4's random scenes beyond CTest's shards (seeds 7300..7699, 8 parts at once; tests/lab4_random_scenes.cpp):
# the summary lines and failures in random_scenes.txt, each failing scene's pictures under random/.
for p in 0 1 2 3 4 5 6 7; do
  LAB_TEST_OUTPUT=\$OUT/random $build/tests/lab4_random_scenes --first \$((7300 + 50 * p)) --count 50 > \$OUT/random_part\$p.log 2>&1 &
done; wait
grep -h -E '^(lab4_random_scenes:|FAIL seed)' \$OUT/random_part*.log | tee \$OUT/random_scenes.txt
rm -f \$OUT/random/lab4_random/*.json
RUN
chmod +x .gpu/check.sh
echo "gpu_check: .gpu/ ready ($(du -sh .gpu | cut -f1)); now: run(command=\"bash .gpu/check.sh\", carry=[\".gpu\"])"
