#!/usr/bin/env python3
"""Unit tests of bench/tradeoff_lib (the time-against-error sweep, docs/tradeoffs.md): the pure
parts, against values worked out by hand. Standard library only; runs no lab and needs neither
a build nor matplotlib.

    python3 tests/test_tradeoff.py        (CTest: test_tradeoff)
"""
import csv
import io
import os
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))

from tradeoff_lib import check, cli, device, knobs, measure, plot, results, scenes  # noqa: E402


def measured(name, cpu_ms, error, group="g", spread=0.0, key="mean_abs", **roles):
    """A configuration as measure() leaves it (one round)."""
    c = knobs.config(name, group, {}, **roles)
    c.update(cpu_ms=cpu_ms, cpu_spread_ms=spread, median_ms=2 * cpu_ms, p95_ms=3 * cpu_ms, spread_ms=0.0,
             best_ms=2 * cpu_ms, times=[2 * cpu_ms], errors={key: error})
    return c


class ParetoFront(unittest.TestCase):
    # cpu_ms, error: A (1, 5), B (2, 3), C (3, 4), D (4, 1), E (5, 2).
    # C is beaten by B (cheaper and better), E by D; A, B and D are the front.
    POINTS = [("A", 1, 5), ("B", 2, 3), ("C", 3, 4), ("D", 4, 1), ("E", 5, 2)]

    def front(self, spreads=None, key="mean_abs"):
        cs = [measured(n, cpu, e, spread=(spreads or {}).get(n, 0.0), key=key) for n, cpu, e in self.POINTS]
        results.mark_front(cs, {"g": {"front": True}}, key)
        return {c["config"]: (c["on_front"], c["dominated_by"]) for c in cs}

    def test_five_points(self):
        self.assertEqual(self.front(), {"A": ("yes", ""), "B": ("yes", ""), "C": ("no", "B"),
                                        "D": ("yes", ""), "E": ("no", "D")})

    def test_dominated_within_the_noise_is_not_listed(self):
        # C's spread 1.5: B is cheaper by 1 ms only, less than the noise (2 + 1.5 > 3); E's 0.5: D still is.
        got = self.front({"C": 1.5, "E": 0.5})
        self.assertEqual(got["C"], ("no", ""))
        self.assertEqual(got["E"], ("no", "D"))

    def test_the_lab_error_figure(self):
        self.assertEqual(self.front(key="shadow_mae")["C"], ("no", "B"))

    def test_several_dominators_in_order(self):
        cs = [measured("A", 1, 1), measured("B", 2, 2), measured("C", 3, 3)]
        results.mark_front(cs, {"g": {"front": True}})
        self.assertEqual([(c["on_front"], c["dominated_by"]) for c in cs], [("yes", ""), ("no", "A"), ("no", "A;B")])

    def test_groups_apart_and_groups_without_front(self):
        cs = [measured("cheap", 1, 1, group="a"), measured("dear", 2, 2, group="b"),
              measured("x", 1, 1, group="bars"), measured("y", 2, 2, group="bars")]
        results.mark_front(cs, {"a": {"front": True}, "b": {"front": True}, "bars": {"front": False}})
        self.assertEqual([(c["on_front"], c["dominated_by"]) for c in cs],
                         [("yes", ""), ("yes", ""), ("", ""), ("", "")])

    def test_equal_error_does_not_dominate(self):
        cs = [measured("A", 1, 2), measured("B", 2, 2)]
        results.mark_front(cs, {"g": {"front": True}})
        self.assertEqual([c["on_front"] for c in cs], ["yes", "yes"])


class CsvRows(unittest.TestCase):
    def test_columns(self):
        self.assertEqual(len(results.CSV_FIELDS), 28)
        self.assertEqual(results.CSV_FIELDS[:3], ["lab", "group", "config"])
        self.assertEqual(results.CSV_FIELDS[14:], ["mean_abs", "p99_abs", "max_abs", "over_2", "mean_de2000",
                                                   "p99_de2000", "wrong_side_pct", "shadow_mae", "on_front",
                                                   "dominated_by", "device", "device_type", "lp_num_threads",
                                                   "cpu_model"])

    LAVAPIPE = {"device": "llvmpipe (LLVM 15.0.6, 256 bits)", "device_type": "cpu", "lp_num_threads": "2",
                "cpu_model": "AMD EPYC 7B13"}

    def row(self, on=None):
        c = knobs.config("all curved at 32", "tessellation", {}, knob=32, default=True, seed="seed 000")
        c.update(median_ms=1.23456, p95_ms=2.0, spread_ms=0.1, best_ms=1.2, cpu_ms=3.14159, cpu_spread_ms=0.25,
                 times=[1.234, 5.678], on_front="yes", dominated_by="",
                 errors={"mean_abs": 0.25, "p99_abs": 4.0, "max_abs": 141.0, "over_2": 1.5, "mean_de2000": 0.123456,
                         "p99_de2000": 2.0})
        return results.csv_row("lab1_camera", c, 2, on)

    def test_row(self):
        row = self.row()
        self.assertEqual(set(row), set(results.CSV_FIELDS))
        self.assertEqual((row["knob"], row["default"], row["seed"], row["rounds"]), (32, "yes", "seed 000", 2))
        self.assertEqual((row["median_ms"], row["cpu_ms"], row["cpu_spread_ms"]), ("1.235", "3.142", "0.250"))
        self.assertEqual(row["round_ms"], "1.23;5.68")
        self.assertEqual((row["mean_abs"], row["mean_de2000"], row["max_abs"]), ("0.2500", "0.1235", "141.0000"))
        self.assertEqual((row["wrong_side_pct"], row["shadow_mae"]), ("", ""))  # lab 4's figures only
        self.assertEqual((row["device"], row["device_type"], row["lp_num_threads"], row["cpu_model"]), ("", "", "", ""))
        row = self.row(self.LAVAPIPE)
        self.assertEqual((row["device"], row["device_type"], row["lp_num_threads"], row["cpu_model"]),
                         ("llvmpipe (LLVM 15.0.6, 256 bits)", "cpu", "2", "AMD EPYC 7B13"))

    def test_device_round_trip(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "lab.csv")
            results.write_rows(path, [self.row(self.LAVAPIPE)])
            c = results.from_row(results.read_rows(path)[0], {})
        self.assertEqual(c["device"], self.LAVAPIPE)
        self.assertEqual(device.label(c["device"]), "llvmpipe (LLVM 15.0.6, 256 bits) (cpu; AMD EPYC 7B13, LP_NUM_THREADS=2)")

    def test_old_csv_without_device(self):
        # A CSV written before the device was recorded (the committed ones): readable, "not recorded".
        old = "lab,group,config,cpu_ms,cpu_spread_ms,median_ms,p95_ms,spread_ms,best_ms,rounds,mean_abs,on_front,dominated_by\n" \
              "lab1_camera,tessellation,sphere 8,1.5,0.1,2.0,2.5,0.2,1.9,3,0.7,yes,\n"
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "old.csv")
            with open(path, "w") as f:
                f.write(old)
            rows = results.read_rows(path)
        c = results.from_row(rows[0], {})
        self.assertEqual((c["cpu_ms"], c["errors"]), (1.5, {"mean_abs": 0.7}))
        self.assertEqual(c["device"], {"device": "", "device_type": "", "lp_num_threads": "", "cpu_model": ""})
        self.assertEqual(device.label(c["device"]), "device not recorded")
        self.assertEqual(device.problems(rows), ["sphere 8: no device",
                                                 "sphere 8: device_type '' is not one of "
                                                 "['cpu', 'integrated', 'discrete', 'virtual', 'other']"])

    def test_round_trip(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "lab.csv")
            results.write_rows(path, [self.row()])
            with open(path, newline="") as f:
                self.assertEqual(f.readline().strip(), ",".join(results.CSV_FIELDS))
            rows = results.read_rows(path)
        self.assertEqual(len(rows), 1)
        c = results.from_row(rows[0], {})
        self.assertEqual((c["config"], c["group"], c["cpu_ms"], c["median_ms"]),
                         ("all curved at 32", "tessellation", 3.142, 1.235))
        self.assertEqual(c["errors"], {"mean_abs": 0.25, "p99_abs": 4.0, "max_abs": 141.0, "over_2": 1.5,
                                       "mean_de2000": 0.1235, "p99_de2000": 2.0})
        self.assertEqual((c["default"], c["series"]), (False, ""))  # roles: from the knob table only
        known = {"all curved at 32": knobs.config("all curved at 32", "x", {}, knob=32, default=True, series="all")}
        c = results.from_row(rows[0], known)
        self.assertEqual((c["default"], c["series"], c["group"]), (True, "all", "tessellation"))


class Parsing(unittest.TestCase):
    BENCHMARK = ("lab1_camera: Vulkan 1.3, llvmpipe\n"
                 "benchmark lab=lab1_camera width=64 height=36 frames=3 min_ms=0.635 median_ms=0.657 "
                 "p95_ms=0.717 mean_ms=0.670 device=llvmpipe_(LLVM_15.0.6,_256_bits) device_type=cpu\n")
    CPUINFO = ("processor\t: 0\nvendor_id\t: AuthenticAMD\nmodel name\t: AMD EPYC 7B13  64-Core Processor\n"
               "processor\t: 1\nmodel name\t: AMD EPYC 7B13  64-Core Processor\n")

    def test_benchmark_line(self):
        self.assertEqual(measure.parse_fields(self.BENCHMARK, "benchmark"),
                         {"lab": "lab1_camera", "width": "64", "height": "36", "frames": "3", "min_ms": "0.635",
                          "median_ms": "0.657", "p95_ms": "0.717", "mean_ms": "0.670",
                          "device": "llvmpipe_(LLVM_15.0.6,_256_bits)", "device_type": "cpu"})

    def test_window_benchmark_line(self):
        line = ("benchmark lab=lab2_lighting width=1280 height=720 frames=300 min_ms=0.2 median_ms=0.237 p95_ms=0.3 "
                "mean_ms=0.25 target=window device=NVIDIA_H200 device_type=discrete\n")
        fields = measure.parse_fields(line, "benchmark")
        self.assertEqual((fields["target"], fields["device"], fields["device_type"]),
                         ("window", "NVIDIA_H200", "discrete"))

    def test_cpu_model(self):
        self.assertEqual(device.cpu_model(self.CPUINFO), "AMD EPYC 7B13 64-Core Processor")
        self.assertEqual(device.cpu_model("processor\t: 0\nCPU part\t: 0xd0c\n"), "")  # no model name (arm)

    def test_device_of_a_cpu_run(self):
        fields = measure.parse_fields(self.BENCHMARK, "benchmark")
        self.assertEqual(device.of_benchmark(fields, {"LP_NUM_THREADS": "2"}, "AMD EPYC 7B13"),
                         {"device": "llvmpipe (LLVM 15.0.6, 256 bits)", "device_type": "cpu",
                          "lp_num_threads": "2", "cpu_model": "AMD EPYC 7B13"})

    def test_device_of_a_gpu_run(self):
        # A GPU: LP_NUM_THREADS and the CPU do not make its figures, so they are not recorded.
        fields = {"median_ms": "0.237", "device": "NVIDIA_H200", "device_type": "discrete"}
        d = device.of_benchmark(fields, {"LP_NUM_THREADS": "2"}, "AMD EPYC 7B13")
        self.assertEqual(d, {"device": "NVIDIA H200", "device_type": "discrete", "lp_num_threads": "", "cpu_model": ""})
        self.assertEqual(device.label(d), "NVIDIA H200 (discrete)")
        self.assertEqual(device.title_parts(d), ("NVIDIA H200 (discrete)", ""))

    def test_title_parts(self):
        lavapipe = {"device": "llvmpipe (LLVM 15.0.6, 256 bits)", "device_type": "cpu", "lp_num_threads": "2",
                    "cpu_model": "AMD EPYC 7B13"}
        self.assertEqual(device.title_parts(lavapipe), ("llvmpipe (LLVM 15.0.6, 256 bits) (cpu)",
                                                        "AMD EPYC 7B13, LP_NUM_THREADS=2"))
        self.assertEqual(device.title_parts({"device": ""}), ("device not recorded", ""))
        self.assertEqual(device.title_parts(None), ("device not recorded", ""))

    def test_a_line_without_device_exits(self):
        with self.assertRaises(SystemExit):
            device.of_benchmark({"median_ms": "0.657"}, {}, "")

    def test_first_line_with_the_prefix(self):
        text = "note median_ms=9\nstarting benchmark median_ms=8\nbenchmark median_ms=1\nbenchmark median_ms=2\n"
        self.assertEqual(measure.parse_fields(text, "benchmark"), {"median_ms": "1"})
        self.assertEqual(measure.parse_fields(text, ""), {"median_ms": "9"})

    def test_missing_line_exits(self):
        with self.assertRaises(SystemExit):
            measure.parse_fields("benchmark\nno fields here\n", "benchmark")

    def test_compare_errors(self):
        fields = measure.parse_fields("mean_abs=0.2508 p99_abs=4.0 max_abs=141 over_2=1.25% mean_de2000=0.1 "
                                      "p99_de2000=2 pixels=57600 masked=0", "mean_abs")
        self.assertEqual(measure.parse_errors(fields), {"mean_abs": 0.2508, "p99_abs": 4.0, "max_abs": 141.0,
                                                        "over_2": 1.25, "mean_de2000": 0.1, "p99_de2000": 2.0})
        self.assertEqual(measure.parse_errors({"wrong_side_pct": "0.5%", "shadow_mae": "0.4", "pixels": "1"}),
                         {"wrong_side_pct": 0.5, "shadow_mae": 0.4})

    def test_cpu_ms_per_frame(self):
        self.assertAlmostEqual(measure.cpu_ms_per_frame([0.5, 1.7], 5), 300.0)  # 1.2 s over 4 frames
        self.assertEqual(measure.cpu_ms_per_frame([0.5, 0.4], 5), 0.0)


class Rounds(unittest.TestCase):
    def test_summary(self):
        c = {"times": [3.0, 1.0, 2.0], "p95s": [4.0, 6.0, 5.0], "cpu": [10.0, 12.0, 17.0]}
        measure.summarize(c)
        self.assertEqual((c["median_ms"], c["p95_ms"], c["spread_ms"], c["best_ms"], c["cpu_ms"], c["cpu_spread_ms"]),
                         (2.0, 5.0, 2.0, 1.0, 12.0, 7.0))

    def test_order(self):
        self.assertEqual(measure.round_order(5, 0), [0, 1, 2, 3, 4])
        shuffled = [measure.round_order(20, r) for r in (1, 2)]
        self.assertEqual([sorted(o) for o in shuffled], [list(range(20))] * 2)
        self.assertNotEqual(shuffled[0], shuffled[1])
        self.assertNotEqual(shuffled[0], list(range(20)))
        self.assertEqual(measure.round_order(20, 1), shuffled[0])  # repeatable

    def test_select(self):
        cs = [knobs.config("flat 8", "a", {}), knobs.config("phong 8", "a", {}), knobs.config("phong 16", "b", {})]
        self.assertEqual([c["config"] for c in measure.select(cs, "a")], ["flat 8", "phong 8"])
        self.assertEqual([c["config"] for c in measure.select(cs, None, "^phong")], ["phong 8", "phong 16"])
        self.assertEqual([c["config"] for c in measure.select(cs, "a", "16")], [])
        self.assertEqual(len(measure.select(cs)), 3)


class SceneVariants(unittest.TestCase):
    SCENE = {"objects": [{"mesh": "sphere"}, {"mesh": "cylinder", "rings": 4}, {"mesh": "torus"},
                         {"mesh": "cube"}, {"mesh": "cone", "segments": 5}],
             "lighting": {"shading": "flat", "model": "phong"},
             "materials": {"m": {"sampler": {"filter": "nearest", "wrap": "repeat", "anisotropy": 4}}},
             "lights": [{"type": "point", "cast_shadows": True, "shadow": {"pcf": 3}}, {"type": "spot"}]}

    def test_tessellate(self):
        t = scenes.tessellate(self.SCENE, 8)
        self.assertEqual(t["objects"], [{"mesh": "sphere", "segments": 8, "rings": 4}, {"mesh": "cylinder", "segments": 8},
                                        {"mesh": "torus", "segments": 12, "rings": 4}, {"mesh": "cube"},
                                        {"mesh": "cone", "segments": 8}])
        self.assertEqual(scenes.tessellate(self.SCENE, 2)["objects"][2], {"mesh": "torus", "segments": 3, "rings": 3})
        self.assertEqual(self.SCENE["objects"][0], {"mesh": "sphere"})  # the input is left alone

    def test_set_mesh(self):
        t = scenes.set_mesh(self.SCENE, "cylinder", 16, 0)
        self.assertEqual(t["objects"][1], {"mesh": "cylinder", "segments": 16, "rings": 4})
        t = scenes.set_mesh(self.SCENE, "sphere", 64, 32)
        self.assertEqual(t["objects"][0], {"mesh": "sphere", "segments": 64, "rings": 32})

    def test_with_shadow(self):
        t = scenes.with_shadow(self.SCENE, {"resolution": 512})
        self.assertEqual([l.get("shadow") for l in t["lights"]], [{"resolution": 512}, None])

    def test_truth(self):
        t = scenes.truth_of(scenes.tessellate(self.SCENE, 8))
        self.assertEqual(t["objects"], [{"mesh": "sphere"}, {"mesh": "cylinder"}, {"mesh": "torus"}, {"mesh": "cube"},
                                        {"mesh": "cone"}])
        self.assertEqual(t["lighting"], {"model": "phong"})
        self.assertEqual(t["materials"]["m"]["sampler"], {"wrap": "repeat"})
        t = scenes.truth_of(self.SCENE, "lab4_shadows")
        self.assertEqual(t["lights"][0], {"type": "point", "cast_shadows": True})
        self.assertEqual(t["objects"][1], {"mesh": "cylinder", "rings": 4})  # lab 4: the meshes matter

    def test_load_scene_makes_paths_absolute(self):
        s = scenes.load_scene("lab4_shadows.json")
        meshes = [o["mesh"] for o in s["objects"] if o["mesh"] not in scenes.PRIMITIVES]
        self.assertTrue(meshes and all(os.path.isabs(m) and os.path.exists(m) for m in meshes))
        maps = [m[k] for m in s["materials"].values() for k in scenes.TEXTURE_KEYS if k in m]
        self.assertIn(os.path.join(ROOT, "scenes", "textures", "tiles.png"), maps)
        self.assertIn("procedural:metal", maps)


class Configurations(unittest.TestCase):
    def names(self, lab, quick):
        return [c["config"] for c in knobs.KNOBS[lab]["configs"](quick)]

    def test_interleave(self):
        self.assertEqual(knobs.interleave([[1, 2, 3], [4], [5, 6]]), [1, 4, 5, 2, 6, 3])
        self.assertEqual([l["type"] for l in knobs.many_lights(5)], ["directional", "point", "spot", "directional", "point"])
        self.assertEqual(len(knobs.many_lights(72)), 72)

    def test_lab1(self):
        cs = knobs.lab1_configs(True)
        self.assertEqual([(c["config"], c["knob"], c["default"], c["series"]) for c in cs],
                         [("all curved at 8", 8, False, "all"), ("all curved at 16", 16, False, "all"),
                          ("all curved at 32", 32, True, "all"), ("all curved at 64", 64, False, "all")])
        full = knobs.lab1_configs(False)
        self.assertEqual(len(full), 11 + 14)
        torus = [c for c in full if c["config"] == "torus 96x32"][0]
        self.assertEqual((torus["knob"], torus["series"]), (96 * 32, ""))
        self.assertEqual([c["knob"] for c in full if c["config"].startswith("cone")], [16, 64])

    def test_lab2(self):
        self.assertEqual(self.names("lab2_lighting", True),
                         ["flat 8", "flat 16", "flat 32", "phong 8", "phong 16", "phong 32", "lambert", "blinn_phong",
                          "1 lights", "8 lights"])
        full = knobs.lab2_configs(False)
        self.assertEqual(len(full), 15 + 8 + 7)
        self.assertEqual([(c["config"], c["seed"]) for c in full if c["seed"]], [("phong 32", "seed 000"),
                                                                                  ("phong", "seed 001")])
        self.assertEqual([c["config"] for c in full if c["default"]], ["phong 32", "blinn_phong"])
        self.assertEqual([c["config"] for c in full if c.get("slow")], ["32 lights", "72 lights"])
        self.assertTrue(all(c["scene"]["lighting"]["markers"] is False for c in full))

    def test_lab3(self):
        cs = knobs.lab3_configs(True)
        self.assertEqual([(c["config"], c["knob"], c["default"], c["seed"]) for c in cs],
                         [("nearest", 1, False, ""), ("trilinear", 1, False, ""),
                          ("trilinear + aniso 16", 16, False, "seed 002"),
                          ("bilinear, nearest mips + probes 4", 4, True, "")])
        self.assertEqual(cs[0]["scene"]["materials"]["floor"]["sampler"],
                         {"filter": "nearest", "mipmaps": "none", "anisotropy": 1, "wrap": "repeat"})
        self.assertEqual(len(knobs.lab3_configs(False)), 11)

    def test_lab4(self):
        quick, full = knobs.lab4_configs(True), knobs.lab4_configs(False)
        # Per scene: filter × kernels × resolutions, the fitted default and the seed.
        self.assertEqual((len(quick), len(full)), (2 * (2 * 2 * 2 + 2), 2 * (2 * 4 * 4 + 2)))
        self.assertEqual([(c["group"], c["config"]) for c in full if c["default"]],
                         [("default scene", "2048 pcf1 nearest"), ("grazing stress", "2048 pcf1 nearest")])
        seed = [c for c in full if c["seed"]][0]
        shadows = [l["shadow"] for l in seed["scene"]["lights"] if l.get("cast_shadows")]
        self.assertTrue(shadows and all(s == knobs.LAB4_SEED for s in shadows))
        self.assertEqual(quick[1]["config"], "2048 pcf1 nearest")
        self.assertEqual(quick[1]["series"], "nearest 1x1")
        # The default with maps sized to the picture: in no series (its knob is the cap, not the size).
        fitted = [c for c in full if c["config"] == "2048 pcf1 nearest, fit to view"]
        self.assertEqual(len(fitted), 2)
        self.assertTrue(all(not c["series"] and not c["default"] for c in fitted))
        shadows = [l["shadow"] for l in fitted[0]["scene"]["lights"] if l.get("cast_shadows")]
        self.assertTrue(shadows and all(s == dict(knobs.LAB4_DEFAULT, fit_to_view=True) for s in shadows))

    def test_lab_settings(self):
        self.assertEqual([knobs.frames(lab, False) for lab in sorted(knobs.KNOBS)], [61, 21, 21, 16])
        self.assertEqual(knobs.frames("lab4_shadows", True), 3)
        self.assertEqual((knobs.size("lab4_shadows", False), knobs.size("lab4_shadows", True)), ((640, 360), (320, 180)))
        self.assertEqual((knobs.error_key("lab1_camera"), knobs.error_key("lab4_shadows")), ("mean_abs", "shadow_mae"))
        self.assertEqual(knobs.KNOBS["lab4_shadows"]["time_args"], ["--dev-animate-lights"])


class QuickCheck(unittest.TestCase):
    def rows(self, n=2):
        out = io.StringIO()
        wr = csv.DictWriter(out, fieldnames=results.CSV_FIELDS)
        wr.writeheader()
        for i in range(n):
            wr.writerow(dict({k: "1.0" for k in results.CSV_FIELDS}, config=f"c{i}", default="yes" if i == 0 else "",
                             device="llvmpipe (LLVM 15.0.6, 256 bits)", device_type="cpu", lp_num_threads="2",
                             cpu_model="AMD EPYC 7B13"))
        return list(csv.DictReader(io.StringIO(out.getvalue())))

    def test_good_csv(self):
        self.assertEqual(check.csv_problems(self.rows(), 2), [])

    def test_bad_csv(self):
        rows = self.rows()
        rows[0]["default"] = ""
        rows[1]["cpu_ms"] = "nan"
        rows[1]["mean_abs"] = ""
        self.assertEqual(check.csv_problems(rows, 3),
                         ["2 rows for 3 configurations", "c1: cpu_ms = nan", "c1: mean_abs = '' is not a number",
                          "no default configuration"])

    def test_device_columns(self):
        rows = self.rows(3)
        rows[0]["device"] = ""
        rows[1]["cpu_model"] = ""
        rows[2].update(device="NVIDIA H200", device_type="discrete", lp_num_threads="", cpu_model="")
        self.assertEqual(check.csv_problems(rows, 3),
                         ["c0: no device", "c1: a CPU device without LP_NUM_THREADS or CPU model",
                          "several devices in one CSV: NVIDIA H200 (discrete); device not recorded; "
                          "llvmpipe (LLVM 15.0.6, 256 bits) (cpu; , LP_NUM_THREADS=2)"])
        rows = self.rows(1)
        rows[0]["device_type"] = "gpu"
        self.assertEqual(check.csv_problems(rows, 1),
                         ["c0: device_type 'gpu' is not one of ['cpu', 'integrated', 'discrete', 'virtual', 'other']"])

    def test_series_must_fall(self):
        ok = [measured("8", 1, 0.25, knob=8, series="all"), measured("16", 2, 0.08, knob=16, series="all")]
        self.assertEqual(check.series_problems(ok), [])
        bad = ok + [measured("32", 3, 0.08, knob=32, series="all")]
        self.assertEqual(check.series_problems(bad), ["series all: error at 16 (0.08) not above error at 32 (0.08)"])

    def test_order(self):
        cs = [measured("nearest", 1, 9.3), measured("trilinear", 2, 3.3)]
        self.assertEqual(check.order_problems(cs, [("trilinear", "nearest"), ("absent", "nearest")]), [])
        self.assertEqual(check.order_problems(cs, [("nearest", "trilinear")]),
                         ["error of nearest (9.3) not below error of trilinear (3.3)"])


class CommandLine(unittest.TestCase):
    def test_defaults(self):
        a = cli.parse_args(["lab1_camera", "--build", "/b"])
        self.assertEqual((a.frames, a.rounds, a.out_dir), (61, 3, os.path.join(ROOT, "docs", "tradeoffs")))
        a = cli.parse_args(["lab2_lighting", "--quick", "--build", "/b"])
        self.assertEqual((a.frames, a.rounds, a.out_dir), (3, 1, "/b/tradeoff_quick"))
        a = cli.parse_args(["lab4_shadows", "--build", "/b", "--frames", "5", "--out-dir", "/o"])
        self.assertEqual((a.frames, a.rounds, a.out_dir), (5, 3, "/o"))

    def test_title_note(self):
        a = cli.parse_args(["lab1_camera", "--quick"])
        self.assertEqual(cli.title_note("lab1_camera", a), "320x180, 1 interleaved rounds x 3 frames; "
                                                         "bars: round-to-round spread")
        a = cli.parse_args(["lab4_shadows"])
        self.assertTrue(cli.title_note("lab4_shadows", a).startswith("640x360, 3 interleaved"))
        self.assertTrue(cli.title_note("lab4_shadows", a).endswith(
            "; time: a frame that re-renders every shadow map (--dev-animate-lights), error: the static picture"))


class Panels(unittest.TestCase):
    def kinds(self, lab, quick):
        return [(g, k) for g, _, k in plot.panels(lab, knobs.KNOBS[lab]["configs"](quick))]

    def test_panels(self):
        self.assertEqual(self.kinds("lab1_camera", True), [("tessellation", "front")])
        self.assertEqual(self.kinds("lab1_camera", False), [("tessellation", "front"), ("tessellation", "zoom")])
        self.assertEqual(self.kinds("lab2_lighting", True), [("shading x tessellation", "front"),
                                                             ("lighting model", "bars"), ("light count", "count")])
        self.assertEqual(self.kinds("lab3_textures", True), [("sampler", "labelled")])
        self.assertEqual(self.kinds("lab4_shadows", True), [("default scene", "front"), ("default scene", "zoom"),
                                                            ("grazing stress", "front"), ("grazing stress", "zoom")])


if __name__ == "__main__":
    unittest.main()
