#!/usr/bin/env python3
"""lab4_smoke.py — lab 4's smoke runs of the real binary (CTest: lab4_smoke_*).

    lab4_smoke.py LAB4_EXE SOURCE_DIR CASE

CASE is one of:
  maps_once    the default scene, 3 frames, validation on: every shadow map is rendered once
               (a static scene), no validation message;
  animated     --dev-animate-lights: every map is rendered every frame (3 maps x 3 frames);
  no_shadows   lab 3's scene (no light casts shadows): no shadow pass at all;
  bad_input    absurd values (even PCF, resolution 0, opacity 1.5): exit code 2, one line.
"""
import json
import os
import subprocess
import sys
import tempfile


def run(exe, args, env=None):
    full_env = dict(os.environ, LP_NUM_THREADS=os.environ.get("LP_NUM_THREADS", "2"))
    full_env.update(env or {})
    p = subprocess.run([exe] + args, capture_output=True, text=True, env=full_env, timeout=280)
    return p.returncode, p.stdout + p.stderr


def renders(output):
    for line in output.splitlines():
        if line.endswith("shadow map renders"):
            return int(line.split()[1])
    return None


def fail(message, output=""):
    print("FAIL:", message)
    print(output)
    sys.exit(1)


def base_scene():
    return {
        "camera": {"position": [3, 4, 6], "target": [0, 0.3, 0], "fov_y_deg": 50},
        "ambient": {"intensity": 0.1},
        "lighting": {"nan_check": "on"},
        "lights": [],
        "materials": {"white": {"albedo": [0.8, 0.8, 0.8]}, "glass": {"albedo": [1, 0.3, 0.2], "opacity": 0.5}},
        "objects": [
            {"mesh": "plane", "material": "white", "scale": [8, 1, 8]},
            {"mesh": "cube", "material": "white", "position": [0, 0.5, 0]},
            {"mesh": "sphere", "material": "glass", "position": [-1.5, 1.2, 1.0]},
        ],
    }


def light(kind, **keys):
    l = {"type": kind, "intensity": 1.0, "cast_shadows": True}
    if kind != "directional":
        l["attenuation"] = [1, 0, 0]
    l.update(keys)
    return l


def main():
    if sys.argv[1:2] in (["-h"], ["--help"]):
        print(__doc__.strip())
        return
    if len(sys.argv) != 4:
        print("lab4_smoke: usage: lab4_smoke.py LAB4_EXE SOURCE_DIR CASE (see --help)", file=sys.stderr)
        sys.exit(2)
    exe, source, case = sys.argv[1:4]
    default_scene = os.path.join(source, "scenes", "lab4_shadows.json")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = os.environ.get("LAB4_SMOKE_KEEP", tmp)  # a folder to keep the pictures in (to look at them)
        small = ["--headless", "--width", "320", "--height", "180", "--validate"]
        if case == "maps_once":
            rc, out = run(exe, small + ["--frames", "3", "--scene", default_scene, "--out", tmp + "/a.png"])
            if rc != 0 or renders(out) != 3:
                fail("default scene: want exit 0 and 3 map renders in 3 frames (one per light)", out)
        elif case == "animated":
            rc, out = run(exe, small + ["--frames", "3", "--scene", default_scene, "--out", tmp + "/a.png",
                                        "--dev-animate-lights"])
            if rc != 0 or renders(out) != 9:
                fail("animated lights: want exit 0 and 9 map renders in 3 frames", out)
        elif case == "no_shadows":
            scene = os.path.join(source, "scenes", "lab3_textures.json")
            rc, out = run(exe, small + ["--frames", "2", "--scene", scene, "--out", tmp + "/a.png"])
            if rc != 0 or renders(out) != 0:
                fail("lab 3's scene: want exit 0 and no shadow map at all", out)
        elif case == "bad_input":
            bad = {"pcf_even": ("shadow", {"pcf": 4}), "resolution_0": ("shadow", {"resolution": 0}),
                   "opacity": ("opacity", 1.5)}
            for name, (key, value) in bad.items():
                scene = base_scene()
                scene["lights"] = [light("directional", direction=[0, -1, 0])]
                if key == "opacity":
                    scene["materials"]["glass"]["opacity"] = value
                else:
                    scene["lights"][0]["shadow"] = value
                path = os.path.join(tmp, name + ".json")
                json.dump(scene, open(path, "w"))
                png = os.path.join(tmp, name + ".png")
                rc, out = run(exe, small + ["--scene", path, "--out", png])
                lines = [l for l in out.splitlines() if l.strip()]
                if rc != 2 or len(lines) != 1 or path not in lines[0] or os.path.exists(png):
                    fail(f"{name}: want exit 2, one line naming {path}, no PNG (got exit {rc})", out)
                print(f"{name}: ok: {lines[0]}")
        else:
            fail("unknown case " + case)
    print(case, "passed")


if __name__ == "__main__":
    main()
