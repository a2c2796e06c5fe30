#!/bin/bash
# gpu_check.sh [BUILD_DIR] — prepare a run of the headless tests on a real GPU lent by the `device` tool.
#
# It packs the build with ../shared/tools/gpu_bundle.sh and writes .gpu/check.sh. Then call the device tool:
#     run(command="bash .gpu/check.sh", carry=[".gpu"])
# check.sh, on the GPU machine:
#   - prints the device and its texture precision limits;
#   - renders every lab headless with --validate and runs `--benchmark 300`;
#   - times lab 4 animated from a cold GPU with and without the benchmark's one-second warm-up, the
#     GPU's clocks each second in clocks_per_second.txt;
#   - times each of lab 3's sampler settings (the rows of sampler_errors.md, which the render test
#     writes there) at 1280x720: the GPU's time against error;
#   - runs tests/gpu_passes.py on lab 4's every-map scene (where the machine has python3);
#   - measures what the GPU's pixels cost (pixel_rate.txt): lab 1 at four picture sizes, and lab 4
#     with one directional map holding no caster (cleared and stored only) at 2048² and 4096²;
#   - runs every GoogleTest program (the render tests against the reference; the script tests need
#     Python, CMake, Xvfb, which the GPU machine lacks), lab 4's random-scene regressions, then its
#     random scenes 7300..7699 (CTest runs 0..299) and the translucent stacks 0..399.
# Logs and failing tests' diff images come back under $OUT.
set -euo pipefail
# -h / --help: the comment at the top of this file, nothing run.
case "${1:-}" in -h | --help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; exit 0 ;; esac
root=$(git rev-parse --show-toplevel); cd "$root"
build=$(cd "${1:-build}" && pwd)
bundle=${GPU_BUNDLE:-$root/../shared/tools/gpu_bundle.sh}
[[ -f $bundle ]] || { echo "gpu_check: $bundle not found (the course's shared tools)" >&2; exit 2; }
bash "$bundle" "$build" >/dev/null
# Lab 4's scene with one shadow-casting light, the directional, and no caster: its map is only
# cleared and stored. Paths made absolute by tradeoff_lib's load_scene() (the file lives in .gpu/;
# the sources sit at the same path on the GPU machine).
for r in 2048 4096; do
  PYTHONPATH="$root/bench" python3 - "$r" > ".gpu/empty_map_$r.json" <<'PY'
import json, sys
from tradeoff_lib.scenes import load_scene
scene = load_scene("lab4_shadows.json")
for i, light in enumerate(scene["lights"]):
    light["cast_shadows"] = i == 0
scene["lights"][0].setdefault("shadow", {})["resolution"] = int(sys.argv[1])
for obj in scene["objects"]:
    obj["cast_shadows"] = False
json.dump(scene, sys.stdout, indent=1)
PY
done
cat > .gpu/check.sh <<RUN
#!/bin/bash
set -u
G=\$(cd "\$(dirname "\$0")" && pwd)
tar xzf "\$G/bundle.tar.gz" -C /
export LD_LIBRARY_PATH=/opt/labgpu/lib VK_LAYER_PATH=/opt/labgpu/layers
for f in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json; do
  [ -f "\$f" ] && { export VK_DRIVER_FILES=\$f; break; }; done
vi=/opt/labgpu/bin/vulkaninfo
{ \$vi --summary 2>&1 | grep -E "deviceName|driverInfo|apiVersion" | head -3
  \$vi 2>&1 | grep -E "subTexelPrecisionBits|mipmapPrecisionBits|maxImageDimension2D" | head -3
  \$vi 2>&1 | grep -E "^\s*(samplerAnisotropy|fillModeNonSolid|wideLines|depthClamp|depthBiasClamp|fragmentStoresAndAtomics|timestampComputeAndGraphics)\s*=" | sort -u; } | tee \$OUT/device.txt
for lab in \$(ls -d $build/lab*_*/); do n=\$(basename "\$lab")
  "\$lab/\$n" --headless --validate --out \$OUT/\$n.png 2>&1 | tail -1; "\$lab/\$n" --benchmark 300 2>&1 | grep -E '^(benchmark|gpu_passes) '
done | tee \$OUT/labs.txt
# The GPU's clock while the benchmarks run (nvidia-smi, where the driver has it; read only, nothing
# set): the limits in clocks.txt, one line a second in clocks_per_second.txt. Then lab 4 animated
# from a cold GPU with the warm-up of before 27 Nov 2026 (three frames, --dev-warmup-ms 0) against
# the default (a second at least).
smi=\$(command -v nvidia-smi || ls /usr/local/nvidia/bin/nvidia-smi 2>/dev/null || true)
[ -n "\$smi" ] && { \$smi --query-gpu=clocks.sm,clocks.max.sm,clocks.mem,pstate --format=csv | tee \$OUT/clocks.txt
  \$smi --query-gpu=timestamp,clocks.sm,clocks.mem,pstate,utilization.gpu --format=csv,noheader -lms 200 > \$OUT/smi.csv 2>&1 & smi_pid=\$!; }
for w in 0 1000 0 1000; do
  echo "lab4 animated warm-up \$w ms: \$($build/lab4_shadows/lab4_shadows --dev-animate-lights --benchmark 300 --dev-warmup-ms \$w 2>&1 | grep -E '^(benchmark|gpu_passes) ' | tr '\\n' ' ')"
done | tee \$OUT/warmup.txt
# Lab 4 with its maps re-rendered every frame (issue: ≤ 1 ms on an H200): the default scene, swlike
# and the gallery's translucent layers, two rounds each, with the GPU time of every pass.
for r in 1 2; do for v in animated swlike layers; do
  a=(--dev-animate-lights); [ \$v = swlike ] && a+=(--scene $root/scenes/bench/swlike_shadows.json)
  [ \$v = layers ] && a+=(--scene $root/docs/images/lab4_shadows/scenes/translucent_layers.json)
  echo "lab4 \$v round \$r: \$($build/lab4_shadows/lab4_shadows "\${a[@]}" --benchmark 300 2>&1 | grep -E '^(benchmark|gpu_passes) ' | tr '\\n' ' ')"
done; done | tee \$OUT/lab4_animated.txt
# What the GPU's pixels cost (docs/performance.md, "Lab 4 on a GPU"): GPU time linear in
# the pixels written means every pass is bound by writing them.
for wh in 640x360 1280x720 2560x1440 5120x2880; do
  echo "lab1 \$wh: \$($build/lab1_camera/lab1_camera --width \${wh%x*} --height \${wh#*x} --benchmark 300 2>&1 | grep -E '^gpu_passes ')"
done | tee \$OUT/pixel_rate.txt
for r in 2048 4096; do
  echo "lab4 empty \${r}² map: \$($build/lab4_shadows/lab4_shadows --dev-animate-lights --scene \$G/empty_map_\$r.json --benchmark 300 2>&1 | grep -E '^gpu_passes ')"
done | tee -a \$OUT/pixel_rate.txt
# tests/gpu_passes.py on this device (where python3 is there): per-pass times that cannot overlap,
# whatever the GPU runs in parallel (common/dev/gpu_timer.h).
if command -v python3 >/dev/null; then python3 $root/tests/gpu_passes.py $build/lab4_shadows/lab4_shadows lab4_maps 2>&1 | tail -3
else echo "gpu_passes: no python3 on this machine: not run"; fi | tee \$OUT/gpu_passes.txt
# The GoogleTest programs, run directly (CTest and the libraries it needs would not fit the 64 MiB
# the device tool carries), eight at a time; each program's log, and the failures in gtest.txt.
ls $build/tests/test_* | grep -vE '\\.cmake\$|_tests\\.cmake' | while read -r t; do [ -x "\$t" ] && echo "\$t"; done |
  xargs -P8 -I{} sh -c '"\$1" --gtest_brief=1 > \$OUT/gtest_\$(basename "\$1").log 2>&1; echo "\$(basename "\$1") rc=\$?"' _ {} | sort | tee \$OUT/gtest.txt
grep -h -E '^\\[  (PASSED|FAILED) |^\\[  FAILED  \\]' \$OUT/gtest_*.log | sort | uniq -c | tee -a \$OUT/gtest.txt
# The device tool brings back a limited number of files: the logs go back as one archive.
(cd \$OUT && tar czf gtest_logs.tgz gtest_*.log && rm -f gtest_*.log)
# Lab 3's sampler settings on this GPU: the error of each against the supersampled truth
# (Lab3Filtering.AnisotropyLowersTheErrorAgainstTheGroundTruth wrote sampler_errors.md and each
# row's scene, truth_N.json, in the order of its rows) and its GPU time at 1280x720: the GPU's front.
# (this GPU's file: the GoogleTest programs above just wrote it)
cp $build/test_output/lab3/sampler_errors.md \$OUT/ 2>/dev/null
for n in \$(ls $build/test_output/lab3/ | sed -n 's/^truth_\([0-9]*\)[.]json\$/\1/p' | sort -n); do
  echo "truth_\$n \$($build/lab3_textures/lab3_textures --scene $build/test_output/lab3/truth_\$n.json --width 1280 --height 720 --benchmark 300 2>&1 | grep -E '^(benchmark|gpu_passes) ' | grep -oE '(median_ms|main_pass_ms)=[0-9.]+' | tr '\n' ' ')"
done | tee \$OUT/lab3_sampler_times.txt
$build/tests/lab4_random_scenes --seeds 7638,7678 > \$OUT/random_regressions.log 2>&1; tail -2 \$OUT/random_regressions.log
find $build/test_output -name '*_diff.png' | tar czf \$OUT/diffs.tgz -T - 2>/dev/null
[ -f \$OUT/smi.csv ] && { kill \$smi_pid 2>/dev/null; awk -F', ' '{ split(\$1, t, " "); s = substr(t[2], 1, 8); if (s != last) print s, \$2, \$3, \$4, \$5; last = s }' \$OUT/smi.csv > \$OUT/clocks_per_second.txt; rm \$OUT/smi.csv; }
# Lab 4's random scenes beyond CTest's shards (seeds 7300..7699, 8 parts at once; tests/lab4_random_scenes.cpp):
# the summary lines and failures in random_scenes.txt, each failing scene's pictures under random/.
for p in 0 1 2 3 4 5 6 7; do
  LAB_TEST_OUTPUT=\$OUT/random $build/tests/lab4_random_scenes --first \$((7300 + 50 * p)) --count 50 > \$OUT/random_part\$p.log 2>&1 &
done; wait
grep -h -E '^(lab4_random_scenes:|FAIL seed)' \$OUT/random_part*.log | tee \$OUT/random_scenes.txt
# The same for the translucent stacks (lab4_random_scenes --translucent-stacks), seeds 0..399.
for p in 0 1 2 3 4 5 6 7; do
  LAB_TEST_OUTPUT=\$OUT/stacks $build/tests/lab4_random_scenes --translucent-stacks --first \$((50 * p)) --count 50 > \$OUT/stacks_part\$p.log 2>&1 &
done; wait
grep -h -E '^(lab4_random_scenes:|FAIL seed)' \$OUT/stacks_part*.log | tee \$OUT/stacks_scenes.txt
rm -f \$OUT/stacks/lab4_random/*.json
rm -f \$OUT/random/lab4_random/*.json
RUN
chmod +x .gpu/check.sh
# The device tool carries at most 64 MiB; the build's test by-products (the grader's and the site's
# copies, test_output/) can push the bundle past it.
[ "$(du -sm .gpu | cut -f1)" -le 60 ] || echo "gpu_check: .gpu/ is $(du -sh .gpu | cut -f1), near the device tool's 64 MiB: delete $build/grader, $build/site-no-answers and $build/test_output (tests remake them) and run again" >&2
echo "gpu_check: .gpu/ ready ($(du -sh .gpu | cut -f1)); now: run(command=\"bash .gpu/check.sh\", carry=[\".gpu\"])"
