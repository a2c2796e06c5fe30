"""Measuring: running the lab and the reference tools of a build.

Runner runs the lab headless with --benchmark (LP_NUM_THREADS fixed), renders the truths with
lab_reference and compares with lab_compare; measure() runs every configuration in interleaved
rounds (all configurations, then all again in another order, so that load on the shared machine
hits every configuration alike) and sums the rounds up.

Two costs per configuration: the wall-clock frame time of --benchmark and the CPU time one frame
costs (all of lavapipe's threads: the CPU seconds of the run minus those of a 1-frame run, over
the frames between). On a machine shared with others the wall clock mostly measures them; the
CPU time repeats within a few per cent.
"""
import hashlib
import json
import os
import random
import re
import statistics
import subprocess
import sys
import tempfile

from . import device, knobs
from .results import ERROR_KEYS, SHADOW_KEYS, mark_front
from .scenes import truth_of


def run(cmd, env=None, cpu=None):
    """Runs cmd, returns its output; exits on failure. cpu: a list that gets the child's CPU
    seconds (user + system, all its threads) appended."""
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    out = p.stdout.read()
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    if p.returncode != 0:
        sys.exit(f"tradeoff: {' '.join(cmd)} failed (exit {p.returncode}):\n{out}")
    if cpu is not None:
        cpu.append(usage.ru_utime + usage.ru_stime)
    return out


def parse_fields(text, prefix):
    """The key=value fields of the first line starting with `prefix` (any line with fields when
    prefix is ""), as strings: the lab's `benchmark ... min_ms=...` line, lab_compare's
    `mean_abs=...` line, lab_reference's `reference ... ms=...` line. Exits when there is none."""
    for line in text.splitlines():
        if line.startswith(prefix) or prefix == "":
            fields = dict(re.findall(r"(\w+)=([^\s]+)", line))
            if fields:
                return fields
    sys.exit(f"tradeoff: no '{prefix}' line in:\n{text}")


def cpu_ms_per_frame(cpu, frames):
    """The CPU time of one frame in ms: the seconds of a `frames`-frame run (cpu[1]) minus those
    of a 1-frame run (cpu[0]: start-up, pipeline compilation and warm-up alike), over the frames
    between them."""
    return max(0.0, (cpu[1] - cpu[0]) / (frames - 1) * 1000.0)


class Runner:
    """The lab binary, lab_reference and lab_compare of one build, and a scratch folder (tmp)
    for the scene variants, the lab's pictures and the truths."""

    def __init__(self, lab, args):
        self.lab, self.args = lab, args
        self.exe = args.exe or os.path.join(args.build, lab, lab)
        self.reference = os.path.join(args.build, "tests", "lab_reference")
        self.compare = os.path.join(args.build, "tests", "lab_compare")
        for path in (self.exe, self.reference, self.compare):
            if not os.access(path, os.X_OK):
                sys.exit(f"tradeoff: {path} not found (build first: cmake --build {args.build})")
        self.env = dict(os.environ, LP_NUM_THREADS=str(args.threads))
        self.tmp = tempfile.mkdtemp(prefix=f"tradeoff_{lab}_")
        self.truths = {}
        self.cpu_model = device.read_cpu_model()
        self.device = None  # what the first run named (device.py); every run must name the same

    def note_device(self, fields):
        """The device of a run's benchmark fields: the first sets it, a later one that differs
        ends the sweep (one device, one front)."""
        d = device.of_benchmark(fields, self.env, self.cpu_model)
        if self.device is None:
            self.device = d
        elif d != self.device:
            sys.exit(f"tradeoff: the device changed during the sweep: {device.label(self.device)}, "
                     f"then {device.label(d)}")

    def write_scene(self, scene, name):
        path = os.path.join(self.tmp, name + ".json")
        with open(path, "w") as f:
            json.dump(scene, f)
        return path

    def truth(self, scene, w, h, supersample=1):
        """The ideal reference PNG of a scene (rendered once per distinct truth). Lab 4: the
        ray-traced shadows, plus the unoccluded and unlit pictures the shadow metric needs
        (PATH.u.png, PATH.z.png)."""
        t = truth_of(scene, self.lab)
        key = hashlib.sha1((json.dumps(t, sort_keys=True) + f"{w}x{h}s{supersample}").encode()).hexdigest()[:12]
        if key not in self.truths:
            path = os.path.join(self.tmp, f"truth_{key}.png")
            truth_args = knobs.KNOBS[self.lab].get("truth", ["--ideal", "--supersample", str(supersample)])
            if truth_args == "shadow":
                truth_args = ["--unshadowed", path[:-4] + ".u.png", "--unlit", path[:-4] + ".z.png"]
            out = run([self.reference, "--lab", self.lab, "--scene", self.write_scene(t, "truth_" + key),
                       "--width", str(w), "--height", str(h)] + truth_args + ["--out", path])
            self.truths[key] = path
            print(f"  truth {key}: {parse_fields(out, 'reference')['ms']} ms", flush=True)
        return self.truths[key]

    def render(self, scene_path, w, h, frames, png=None, cpu=None, extra_args=()):
        """One --benchmark run: the fields of its `benchmark` line."""
        cmd = [self.exe, "--scene", scene_path, "--width", str(w), "--height", str(h), "--benchmark", str(frames)]
        if png:
            cmd += ["--out", png]
        if self.args.quick:
            cmd.append("--validate")  # quick runs are tests: validation on, timing not judged
        fields = parse_fields(run(cmd + list(extra_args), self.env, cpu), "benchmark")
        self.note_device(fields)
        return fields

    def frame_cpu_ms(self, scene_path, w, h, frames, png=None):
        """--benchmark `frames` (wall-clock figures) and the CPU time one frame costs (cpu_ms).
        Other users of the machine delay a frame (wall clock) but hardly change its CPU time."""
        cpu = []
        self.render(scene_path, w, h, 1, None, cpu)
        b = self.render(scene_path, w, h, frames, png, cpu)
        b["cpu_ms"] = cpu_ms_per_frame(cpu, frames)
        return b

    def redrawn_frame_cpu_ms(self, scene_path, w, h, frames, png, time_args):
        """Lab 4: the picture of the static scene gives the error; the time is a frame that
        re-renders every shadow map (`time_args`, --dev-animate-lights: what the map's resolution
        costs; a static scene pays it once). A static 1-frame run does the same work as an
        animated one (the first frame renders every map), so it serves as the CPU baseline too."""
        cpu = []
        self.render(scene_path, w, h, 1, png or os.path.join(self.tmp, "unused.png"), cpu)
        b = self.render(scene_path, w, h, frames, None, cpu, time_args)
        b["cpu_ms"] = cpu_ms_per_frame(cpu, frames)
        return b

    def compare_png(self, truth, png, heatmap=None):
        """lab_compare's figures (strings, `over_2` and `wrong_side_pct` with a % sign)."""
        cmd = [self.compare, truth, png] + (["--heatmap", heatmap] if heatmap else [])
        if knobs.KNOBS[self.lab].get("truth") == "shadow":
            cmd += ["--shadow", truth[:-4] + ".u.png", truth[:-4] + ".z.png",
                    "--band", str(knobs.KNOBS[self.lab]["band"])]
        return parse_fields(run(cmd), "mean_abs")


def select(configs, group=None, only=None):
    """The configurations of `group` (all when None) whose name matches the regular expression `only`."""
    if group:
        configs = [c for c in configs if c["group"] == group]
    if only:
        configs = [c for c in configs if re.search(only, c["config"])]
    return configs


def round_order(n, r):
    """The order of round r (0-based) over n configurations: as listed first, then shuffled with a
    fixed seed per round (repeatable), so that load from other users of the machine does not fall
    on the same configurations every round."""
    order = list(range(n))
    if r > 0:
        random.Random(r).shuffle(order)
    return order


def parse_errors(fields):
    """lab_compare's fields as numbers (the % sign dropped), those the CSV has."""
    return {k: float(fields[k].rstrip("%")) for k in ERROR_KEYS + SHADOW_KEYS if k in fields}


def measure_once(runner, lab, c, i, r, frames, w, h):
    """One run of configuration c (index i) in round r: its times appended; in the first round
    the picture is kept and compared with the truth."""
    png = os.path.join(runner.tmp, f"config_{i}.png") if r == 0 else None
    frames = max(3, frames // c.get("slow", 1))
    time_args = knobs.KNOBS[lab].get("time_args")
    if time_args:
        b = runner.redrawn_frame_cpu_ms(c["scene_path"], w, h, frames, png, time_args)
    else:
        b = runner.frame_cpu_ms(c["scene_path"], w, h, frames, png)
    c["cpu"].append(b["cpu_ms"])
    c["times"].append(float(b["median_ms"]))
    c["p95s"].append(float(b["p95_ms"]))
    if png:
        c["errors"] = parse_errors(runner.compare_png(runner.truth(c["scene"], w, h), png))


def summarize(c):
    """The rounds of c summed up: medians over the rounds, spreads (max - min), the best round."""
    c["median_ms"] = statistics.median(c["times"])
    c["p95_ms"] = statistics.median(c["p95s"])
    c["spread_ms"] = max(c["times"]) - min(c["times"])
    c["best_ms"] = min(c["times"])
    c["cpu_ms"] = statistics.median(c["cpu"])
    c["cpu_spread_ms"] = max(c["cpu"]) - min(c["cpu"])


def measure(lab, args):
    """Every selected configuration of the lab's knob table, measured in args.rounds interleaved
    rounds, summed up and marked on the front. Returns the configurations and the runner (whose
    scratch folder the caller removes)."""
    runner = Runner(lab, args)
    w, h = knobs.size(lab, args.quick)
    key = knobs.error_key(lab)
    configs = select(knobs.KNOBS[lab]["configs"](args.quick), args.group, args.only)
    for i, c in enumerate(configs):
        c["scene_path"] = runner.write_scene(c["scene"], f"config_{i}")
        c["times"], c["p95s"], c["cpu"] = [], [], []
    for r in range(args.rounds):
        for i in round_order(len(configs), r):
            c = configs[i]
            measure_once(runner, lab, c, i, r, args.frames, w, h)
            print(f"  round {r + 1}/{args.rounds} {c['group']:>22} | {c['config']:<18} "
                  f"cpu {c['cpu'][-1]:8.2f} ms  wall {c['times'][-1]:8.2f} ms  {key} {c['errors'][key]:.4f}",
                  flush=True)
    for c in configs:
        summarize(c)
    mark_front(configs, knobs.KNOBS[lab]["groups"], key)
    return configs, runner
