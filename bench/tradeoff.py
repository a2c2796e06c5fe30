#!/usr/bin/env python3
"""tradeoff.py — frame time against error for one lab's knobs (docs/tradeoffs.md).

    python3 bench/tradeoff.py LAB [--quick] [--build DIR] [--out-dir DIR] [--frames N] [--rounds R]

For every configuration in the lab's knob table (KNOBS below) the script writes a scene
file, runs the lab headless with --benchmark (LP_NUM_THREADS fixed; the same process
writes its last frame to a PNG) and compares that PNG with the ideal reference
(`lab_reference --ideal`: exact curved surfaces, per-pixel exact normals; lab 3: the
supersampled texture, `lab_reference --supersample 16`; lab 4: the ray-traced shadows with the shadow
error metric, `lab_compare --shadow`) using `lab_compare`. Rounds are interleaved (all configurations, then all again, in another
order) so that load on the shared machine hits every configuration alike.

Two costs per configuration: the wall-clock frame time of --benchmark (median of the
rounds' medians, their spread, the best round) and the CPU time one frame costs (all of
lavapipe's threads; the CPU seconds of the run minus those of a 1-frame run, over the
frames between). On a machine shared with others the wall clock mostly measures them
(x2-3 between rounds); the CPU time repeats within a few per cent, so the front is drawn
on it.

Writes OUT_DIR/LAB.csv and OUT_DIR/LAB.png (time against error, the Pareto front drawn,
the default and the seeds' configurations labelled), and in a full run the README
heatmaps. --quick: a handful of configurations at 320×180 with validation on, written to
build/tradeoff_quick/, then checks that the CSV is well-formed and that the error grows
when the tessellation drops (lab 3: that trilinear filtering beats nearest) (exit code 1
otherwise). CTest runs it.

To add a lab: write a function returning its configurations (see lab1_configs) and add
it to KNOBS; groups with "front": True get a Pareto front.
"""
import argparse
import copy
import csv
import hashlib
import json
import math
import os
import random
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PRIMITIVES = {"plane", "cube", "sphere", "icosphere", "icosahedron", "cylinder", "cone", "torus"}
ERROR_KEYS = ["mean_abs", "p99_abs", "max_abs", "over_2", "mean_de2000", "p99_de2000"]
CSV_FIELDS = (["lab", "group", "config", "knob", "default", "seed", "cpu_ms", "cpu_spread_ms", "median_ms", "p95_ms",
               "spread_ms", "best_ms", "rounds", "round_ms"]
              + ERROR_KEYS + ["on_front", "dominated_by"])


# ---------------------------------------------------------------------------
# Scenes
# ---------------------------------------------------------------------------

def load_scene(name):
    """A scene from scenes/, with model paths made absolute (variants are written elsewhere)."""
    path = os.path.join(ROOT, "scenes", name)
    with open(path) as f:
        scene = json.load(f)
    for obj in scene["objects"]:
        if obj["mesh"] not in PRIMITIVES and not os.path.isabs(obj["mesh"]):
            obj["mesh"] = os.path.normpath(os.path.join(os.path.dirname(path), obj["mesh"]))
    return scene


def tessellate(scene, s):
    """Every curved primitive at 'level' s: sphere s × s/2, cylinder and cone s, torus 1.5·s × s/2.
    s = 32 is exactly the primitives' defaults (docs/meshes.md: 32×16, 32, 32, 48×16)."""
    out = copy.deepcopy(scene)
    for obj in out["objects"]:
        m = obj["mesh"]
        if m == "sphere":
            obj["segments"], obj["rings"] = s, max(2, s // 2)
        elif m in ("cylinder", "cone"):
            obj["segments"] = s  # rings: the default single band (the side is straight)
            obj.pop("rings", None)
        elif m == "torus":
            obj["segments"], obj["rings"] = max(3, (3 * s) // 2), max(3, s // 2)
    return out


def set_mesh(scene, mesh, segments, rings):
    out = copy.deepcopy(scene)
    for obj in out["objects"]:
        if obj["mesh"] == mesh:
            obj["segments"] = segments
            if rings:
                obj["rings"] = rings
    return out


def truth_of(scene, lab=""):
    """What the ideal reference depends on: the scene without tessellation and shading model.
    Lab 4's truth is the same scene (same meshes, same samplers) with exact shadows: only the
    lights' shadow-map settings do not matter to it."""
    t = copy.deepcopy(scene)
    if lab == "lab4_shadows":
        for light in t.get("lights", []):
            light.pop("shadow", None)
        return t
    for obj in t["objects"]:
        obj.pop("segments", None)
        obj.pop("rings", None)
    t.get("lighting", {}).pop("shading", None)
    for m in t.get("materials", {}).values():
        # Lab 3: the filtering ground truth does not depend on the sampler's filter (only on its wrap).
        for k in ("filter", "mipmaps", "anisotropy"):
            m.get("sampler", {}).pop(k, None)
    return t


def config(name, group, scene, knob="", default=False, seed="", series=""):
    """One configuration. `series` names a run of configurations in which only the
    tessellation changes (ordered by `knob`, finer = larger): the quick check demands that
    the error falls along it."""
    return {"config": name, "group": group, "scene": scene, "knob": knob, "default": default, "seed": seed,
            "series": series}


# ---------------------------------------------------------------------------
# The knob tables
# ---------------------------------------------------------------------------

def lab1_configs(quick):
    base = load_scene("lab1_camera.json")
    levels = [8, 16, 32, 64] if quick else [8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256]
    out = [config(f"all curved at {s}", "tessellation", tessellate(base, s), knob=s, default=(s == 32),
                  series="all") for s in levels]
    if not quick:
        # One primitive at a time around the defaults: is each default on the front by itself?
        default = tessellate(base, 32)
        for mesh, variants in [("sphere", [(16, 16), (32, 8), (32, 32), (64, 16), (64, 32)]),
                               ("cylinder", [(16, 0), (64, 0)]), ("cone", [(16, 0), (64, 0)]),
                               ("torus", [(24, 16), (48, 8), (48, 24), (96, 16), (96, 32)])]:
            for seg, rings in variants:
                name = f"{mesh} {seg}" + (f"x{rings}" if mesh in ("sphere", "torus") else "")
                out.append(config(name, "tessellation", set_mesh(default, mesh, seg, rings),
                                  knob=seg * max(rings, 1)))
    return out


def many_lights(n):
    """The first n of lab2_many_lights.json's 8 + 32 + 32 lights, the types taken in turn."""
    lights = load_scene("lab2_many_lights.json")["lights"]
    by_type = [[l for l in lights if l["type"] == t] for t in ("directional", "point", "spot")]
    order = []
    while any(by_type):
        for group in by_type:
            if group:
                order.append(group.pop(0))
    return order[:n]


def lab2_configs(quick):
    base = load_scene("lab2_lighting.json")
    base.setdefault("lighting", {})["markers"] = False  # the reference has no light markers
    out = []
    # Shading × tessellation, against per-pixel shading of the exact surfaces.
    levels = [8, 16, 32] if quick else [8, 16, 32, 64, 128]
    shadings = ["flat", "phong"] if quick else ["flat", "gouraud", "phong"]
    for shading in shadings:
        for s in levels:
            scene = tessellate(base, s)
            scene["lighting"]["shading"] = shading
            seed = ""
            if shading == "phong" and s == 32:
                seed = "seed 000"  # Blinn-Phong per pixel, 1 directional + 2 point + 1 spot light
            out.append(config(f"{shading} {s}", "shading x tessellation", scene, knob=s,
                              default=(shading == "phong" and s == 32), seed=seed, series=shading))
    # Each lighting model at equal scene (default tessellation, per-pixel shading), each
    # against its own truth.
    models = ["lambert", "blinn_phong"] if quick else \
        ["lambert", "phong", "blinn_phong", "toon", "oren_nayar", "minnaert", "cook_torrance", "ward"]
    for model in models:
        scene = copy.deepcopy(base)
        scene["lighting"]["model"] = model
        seed = "seed 001" if model == "phong" else ""  # the Phong lighting model
        out.append(config(model, "lighting model", scene, default=(model == "blinn_phong"), seed=seed))
    # Light count (the default scene's objects, lights from lab2_many_lights.json).
    counts = [1, 8] if quick else [1, 2, 4, 8, 16, 32, 72]
    for n in counts:
        scene = copy.deepcopy(base)
        scene["lights"] = many_lights(n)
        c = config(f"{n} lights", "light count", scene, knob=n)
        if n >= 32:
            c["slow"] = 2  # about a second a frame: half the frames
        out.append(c)
    return out


# Lab 3: the sampler settings of bench/lab3_samplers.sh and the test
# Lab3Filtering.AnisotropyLowersTheErrorAgainstTheGroundTruth, on the grazing floor.
LAB3_SAMPLERS = [
    ("nearest", {"filter": "nearest", "mipmaps": "none", "anisotropy": 1}),
    ("linear, no mipmaps", {"filter": "linear", "mipmaps": "none", "anisotropy": 1}),
    ("trilinear", {"filter": "linear", "mipmaps": "linear", "anisotropy": 1}),
    ("trilinear + aniso 2", {"filter": "linear", "mipmaps": "linear", "anisotropy": 2}),
    ("trilinear + aniso 4", {"filter": "linear", "mipmaps": "linear", "anisotropy": 4}),
    ("trilinear + aniso 8", {"filter": "linear", "mipmaps": "linear", "anisotropy": 8}),
    ("trilinear + aniso 16", {"filter": "linear", "mipmaps": "linear", "anisotropy": 16}),
]


def lab3_configs(quick):
    """Sampler settings on scenes/lab3_floor.json (a tiled floor seen at a grazing angle), each
    against the texture averaged over every pixel's footprint (lab_reference --supersample 16).
    The default sampler (docs/scene-format.md) is seed 002's: linear, linear mips, anisotropy 16."""
    base = load_scene("lab3_floor.json")
    for m in base["materials"].values():
        if "albedo_map" in m and not os.path.isabs(m["albedo_map"]):
            m["albedo_map"] = os.path.join(ROOT, "scenes", m["albedo_map"])
    names = ["nearest", "trilinear", "trilinear + aniso 16"] if quick else [n for n, _ in LAB3_SAMPLERS]
    out = []
    for name, sampler in LAB3_SAMPLERS:
        if name not in names:
            continue
        scene = copy.deepcopy(base)
        scene["materials"]["floor"]["sampler"] = dict(scene["materials"]["floor"]["sampler"], **sampler)
        default = name == "trilinear + aniso 16"
        out.append(config(name, "sampler", scene, knob=sampler["anisotropy"], default=default,
                          seed="seed 002" if default else ""))
    return out


# Lab 4: shadow-map resolution x PCF kernel x filter, on the default scene and on a hard stress
# scene, each against the ray-traced shadows (lab_reference --lab lab4_shadows) with the shadow
# error metric (docs/testing.md): wrong-side pixels outside a band of k = 4 px (the widest kernel
# compared, 7x7: radius 3 texels + 1) and the MAE over the shadow receivers.
LAB4_RESOLUTIONS = [512, 1024, 2048, 4096]
LAB4_KERNELS = [1, 3, 5, 7]
LAB4_FILTERS = ["nearest", "bilinear"]
# The seed's configuration (000_...): one 2048^2 map, 3x3 PCF by hand, LearnOpenGL's constant depth
# bias 0.005, expressed in our keys (lab4_shadows/README.md: 83886 = 0.005 * 2^24 depth units).
LAB4_SEED = {"resolution": 2048, "pcf": 3, "filter": "nearest", "bias": 83886, "slope_bias": 0, "normal_offset": 0}
LAB4_DEFAULT = {"resolution": 2048, "pcf": 1, "filter": "nearest"}  # lab::ShadowDesc's defaults (scene.h)


def lab4_stress_scene():
    """tests/scenes/lab4_grazing.json: long, thin shadows at a grazing light: thin posts and a
    slatted fence on a floor, a directional light 10 degrees above the horizon and a spot light
    low over the floor."""
    with open(os.path.join(ROOT, "tests", "scenes", "lab4_grazing.json")) as f:
        return json.load(f)


def with_shadow(scene, settings):
    """Every shadow-casting light gets exactly `settings` as its "shadow" (other keys: defaults)."""
    out = copy.deepcopy(scene)
    for light in out.get("lights", []):
        if light.get("cast_shadows"):
            light["shadow"] = dict(settings)
    return out


def lab4_configs(quick):
    base = load_scene("lab4_shadows.json")
    base.setdefault("lighting", {})["markers"] = False  # the reference draws no light markers
    for m in base["materials"].values():
        for k in ("albedo_map", "specular_map", "emissive_map"):
            if k in m and not m[k].startswith("procedural:") and not os.path.isabs(m[k]):
                m[k] = os.path.join(ROOT, "scenes", m[k])
        if any(k in m for k in ("albedo_map", "specular_map", "emissive_map")):
            # The reference does not model anisotropic filtering; with it off both sides sample alike,
            # so the error left is the shadows'.
            m["sampler"] = dict(m.get("sampler", {}), anisotropy=1)
    scenes = [("default scene", base), ("grazing stress", lab4_stress_scene())]
    resolutions = [512, 2048] if quick else LAB4_RESOLUTIONS
    kernels = [1, 3] if quick else LAB4_KERNELS
    out = []
    for group, scene in scenes:
        for flt in LAB4_FILTERS:
            for n in kernels:
                for r in resolutions:
                    settings = {"resolution": r, "pcf": n, "filter": flt}
                    out.append(config(f"{r} pcf{n} {flt}", group, with_shadow(scene, settings), knob=r,
                                      default=settings == LAB4_DEFAULT, series=f"{flt} {n}x{n}"))
        out.append(config("seed: 2048 pcf3 nearest, bias 0.005", group, with_shadow(scene, LAB4_SEED),
                          knob=2048, seed="seed 000"))
    return out


KNOBS = {
    "lab1_camera": {"configs": lab1_configs, "groups": {"tessellation": {"front": True}}},
    "lab2_lighting": {"configs": lab2_configs,
                      "groups": {"shading x tessellation": {"front": True}, "lighting model": {"front": False},
                                 "light count": {"front": False}}},
    # truth: lab_reference's options for the truth; order: (better, worse) pairs of configurations
    # whose error the quick check compares.
    "lab3_textures": {"configs": lab3_configs, "groups": {"sampler": {"front": True, "label_all": True}},
                      "truth": ["--supersample", "16"], "truth_name": "16x16 supersampled",
                      "order": [("trilinear", "nearest")]},
    # error: the figure the front and the plot use (default mean_abs); compare: lab_compare's extra options.
    "lab4_shadows": {"configs": lab4_configs,
                     "groups": {"default scene": {"front": True}, "grazing stress": {"front": True}},
                     "truth": "shadow", "truth_name": "ray-traced shadows", "error": "shadow_mae",
                     "error_label": "shadow MAE over the receivers vs ray-traced shadows (1/255)",
                     "band": 4, "time_env": {"LAB_ANIMATE_LIGHTS": "1"}, "size": (640, 360), "frames": 16},
}
# The lab 4 shadow metric's figures (lab_compare --shadow), in every CSV (empty for other labs).
SHADOW_KEYS = ["wrong_side_pct", "shadow_mae"]
CSV_FIELDS = CSV_FIELDS[:-2] + SHADOW_KEYS + CSV_FIELDS[-2:]
ERROR = {"key": "mean_abs"}  # set from the lab's knob table in main()


# ---------------------------------------------------------------------------
# Running
# ---------------------------------------------------------------------------

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
    for line in text.splitlines():
        if line.startswith(prefix) or prefix == "":
            fields = dict(re.findall(r"(\w+)=([^\s]+)", line))
            if fields:
                return fields
    sys.exit(f"tradeoff: no '{prefix}' line in:\n{text}")


class Sweep:
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
            truth_args = KNOBS[self.lab].get("truth", ["--ideal", "--supersample", str(supersample)])
            if truth_args == "shadow":
                truth_args = ["--unshadowed", path[:-4] + ".u.png", "--unlit", path[:-4] + ".z.png"]
            out = run([self.reference, "--lab", self.lab, "--scene", self.write_scene(t, "truth_" + key),
                       "--width", str(w), "--height", str(h)] + truth_args + ["--out", path])
            self.truths[key] = path
            print(f"  truth {key}: {parse_fields(out, 'reference')['ms']} ms", flush=True)
        return self.truths[key]

    def render(self, scene_path, w, h, frames, png=None, cpu=None, extra_env=None):
        cmd = [self.exe, "--scene", scene_path, "--width", str(w), "--height", str(h), "--benchmark", str(frames)]
        if png:
            cmd += ["--out", png]
        if self.args.quick:
            cmd.append("--validate")  # quick runs are tests: validation on, timing not judged
        return parse_fields(run(cmd, dict(self.env, **(extra_env or {})), cpu), "benchmark")

    def frame_cpu_ms(self, scene_path, w, h, frames, png=None, extra_env=None):
        """--benchmark `frames` (wall-clock figures) and the CPU time one frame costs: the CPU
        seconds of that run minus those of a 1-frame run (start-up, pipeline compilation, warm-up
        are the same in both), over the frames between them. Other users of the machine delay a
        frame (wall clock) but hardly change its CPU time."""
        cpu = []
        self.render(scene_path, w, h, 1, None, cpu, extra_env)
        b = self.render(scene_path, w, h, frames, png, cpu, extra_env)
        b["cpu_ms"] = max(0.0, (cpu[1] - cpu[0]) / (frames - 1) * 1000.0)
        return b

    def compare_png(self, truth, png, heatmap=None):
        cmd = [self.compare, truth, png] + (["--heatmap", heatmap] if heatmap else [])
        if KNOBS[self.lab].get("truth") == "shadow":
            cmd += ["--shadow", truth[:-4] + ".u.png", truth[:-4] + ".z.png", "--band", str(KNOBS[self.lab]["band"])]
        return parse_fields(run(cmd), "mean_abs")


def measure(lab, args):
    sweep = Sweep(lab, args)
    w, h = (320, 180) if args.quick else KNOBS[lab].get("size", (1280, 720))
    configs = KNOBS[lab]["configs"](args.quick)
    if args.group:
        configs = [c for c in configs if c["group"] == args.group]
    if args.only:
        configs = [c for c in configs if re.search(args.only, c["config"])]
    for i, c in enumerate(configs):
        c["scene_path"] = sweep.write_scene(c["scene"], f"config_{i}")
        c["times"], c["p95s"] = [], []
    start = time.time()
    for r in range(args.rounds):
        # A different order each round (fixed seeds: repeatable), so that load from other users
        # of the machine does not fall on the same configurations every round.
        order = list(range(len(configs)))
        if r > 0:
            random.Random(r).shuffle(order)
        for i in order:
            c = configs[i]
            png = os.path.join(sweep.tmp, f"config_{i}.png") if r == 0 else None
            frames = max(3, args.frames // c.get("slow", 1))
            time_env = KNOBS[lab].get("time_env")
            if time_env:
                # Lab 4: the picture of the static scene gives the error; the time is a frame that
                # re-renders every shadow map (LAB_ANIMATE_LIGHTS=1: what the map's resolution costs; a
                # static scene pays it once). A static 1-frame run does the same work as an animated
                # one (the first frame renders every map), so it serves as the CPU baseline too.
                cpu = []
                sweep.render(c["scene_path"], w, h, 1, png or os.path.join(sweep.tmp, "unused.png"), cpu)
                b = sweep.render(c["scene_path"], w, h, frames, None, cpu, time_env)
                b["cpu_ms"] = max(0.0, (cpu[1] - cpu[0]) / (frames - 1) * 1000.0)
            else:
                b = sweep.frame_cpu_ms(c["scene_path"], w, h, frames, png)
            c.setdefault("cpu", []).append(b["cpu_ms"])
            c["times"].append(float(b["median_ms"]))
            c["p95s"].append(float(b["p95_ms"]))
            if png:
                e = sweep.compare_png(sweep.truth(c["scene"], w, h), png)
                c["errors"] = {k: float(e[k].rstrip("%")) for k in ERROR_KEYS + SHADOW_KEYS if k in e}
            print(f"  round {r + 1}/{args.rounds} {c['group']:>22} | {c['config']:<18} "
                  f"cpu {c['cpu'][-1]:8.2f} ms  wall {c['times'][-1]:8.2f} ms  {ERROR['key']} {err(c):.4f}",
                  flush=True)
    for c in configs:
        c["median_ms"] = statistics.median(c["times"])
        c["p95_ms"] = statistics.median(c["p95s"])
        c["spread_ms"] = max(c["times"]) - min(c["times"])
        c["best_ms"] = min(c["times"])
        c["cpu_ms"] = statistics.median(c["cpu"])
        c["cpu_spread_ms"] = max(c["cpu"]) - min(c["cpu"])
    mark_front(configs, KNOBS[lab]["groups"])
    return configs, sweep, time.time() - start


def mark_front(configs, groups):
    """Pareto front per group: no other configuration both cheaper and more accurate (lower
    mean |error|). Cheaper = less CPU time per frame (`cpu_ms`; on a shared machine the
    wall-clock frame time mostly measures the other users). `dominated_by` lists those cheaper
    by more than the noise (the larger of the two round-to-round CPU spreads) as well: the
    verdict that survives a re-run."""
    for c in configs:
        c["on_front"], c["dominated_by"] = "", ""
        if not groups.get(c["group"], {}).get("front"):
            continue
        peers = [o for o in configs if o["group"] == c["group"] and o is not c]
        e = err(c)
        strict = [o for o in peers if o["cpu_ms"] < c["cpu_ms"] and err(o) < e]
        robust = [o for o in strict if o["cpu_ms"] + max(o["cpu_spread_ms"], c["cpu_spread_ms"]) < c["cpu_ms"]]
        c["on_front"] = "yes" if not strict else "no"
        c["dominated_by"] = ";".join(o["config"] for o in robust)


def write_csv(lab, configs, path, rounds):
    with open(path, "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=CSV_FIELDS)
        wr.writeheader()
        for c in configs:
            row = {"lab": lab, "group": c["group"], "config": c["config"], "knob": c["knob"],
                   "default": "yes" if c["default"] else "", "seed": c["seed"],
                   "median_ms": f"{c['median_ms']:.3f}", "p95_ms": f"{c['p95_ms']:.3f}",
                   "spread_ms": f"{c['spread_ms']:.3f}", "best_ms": f"{c['best_ms']:.3f}",
                   "cpu_ms": f"{c['cpu_ms']:.3f}", "cpu_spread_ms": f"{c['cpu_spread_ms']:.3f}", "rounds": rounds,
                   "round_ms": ";".join(f"{t:.2f}" for t in c["times"]),
                   "on_front": c["on_front"], "dominated_by": c["dominated_by"]}
            row.update({k: f"{c['errors'][k]:.4f}" if k in c["errors"] else "" for k in ERROR_KEYS + SHADOW_KEYS})
            wr.writerow(row)


# ---------------------------------------------------------------------------
# Plot
# ---------------------------------------------------------------------------

def plot(lab, configs, path, title_note):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # One panel per group; a group with a front and single-primitive variants gets a second,
    # zoomed panel around its default, where those variants are labelled.
    panels = []
    for group in dict.fromkeys(c["group"] for c in configs):
        cs = [c for c in configs if c["group"] == group]
        if KNOBS[lab]["groups"].get(group, {}).get("label_all"):
            panels.append((group, cs, "labelled"))
        elif KNOBS[lab]["groups"].get(group, {}).get("front"):
            panels.append((group, cs, "front"))
            if any(not c["series"] for c in cs):
                panels.append((group, cs, "zoom"))
        elif group == "light count":
            panels.append((group, cs, "count"))
        else:
            panels.append((group, cs, "bars"))
    ratios = [1.5 if kind in ("front", "zoom") else 2.0 if kind == "labelled" else 1.0 for _, _, kind in panels]
    fig, axes = plt.subplots(1, len(panels), figsize=(5.6 * sum(ratios), 5.6), squeeze=False,
                             gridspec_kw={"width_ratios": ratios})
    for ax, (group, cs, kind) in zip(axes[0], panels):
        {"front": plot_front, "zoom": plot_front, "labelled": plot_front, "count": plot_count,
         "bars": plot_bars}[kind](ax, group, cs, kind)
        if kind == "labelled":
            from matplotlib.ticker import ScalarFormatter
            ax.set_ylabel(f"mean |error| vs {KNOBS[lab].get('truth_name', 'ideal')} (1/255, log)")
            for axis in (ax.xaxis, ax.yaxis):  # plain numbers on the log axes
                axis.set_major_formatter(ScalarFormatter())
                axis.set_minor_formatter(ScalarFormatter())
            ax.tick_params(which="minor", labelsize=7)
    fig.suptitle(f"{lab}: time against error\n{title_note}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def err(c):
    """The error the front and the plots use: mean |error| (lab 4: the wrong-side share)."""
    return c["errors"][ERROR["key"]]


def plot_front(ax, group, cs, kind):
    markers = {"flat": "s", "gouraud": "^", "phong": "o", "all": "o"}
    zoom = kind == "zoom"
    for s in dict.fromkeys(c["series"] for c in cs):
        pts = [c for c in cs if c["series"] == s]
        if s:
            pts.sort(key=lambda c: c["knob"])
            ax.plot([c["cpu_ms"] for c in pts], [err(c) for c in pts], marker=markers.get(s, "o"), linestyle="-",
                    alpha=0.8, label=f"{s} (segments)" if s == "all" else s)
        else:
            label = "one primitive varied, others at default" if kind != "labelled" else "configuration"
            if all(c["seed"] for c in pts):
                label = "the seed's configuration"
            ax.scatter([c["cpu_ms"] for c in pts], [err(c) for c in pts], marker="x", color="0.3", zorder=3,
                       label=label)
    front = sorted([c for c in cs if c["on_front"] == "yes"], key=lambda c: c["cpu_ms"])
    ax.step([c["cpu_ms"] for c in front], [err(c) for c in front], where="post", color="black", linewidth=1.2,
            alpha=0.7, label="Pareto front")
    for c in cs:
        ax.errorbar(c["cpu_ms"], err(c), xerr=c["cpu_spread_ms"] / 2, fmt="none", ecolor="0.6",
                    elinewidth=0.8, capsize=2)
        if c["default"]:
            ax.scatter([c["cpu_ms"]], [err(c)], s=170, facecolors="none", edgecolors="red", linewidths=1.6, zorder=4)
    if kind == "labelled":
        label_clusters(ax, cs)
    for c in cs:
        if kind == "labelled":
            continue
        if not c["series"] and kind == "front":
            continue  # labelled in the zoomed panel
        text = str(c["knob"]) if c["series"] else c["config"]
        if c["default"]:
            text = f"{c['config']} (default)"
        if c["seed"]:
            text += f" = {c['seed']}"
        special = c["default"] or c["seed"]
        ax.annotate(text, (c["cpu_ms"], err(c)), textcoords="offset points", xytext=(5, 4),
                    fontsize=8 if special else 7, fontweight="bold" if c["default"] else "normal",
                    color="darkred" if special else "black")
    ax.set_xscale("log")
    ax.set_yscale("log")
    if zoom:
        near = [c for c in cs if not c["series"] or c["default"]]
        xs = [c["cpu_ms"] for c in near]
        ys = [err(c) for c in near]
        ax.set_xlim(min(xs) / 1.08, max(xs) * 1.15)
        ax.set_ylim(min(ys) / 1.3, max(ys) * 1.3)
        ax.set_title(f"{group}: around the default")
    else:
        ax.set_title(group)
    ax.set_xlabel("CPU time per frame (ms, all threads, log)")
    ax.set_ylabel(ERROR.get("label", "mean |error| vs ideal (1/255, log)"))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper right")


def label_clusters(ax, cs):
    """Labels every configuration; those with the same error (the same picture: lab 3's
    anisotropy 2 … 16 on lavapipe) and about the same cost share one label."""
    clusters = []
    for c in sorted(cs, key=lambda c: c["cpu_ms"]):
        for cl in clusters:
            if err(cl[0]) == err(c) and abs(cl[0]["cpu_ms"] - c["cpu_ms"]) < 0.2 * cl[0]["cpu_ms"]:
                cl.append(c)
                break
        else:
            clusters.append([c])
    for cl in clusters:
        cl.sort(key=lambda c: cs.index(c))
        lines = [c["config"] + (" (default)" if c["default"] else "") + (f" = {c['seed']}" if c["seed"] else "")
                 for c in cl]
        special = any(c["default"] or c["seed"] for c in cl)
        x = statistics.median(c["cpu_ms"] for c in cl)
        ax.annotate("\n".join(lines), (x, err(cl[0])), textcoords="offset points", xytext=(-8, 8), ha="right",
                    fontsize=8, color="darkred" if special else "black")


def plot_count(ax, group, cs, kind):
    xs = [c["knob"] for c in cs]
    ax.errorbar(xs, [c["cpu_ms"] for c in cs], yerr=[c["cpu_spread_ms"] / 2 for c in cs], fmt="o-",
                color="tab:blue", capsize=3, label="measured")
    # Cost proportional to the number of lights, through the largest count: a straight line of slope 1.
    last = max(cs, key=lambda c: c["knob"])
    ax.plot(xs, [last["cpu_ms"] * x / last["knob"] for x in xs], ":", color="0.5", label="∝ lights")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.legend(fontsize=7, loc="upper left")
    ax.set_xticks(xs)
    ax.set_xticklabels([str(x) for x in xs])
    ax.set_xlabel("lights (directional, point, spot in turn)")
    ax.set_ylabel("CPU time per frame (ms, all threads, log)")
    for c in cs:
        ax.annotate(f"{c['cpu_ms']:.0f} ms\nerr {err(c):.2f}", (c["knob"], c["cpu_ms"]), textcoords="offset points",
                    xytext=(-10, 8), fontsize=7, color="0.25")
    ax.set_title(f"{group}\n(error vs each count's own ideal)")
    ax.grid(True, alpha=0.3)


def plot_bars(ax, group, cs, kind):
    ys = list(range(len(cs)))
    ax.barh(ys, [c["cpu_ms"] for c in cs], xerr=[c["cpu_spread_ms"] / 2 for c in cs],
            color=["tab:red" if c["default"] else "tab:blue" for c in cs], alpha=0.75, capsize=2)
    ax.set_yticks(ys)
    ax.set_yticklabels([c["config"] + (" (default)" if c["default"] else "") + (f" = {c['seed']}" if c["seed"] else "")
                        for c in cs], fontsize=8)
    ax.invert_yaxis()
    for y, c in zip(ys, cs):
        ax.annotate(f" {c['cpu_ms']:.1f} ms, err {err(c):.2f}", (c["cpu_ms"] + c["cpu_spread_ms"] / 2, y),
                    va="center", fontsize=7)
    ax.set_xlabel("CPU time per frame (ms, all threads)")
    ax.set_title(f"{group} (equal scene;\nerror vs each model's own ideal)")
    ax.grid(True, axis="x", alpha=0.3)
    ax.set_xlim(0, max(c["cpu_ms"] for c in cs) * 1.45)


def replot(lab, csv_path, out_png, quick):
    """Draw LAB.png again from LAB.csv (the configurations' roles come from the knob table)."""
    configs = {c["config"]: c for c in KNOBS[lab]["configs"](quick)}
    out = []
    with open(csv_path, newline="") as f:
        for row in csv.DictReader(f):
            c = dict(configs.get(row["config"], config(row["config"], row["group"], {})))
            c["group"] = row["group"]
            for k in ("median_ms", "p95_ms", "spread_ms", "best_ms", "cpu_ms", "cpu_spread_ms"):
                c[k] = float(row[k])
            c["errors"] = {k: float(row[k]) for k in ERROR_KEYS + SHADOW_KEYS if row.get(k)}
            c["on_front"], c["dominated_by"] = row["on_front"], row["dominated_by"]
            c["rounds"] = row["rounds"]
            out.append(c)
    mark_front(out, KNOBS[lab]["groups"])  # with the lab's error figure (several CSVs may have been joined)
    return out


# ---------------------------------------------------------------------------
# README heatmaps: where the error is
# ---------------------------------------------------------------------------

def sphere_scene(segments, rings, lit, shading="phong"):
    scene = {
        "camera": {"mode": "lookat", "position": [0, 0, 2.2], "target": [0, 0, 0], "fov_y_deg": 40},
        "background": [0.02, 0.03, 0.06],
        "materials": {"m": {"albedo": [0.2, 0.4, 0.9], "specular": [0.6, 0.6, 0.6], "shininess": 48}},
        "objects": [{"mesh": "sphere", "material": "m", "segments": segments, "rings": rings}],
    }
    if lit:
        scene["ambient"] = {"color": [1, 1, 1], "intensity": 0.05}
        scene["lighting"] = {"model": "blinn_phong", "shading": shading}
        scene["lights"] = [{"type": "point", "position": [0.9, 0.8, 1.2], "color": [1, 1, 1], "intensity": 1.6,
                            "attenuation": [1, 0.2, 0.1]}]
    return scene


def heatmap_figure(sweep, scene, name, title, out_dir, w=480, h=360):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt

    path = sweep.write_scene(scene, name)
    png = os.path.join(sweep.tmp, name + ".png")
    sweep.render(path, w, h, 1, png)
    truth = sweep.truth(scene, w, h)
    heat = os.path.join(sweep.tmp, name + "_heat.png")
    e = sweep.compare_png(truth, png, heat)
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.5))
    for ax, img, label in zip(axes, [truth, png, heat], ["ideal (lab_reference --ideal)", "lab", "|error| heatmap"]):
        ax.imshow(mpimg.imread(img))
        ax.set_title(label, fontsize=9)
        ax.axis("off")
    fig.suptitle(f"{title}\nmean |error| {float(e['mean_abs']):.2f}/255, max {e['max_abs']}/255, "
                 f"{e['over_2']} of pixels above 2/255, mean CIEDE2000 {float(e['mean_de2000']):.2f}", fontsize=9)
    fig.tight_layout()
    out = os.path.join(out_dir, name + ".png")
    fig.savefig(out, dpi=80)
    plt.close(fig)
    print(f"  heatmap {out}: {e}")


def heatmaps(lab, sweep, out_dir):
    if lab == "lab1_camera":
        heatmap_figure(sweep, sphere_scene(16, 8, lit=False), "lab1_sphere16_silhouette",
                       "a 16-segment sphere (16 × 8) against the ideal sphere: only the silhouette differs", out_dir)
    elif lab == "lab2_lighting":
        for shading in ("gouraud", "phong"):
            heatmap_figure(sweep, sphere_scene(16, 8, lit=True, shading=shading), f"lab2_sphere16_{shading}",
                           f"{shading.capitalize()} shading of a 16 × 8 sphere under a point light against "
                           f"per-pixel shading of the ideal sphere", out_dir)


# ---------------------------------------------------------------------------
# Quick check (CTest)
# ---------------------------------------------------------------------------

def check(lab, csv_path, configs):
    problems = []
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
        if rows and list(rows[0].keys()) != CSV_FIELDS:
            problems.append(f"header {list(rows[0].keys())} != {CSV_FIELDS}")
    if len(rows) != len(configs):
        problems.append(f"{len(rows)} rows for {len(configs)} configurations")
    for row in rows:
        for k in ["cpu_ms", "cpu_spread_ms", "median_ms", "p95_ms", "spread_ms", "best_ms"] + ERROR_KEYS:
            try:
                v = float(row[k])
            except (TypeError, ValueError):
                problems.append(f"{row.get('config')}: {k} = {row.get(k)!r} is not a number")
                continue
            if not math.isfinite(v) or v < 0:
                problems.append(f"{row['config']}: {k} = {v}")
        if float(row["median_ms"] or 0) <= 0:
            problems.append(f"{row['config']}: no frame time")
    if sum(1 for r in rows if r["default"] == "yes") < 1:
        problems.append("no default configuration")
    # The error must grow when the tessellation drops (data, not timing).
    for series in sorted({c["series"] for c in configs if c["series"]}):
        pts = sorted([c for c in configs if c["series"] == series], key=lambda c: c["knob"])
        for finer, coarser in zip(pts[1:], pts[:-1]):
            if not coarser["errors"]["mean_abs"] > finer["errors"]["mean_abs"]:
                problems.append(f"series {series}: error at {coarser['knob']} ({coarser['errors']['mean_abs']}) "
                                f"not above error at {finer['knob']} ({finer['errors']['mean_abs']})")
    # Configurations whose error must be below another's (lab 3: trilinear below nearest).
    by_name = {c["config"]: c for c in configs}
    for better, worse in KNOBS[lab].get("order", []):
        if better in by_name and worse in by_name and \
                not by_name[better]["errors"]["mean_abs"] < by_name[worse]["errors"]["mean_abs"]:
            problems.append(f"error of {better} ({by_name[better]['errors']['mean_abs']}) not below error of "
                            f"{worse} ({by_name[worse]['errors']['mean_abs']})")
    for p in problems:
        print(f"tradeoff check: {p}")
    return not problems


def ensure_matplotlib():
    """matplotlib comes from Debian (python3-matplotlib, scripts/setup.sh): if this python3 is
    another one (pyenv, a venv) without it, run again under Debian's."""
    try:
        import matplotlib  # noqa: F401
        return
    except ImportError:
        pass
    debian = "/usr/bin/python3"
    if os.path.exists(debian) and os.path.realpath(sys.executable) != os.path.realpath(debian):
        os.execv(debian, [debian] + sys.argv)
    sys.exit("tradeoff: matplotlib is missing: install python3-matplotlib (bash scripts/setup.sh)")


def main():
    ensure_matplotlib()
    ap = argparse.ArgumentParser(description="frame time against error for a lab's knobs")
    ap.add_argument("lab", choices=sorted(KNOBS))
    ap.add_argument("--quick", action="store_true", help="a few configurations at 320x180, then check the CSV")
    ap.add_argument("--build", default=os.environ.get("LAB_BUILD_DIR", os.path.join(ROOT, "build")))
    ap.add_argument("--out-dir", help="default: docs/tradeoffs (quick: BUILD/tradeoff_quick)")
    ap.add_argument("--frames", type=int, help="benchmark frames per run (default: 61 lab 1, 21 lab 2; quick 3)")
    ap.add_argument("--rounds", type=int, help="interleaved rounds (default 3; quick 1)")
    ap.add_argument("--threads", type=int, default=2, help="LP_NUM_THREADS (default 2)")
    ap.add_argument("--no-heatmaps", action="store_true")
    ap.add_argument("--replot", action="store_true", help="only draw LAB.png again from LAB.csv")
    ap.add_argument("--exe", help="the lab binary (default: BUILD/LAB/LAB)")
    ap.add_argument("--only", help="only the configurations whose name matches this regular expression")
    ap.add_argument("--group", help="only this group's configurations (e.g. two groups in two processes, "
                                    "then --replot on the concatenated CSV)")
    args = ap.parse_args()
    args.build = os.path.abspath(args.build)
    ERROR["key"] = KNOBS[args.lab].get("error", "mean_abs")
    if "error_label" in KNOBS[args.lab]:
        ERROR["label"] = KNOBS[args.lab]["error_label"] + " (log)"
    if args.frames is None:
        args.frames = 3 if args.quick else KNOBS[args.lab].get("frames", 61 if args.lab == "lab1_camera" else 21)
    if args.rounds is None:
        args.rounds = 1 if args.quick else 3
    out_dir = args.out_dir or (os.path.join(args.build, "tradeoff_quick") if args.quick
                               else os.path.join(ROOT, "docs", "tradeoffs"))
    os.makedirs(out_dir, exist_ok=True)

    res = "320x180" if args.quick else "x".join(map(str, KNOBS[args.lab].get("size", (1280, 720))))
    note = (f"{res}, LP_NUM_THREADS={args.threads}, {args.rounds} interleaved rounds x {args.frames} frames on a "
            f"shared 2-core machine; bars: round-to-round spread")
    if KNOBS[args.lab].get("time_env"):
        note += "; time: a frame that re-renders every shadow map (LAB_ANIMATE_LIGHTS=1), error: the static picture"
    if args.replot:
        csv_path = os.path.join(out_dir, args.lab + ".csv")
        configs = replot(args.lab, csv_path, None, args.quick)
        # The front columns again, from the recomputed front.
        with open(csv_path, newline="") as f:
            rows = list(csv.DictReader(f))
        for row, c in zip(rows, configs):
            row["on_front"], row["dominated_by"] = c["on_front"], c["dominated_by"]
        with open(csv_path, "w", newline="") as f:
            wr = csv.DictWriter(f, fieldnames=CSV_FIELDS)
            wr.writeheader()
            wr.writerows(rows)
        plot(args.lab, configs, os.path.join(out_dir, args.lab + ".png"), note)
        return
    wall = time.time()
    configs, sweep, _ = measure(args.lab, args)
    csv_path = os.path.join(out_dir, args.lab + ".csv")
    write_csv(args.lab, configs, csv_path, args.rounds)
    plot(args.lab, configs, os.path.join(out_dir, args.lab + ".png"), note)
    if not args.quick and not args.no_heatmaps:
        heatmaps(args.lab, sweep, out_dir)
    print(f"tradeoff: wrote {csv_path} and {args.lab}.png in {time.time() - wall:.0f} s")
    for c in configs:
        if c["default"]:
            print(f"  default {c['group']} | {c['config']}: cpu {c['cpu_ms']:.2f} ms/frame (spread {c['cpu_spread_ms']:.2f}), "
                  f"wall median {c['median_ms']:.2f} ms (spread {c['spread_ms']:.2f}, best {c['best_ms']:.2f}), "
                  f"{ERROR['key']} {err(c):.4f}, on front: {c['on_front'] or 'n/a'}"
                  + (f", dominated beyond noise by {c['dominated_by']}" if c["dominated_by"] else ""))
    shutil.rmtree(sweep.tmp, ignore_errors=True)
    if args.quick and not check(args.lab, csv_path, configs):
        sys.exit(1)


if __name__ == "__main__":
    main()
