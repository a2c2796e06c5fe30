"""Scenes: reading the repository's scene files and writing their variants.

Everything here is a pure function on scene dictionaries (as in docs/scene-format.md):
the knob tables (knobs.py) build their configurations from them.
"""
import copy
import json
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PRIMITIVES = {"plane", "cube", "sphere", "icosphere", "icosahedron", "cylinder", "cone", "torus"}
TEXTURE_KEYS = ("albedo_map", "specular_map", "emissive_map")


def load_scene(name):
    """A scene from scenes/, with model and texture paths made absolute (variants are written elsewhere)."""
    path = os.path.join(ROOT, "scenes", name)
    with open(path) as f:
        scene = json.load(f)
    here = os.path.dirname(path)
    for obj in scene["objects"]:
        if obj["mesh"] not in PRIMITIVES and not os.path.isabs(obj["mesh"]):
            obj["mesh"] = os.path.normpath(os.path.join(here, obj["mesh"]))
    for material in scene.get("materials", {}).values():
        for key in TEXTURE_KEYS:
            value = material.get(key)
            if value and not value.startswith("procedural:") and not os.path.isabs(value):
                material[key] = os.path.join(here, value)
    return scene


def load_test_scene(name):
    """A scene from tests/scenes/, as it is (no paths to resolve: lab4_grazing.json has primitives only)."""
    with open(os.path.join(ROOT, "tests", "scenes", name)) as f:
        return json.load(f)


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
    """Every object drawing primitive `mesh` gets `segments` (and `rings` unless 0)."""
    out = copy.deepcopy(scene)
    for obj in out["objects"]:
        if obj["mesh"] == mesh:
            obj["segments"] = segments
            if rings:
                obj["rings"] = rings
    return out


def with_shadow(scene, settings):
    """Every shadow-casting light gets exactly `settings` as its "shadow" (other keys: defaults)."""
    out = copy.deepcopy(scene)
    for light in out.get("lights", []):
        if light.get("cast_shadows"):
            light["shadow"] = dict(settings)
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
