"""The knob tables: which configurations each lab sweeps.

KNOBS maps a lab to a function returning its configurations (config() below: a name, a
group, the scene to render, its knob value and its role) and to how the lab is measured
(its groups, its truth, its error figure). To add a lab: write a function like
lab1_configs and add it to KNOBS; groups with "front": True get a Pareto front.
"""
import copy

from .scenes import load_scene, load_test_scene, set_mesh, tessellate, with_shadow


def config(name, group, scene, knob="", default=False, seed="", series=""):
    """One configuration. `series` names a run of configurations in which only the
    tessellation changes (ordered by `knob`, finer = larger): the quick check demands that
    the error falls along it."""
    return {"config": name, "group": group, "scene": scene, "knob": knob, "default": default, "seed": seed,
            "series": series}


# ---------------------------------------------------------------------------
# Lab 1: tessellation
# ---------------------------------------------------------------------------

# One primitive at a time around the defaults (full sweep): (segments, rings), rings 0 = default.
LAB1_VARIANTS = [("sphere", [(16, 16), (32, 8), (32, 32), (64, 16), (64, 32)]),
                 ("cylinder", [(16, 0), (64, 0)]), ("cone", [(16, 0), (64, 0)]),
                 ("torus", [(24, 16), (48, 8), (48, 24), (96, 16), (96, 32)])]


def lab1_configs(quick):
    base = load_scene("lab1_camera.json")
    levels = [8, 16, 32, 64] if quick else [8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256]
    out = [config(f"all curved at {s}", "tessellation", tessellate(base, s), knob=s, default=(s == 32),
                  series="all") for s in levels]
    if not quick:
        # Is each primitive's default on the front by itself?
        default = tessellate(base, 32)
        for mesh, variants in LAB1_VARIANTS:
            for seg, rings in variants:
                name = f"{mesh} {seg}" + (f"x{rings}" if mesh in ("sphere", "torus") else "")
                out.append(config(name, "tessellation", set_mesh(default, mesh, seg, rings),
                                  knob=seg * max(rings, 1)))
    return out


# ---------------------------------------------------------------------------
# Lab 2: shading x tessellation, lighting model, light count
# ---------------------------------------------------------------------------

def many_lights(n):
    """The first n of lab2_many_lights.json's 8 + 32 + 32 lights, the types taken in turn."""
    lights = load_scene("lab2_many_lights.json")["lights"]
    return interleave([[l for l in lights if l["type"] == t] for t in ("directional", "point", "spot")])[:n]


def interleave(lists):
    """The lists' items taken in turn (one of each while they last): [[1, 2, 3], [4]] -> [1, 4, 2, 3]."""
    queues = [list(items) for items in lists]
    out = []
    while any(queues):
        for q in queues:
            if q:
                out.append(q.pop(0))
    return out


def lab2_configs(quick):
    base = load_scene("lab2_lighting.json")
    base.setdefault("lighting", {})["markers"] = False  # the reference has no light markers
    return lab2_shading(base, quick) + lab2_models(base, quick) + lab2_light_counts(base, quick)


def lab2_shading(base, quick):
    """Shading × tessellation, against per-pixel shading of the exact surfaces."""
    levels = [8, 16, 32] if quick else [8, 16, 32, 64, 128]
    shadings = ["flat", "phong"] if quick else ["flat", "gouraud", "phong"]
    out = []
    for shading in shadings:
        for s in levels:
            scene = tessellate(base, s)
            scene["lighting"]["shading"] = shading
            default = shading == "phong" and s == 32
            # seed 000: Blinn-Phong per pixel, 1 directional + 2 point + 1 spot light
            out.append(config(f"{shading} {s}", "shading x tessellation", scene, knob=s, default=default,
                              seed="seed 000" if default else "", series=shading))
    return out


def lab2_models(base, quick):
    """Each lighting model at equal scene (default tessellation, per-pixel shading), each
    against its own truth."""
    models = ["lambert", "blinn_phong"] if quick else \
        ["lambert", "phong", "blinn_phong", "toon", "oren_nayar", "minnaert", "cook_torrance", "ward"]
    out = []
    for model in models:
        scene = copy.deepcopy(base)
        scene["lighting"]["model"] = model
        seed = "seed 001" if model == "phong" else ""  # the Phong lighting model
        out.append(config(model, "lighting model", scene, default=(model == "blinn_phong"), seed=seed))
    return out


def lab2_light_counts(base, quick):
    """Light count: the default scene's objects, lights from lab2_many_lights.json."""
    out = []
    for n in [1, 8] if quick else [1, 2, 4, 8, 16, 32, 72]:
        scene = copy.deepcopy(base)
        scene["lights"] = many_lights(n)
        c = config(f"{n} lights", "light count", scene, knob=n)
        if n >= 32:
            c["slow"] = 2  # about a second a frame: half the frames
        out.append(c)
    return out


# ---------------------------------------------------------------------------
# Lab 3: sampler settings
# ---------------------------------------------------------------------------

# The sampler settings of bench/lab3_samplers.sh and the test
# Lab3Filtering.AnisotropyLowersTheErrorAgainstTheGroundTruth, on the grazing floor.
LAB3_SAMPLERS = [
    ("nearest", {"filter": "nearest", "mipmaps": "none", "anisotropy": 1}),
    ("linear, no mipmaps", {"filter": "linear", "mipmaps": "none", "anisotropy": 1}),
    ("trilinear", {"filter": "linear", "mipmaps": "linear", "anisotropy": 1}),
    ("trilinear + aniso 2", {"filter": "linear", "mipmaps": "linear", "anisotropy": 2}),
    ("trilinear + aniso 4", {"filter": "linear", "mipmaps": "linear", "anisotropy": 4}),
    ("trilinear + aniso 8", {"filter": "linear", "mipmaps": "linear", "anisotropy": 8}),
    ("trilinear + aniso 16", {"filter": "linear", "mipmaps": "linear", "anisotropy": 16}),
    # anisotropic filtering in the fragment shader, at most N probes (lab 3's README)
    ("trilinear + probes 2", {"filter": "linear", "mipmaps": "linear", "anisotropy": 2, "anisotropic": "probes"}),
    ("trilinear + probes 4", {"filter": "linear", "mipmaps": "linear", "anisotropy": 4, "anisotropic": "probes"}),
    ("trilinear + probes 8", {"filter": "linear", "mipmaps": "linear", "anisotropy": 8, "anisotropic": "probes"}),
    ("bilinear, nearest mips + probes 4",  # lab 3's default scene's floor
     {"filter": "linear", "mipmaps": "nearest", "anisotropy": 4, "anisotropic": "probes"}),
]
LAB3_QUICK = ["nearest", "trilinear", "trilinear + aniso 16", "bilinear, nearest mips + probes 4"]


def lab3_configs(quick):
    """Sampler settings on scenes/lab3_floor.json (a tiled floor seen at a grazing angle), each
    against the texture averaged over every pixel's footprint (lab_reference --supersample 16).
    The default is what lab 3's default scene gives its floor (scenes/lab3_textures.json: 4 shader
    probes on nearest mipmaps); seed 002's sampler (linear, linear mips, anisotropy 16, also the
    scene format's default when a material names no sampler) is marked as the seed."""
    base = load_scene("lab3_floor.json")
    out = []
    for name, sampler in LAB3_SAMPLERS:
        if quick and name not in LAB3_QUICK:
            continue
        scene = copy.deepcopy(base)
        scene["materials"]["floor"]["sampler"] = dict(scene["materials"]["floor"]["sampler"], **sampler)
        default = name == "bilinear, nearest mips + probes 4"
        out.append(config(name, "sampler", scene, knob=sampler["anisotropy"], default=default,
                          seed="seed 002" if name == "trilinear + aniso 16" else ""))
    return out


# ---------------------------------------------------------------------------
# Lab 4: shadow maps
# ---------------------------------------------------------------------------

# Shadow-map resolution x PCF kernel x filter, on the default scene and on a hard stress scene,
# each against the ray-traced shadows (lab_reference --lab lab4_shadows) with the shadow error
# metric (docs/testing.md): wrong-side pixels outside a band of k = 4 px (the widest kernel
# compared, 7x7: radius 3 texels + 1) and the MAE over the shadow receivers.
LAB4_RESOLUTIONS = [512, 1024, 2048, 4096]
LAB4_KERNELS = [1, 3, 5, 7]
LAB4_FILTERS = ["nearest", "bilinear"]
# The seed's configuration (000_...): one 2048^2 map, 3x3 PCF by hand, LearnOpenGL's constant depth
# bias 0.005, expressed in our keys (lab4_shadows/README.md: 83886 = 0.005 * 2^24 depth units).
LAB4_SEED = {"resolution": 2048, "pcf": 3, "filter": "nearest", "bias": 83886, "slope_bias": 0, "normal_offset": 0}
LAB4_DEFAULT = {"resolution": 2048, "pcf": 1, "filter": "nearest"}  # lab::ShadowDesc's defaults (scene.h)
# The default's maps sized to the picture (lab4_shadows/README.md, "Maps sized to the picture").
LAB4_FITTED = dict(LAB4_DEFAULT, fit_to_view=True)


def lab4_default_scene():
    """scenes/lab4_shadows.json without light markers and with anisotropic filtering off: the
    reference models neither, so the error left is the shadows'."""
    scene = load_scene("lab4_shadows.json")
    scene.setdefault("lighting", {})["markers"] = False
    for m in scene["materials"].values():
        if any(k in m for k in ("albedo_map", "specular_map", "emissive_map")):
            m["sampler"] = dict(m.get("sampler", {}), anisotropy=1)
    return scene


def lab4_configs(quick):
    # The stress scene, tests/scenes/lab4_grazing.json: long, thin shadows at a grazing light: thin
    # posts and a slatted fence on a floor, a directional light 10 degrees above the horizon and a
    # spot light low over the floor.
    scenes = [("default scene", lab4_default_scene()), ("grazing stress", load_test_scene("lab4_grazing.json"))]
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
        out.append(config("2048 pcf1 nearest, fit to view", group, with_shadow(scene, LAB4_FITTED), knob=2048))
        out.append(config("seed: 2048 pcf3 nearest, bias 0.005", group, with_shadow(scene, LAB4_SEED),
                          knob=2048, seed="seed 000"))
    return out


# Per lab: configs, the function above; groups, how each group is drawn ("front": a Pareto front,
# "label_all": every point labelled, "knob": what its series vary, named on a plot that has too many
# series to label every point); truth, lab_reference's options for the truth (default
# --ideal; "shadow": the ray-traced shadows and lab_compare's shadow metric with a band of `band`
# px); truth_name, how the plots name it; order, (better, worse) pairs of configurations whose
# error the quick check compares; error, the figure the front and the plots use (default mean_abs)
# and error_label its axis label; time_args, the lab's extra options for the timed run (lab 4:
# every shadow map re-rendered every frame); size and frames, the full sweep's resolution
# (default 1280x720) and benchmark frames (default 61 lab 1, 21 others).
KNOBS = {
    "lab1_camera": {"configs": lab1_configs, "groups": {"tessellation": {"front": True}}, "frames": 61},
    "lab2_lighting": {"configs": lab2_configs,
                      "groups": {"shading x tessellation": {"front": True}, "lighting model": {"front": False},
                                 "light count": {"front": False}}},
    "lab3_textures": {"configs": lab3_configs, "groups": {"sampler": {"front": True, "label_all": True}},
                      "truth": ["--supersample", "16"], "truth_name": "16x16 supersampled",
                      "order": [("trilinear", "nearest")]},
    "lab4_shadows": {"configs": lab4_configs,
                     "groups": {"default scene": {"front": True, "knob": "shadow map size"},
                                "grazing stress": {"front": True, "knob": "shadow map size"}},
                     "truth": "shadow", "truth_name": "ray-traced shadows", "error": "shadow_mae",
                     "error_label": "shadow MAE on receivers vs ray-traced (1/255)",
                     "band": 4, "time_args": ["--dev-animate-lights"], "size": (640, 360), "frames": 16},
}


def frames(lab, quick):
    """Benchmark frames per run when --frames is not given."""
    return 3 if quick else KNOBS[lab].get("frames", 21)


def size(lab, quick):
    """The rendering's width and height: 320x180 in quick runs."""
    return (320, 180) if quick else KNOBS[lab].get("size", (1280, 720))


def error_key(lab):
    """The error figure the front and the plots use: mean |error| (lab 4: the shadow MAE)."""
    return KNOBS[lab].get("error", "mean_abs")


def error_label(lab):
    """The plots' error axis label."""
    if "error_label" in KNOBS[lab]:
        return KNOBS[lab]["error_label"] + " (log)"
    return "mean |error| vs ideal (1/255, log)"
