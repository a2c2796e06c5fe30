#!/usr/bin/env python3
"""soak.py — every lab in a real window for a while, driven like a restless user.

    python3 bench/soak.py [MINUTES] [LAB...]    default: 10 minutes for every lab that is built
    python3 bench/soak.py 1 lab2_lighting       (what the CTest version lab2_soak runs)

Each lab runs with --validate under its own Xvfb and openbox (a real window manager, so that
minimize and restore are real). xdotool sends, in a fixed pseudo-random order (SOAK_SEED):
window resizes (to 1×1 and back included), minimize + restore, camera keys (W A S D, Space,
Shift), mouse drags and wheel steps, the camera-mode key (C), the reload key (R), and rewrites
of the scene file that alternate a good and a broken scene; the good ones add and remove an
object and, from lab 2 on, add and remove lights (down to none); from lab 4 on they also switch
every light's shadow off and on (with other PCF, filter and map size), take every object's
shadow away and make every material translucent.

Every input must be answered within SOAK_ANSWER_S seconds (default 10): the lab's status file
(--dev-status-file PATH, common/dev/status_file.h) shows a frame drawn after the input — after a
resize, at the new size — and a scene write shows "reloaded" on stdout or "reload failed" on
stderr. So the soak also works for a lab that draws only when something happens: every input
wakes it. The first frame (start-up: shader compilation, uploads) gets SOAK_START_S (default 60).
Resident memory (VmRSS) is read at rest — after every input answered by a frame drawn, so the
renderer in use has drawn at least once, and once the lab has gone idle after it (its status line
ends in " idle": frames finished, freed memory given back with malloc_trim) — and, for the record,
every SOAK_SAMPLE_S seconds (default 3).

Pass: no crash; every input answered; no validation message (the lab, closed with Alt+F4 at the
end, exits 0; it exits 1 after any message) and nothing unexpected on stderr; resident memory
after the warm-up — the first minute, or the first third of a shorter run — grows by less than
1 % (SOAK_MEMORY_GATE; the samples at rest of the last quarter of the time after the warm-up
against those of the first quarter, each divided by the usual level of the scene variant it was
taken with: bench/soak_memory.py; at least SOAK_MIN_SAMPLES after the warm-up, default 10).
Prints the figures per lab; exit 0 when every lab passed, 1 otherwise, 2 for bad usage.
SOAK_KEEP=1 keeps each lab's folder (logs, the RSS samples, the inputs with their times) even
when it passed. For finding where memory goes: SOAK_ACTIONS="scene reload" (only those inputs;
names: resize tiny minimize key drag wheel mode scene reload pause) and SOAK_NO_VALIDATE=1 (the
lab without the validation layer; such a run is not a pass of the soak). LAB_BUILD_DIR: where the
labs are built (default build/).
"""
import copy
import ctypes
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path

sys.dont_write_bytecode = True  # no __pycache__ in the source tree for the import below
from soak_memory import TooFewSamples, memory_figure, per_minute_medians, read_samples  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
LABS = ("lab1_camera", "lab2_lighting", "lab3_textures", "lab4_shadows")
TOOLS = ("Xvfb", "openbox", "xdotool", "xprop")
# Weighted: names repeat. SOAK_ACTIONS="resize scene" keeps only those (to find what costs memory).
ACTIONS = ("resize", "resize", "tiny", "minimize", "key", "key", "key", "drag", "drag", "drag", "wheel",
           "mode", "mode", "scene", "scene", "scene", "scene", "reload", "pause", "pause")
# The inputs answered by a frame drawn: resident memory is sampled at rest after them.
FRAME_ACTIONS = ("resize", "tiny", "minimize", "key", "drag", "wheel", "mode")
SIZES = ((1, 1), (2, 3), (64, 48), (320, 200), (1280, 720), (333, 777), (1000, 10), (10, 700))
CAMERA_KEYS = ("w", "a", "s", "d", "space", "shift")
RESTORED_SIZE = (960, 600)
EXPECTED_STDERR = "reload failed, keeping the last good scene: "
NUMBER = re.compile(r"[0-9]+([.][0-9]+)?")
STATUS_LINE = re.compile(r"frame=([0-9]+) width=([0-9]+) height=([0-9]+)( idle)?")


class UsageError(Exception):
    """Bad command line or settings: one line, exit 2."""


class StepFailed(Exception):
    """A step of the soak failed; the reason has been recorded and printed."""


# ---------------------------------------------------------------- settings

@dataclass
class Settings:
    """The soak's command line and environment knobs (module docstring)."""
    seconds: int
    warmup: int
    answer_s: float
    start_s: float
    sample_s: float
    seed: int
    gate: float
    min_samples: int
    keep: bool
    validate: bool
    actions: tuple
    build: Path


def _env_number(env, name, default, kind=float, what="a number"):
    """The environment knob NAME as a number (DEFAULT when unset or empty); UsageError when it is not one."""
    text = env.get(name, "") or default
    if not NUMBER.fullmatch(text) or (kind is int and "." in text):
        raise UsageError("%s must be %s, got '%s'" % (name, "a whole number" if kind is int else what, text))
    return kind(text)


def parse_settings(argv, env):
    """The settings and the labs to soak, from the arguments (without the program) and ENV."""
    minutes = argv[0] if argv else "10"
    if not NUMBER.fullmatch(minutes):
        raise UsageError("MINUTES must be a number, got '%s' (usage: bench/soak.py [MINUTES] [LAB...])" % minutes)
    gate = _env_number(env, "SOAK_MEMORY_GATE", "1", what="a percentage")
    actions = ACTIONS
    if env.get("SOAK_ACTIONS"):
        wanted = env["SOAK_ACTIONS"].split()
        actions = tuple(a for a in ACTIONS if a in wanted)
        if not actions:
            raise UsageError("SOAK_ACTIONS='%s' names none of: %s"
                             % (env["SOAK_ACTIONS"], " ".join(dict.fromkeys(ACTIONS))))
    seconds = int(float(minutes) * 60)
    settings = Settings(
        seconds=seconds, warmup=60 if seconds >= 180 else seconds // 3,
        answer_s=_env_number(env, "SOAK_ANSWER_S", "10"), start_s=_env_number(env, "SOAK_START_S", "60"),
        sample_s=_env_number(env, "SOAK_SAMPLE_S", "3"), seed=_env_number(env, "SOAK_SEED", "1", int),
        gate=gate, min_samples=_env_number(env, "SOAK_MIN_SAMPLES", "10", int),
        keep=bool(env.get("SOAK_KEEP")), validate=not env.get("SOAK_NO_VALIDATE"), actions=actions,
        build=Path(env.get("LAB_BUILD_DIR") or ROOT / "build"))
    for tool in TOOLS:
        if not shutil.which(tool):
            raise UsageError("%s not found: run scripts/setup.sh (it installs xvfb, openbox, xdotool, x11-utils)"
                             % tool)
    labs = list(argv[1:]) or [lab for lab in LABS if os.access(settings.build / lab / lab, os.X_OK)]
    if not labs:
        raise UsageError("no lab built in %s (run scripts/setup.sh)" % settings.build)
    return settings, labs


# ---------------------------------------------------------------- small helpers

LIBC = ctypes.CDLL(None)
PR_SET_PDEATHSIG = 1


def die_with_parent():
    """In a child before exec: SIGTERM it when the soak dies, even killed (a CTest timeout)."""
    LIBC.prctl(PR_SET_PDEATHSIG, int(signal.SIGTERM))


def tail(path, n):
    """The last N lines of a text file, joined by newlines ("" when it cannot be read)."""
    try:
        return "\n".join(Path(path).read_text(errors="replace").splitlines()[-n:])
    except OSError:
        return ""


def lines_of(path):
    """The lines of a text file (none when it cannot be read)."""
    try:
        return Path(path).read_text(errors="replace").splitlines()
    except OSError:
        return []


def count_lines(path, prefix):
    """How many lines of PATH start with PREFIX."""
    return sum(1 for line in lines_of(path) if line.startswith(prefix))


def xdo(*args, quiet=False):
    """xdotool ARGS with a 5-s limit (its --sync waits forever for a window that never changes); True if it worked."""
    out = subprocess.DEVNULL if quiet else None
    try:
        return subprocess.run(["xdotool", *map(str, args)], stdout=out, stderr=out, timeout=5).returncode == 0
    except subprocess.TimeoutExpired:
        return False


def vm_rss(pid):
    """The process's resident memory and its anonymous part in KiB, as text ("" when unknown)."""
    fields = {}
    try:
        for line in Path("/proc/%d/status" % pid).read_text().splitlines():
            key, _, value = line.partition(":")
            fields[key] = value.split()[0] if value.split() else ""
    except OSError:
        pass
    return fields.get("VmRSS", ""), fields.get("RssAnon", "")


def elapsed(t0):
    """Seconds since T0."""
    return time.time() - t0


def say(lab, text):
    """One line of the report."""
    print("soak: %s: %s" % (lab, text), flush=True)


# ---------------------------------------------------------------- the scene variants

def _changed(scene, **changes):
    """A copy of SCENE with its top-level keys CHANGES replaced."""
    return {**copy.deepcopy(scene), **copy.deepcopy(changes)}


def _each_changed(scene, key, **changes):
    """A copy of SCENE in which every item of SCENE[KEY] (a list or an object's values) gets CHANGES."""
    result = copy.deepcopy(scene)
    items = result[key].values() if isinstance(result[key], dict) else result[key]
    for item in items:
        item.update(changes)
    return result


def _shadows_all_pcf5(light):
    """The light casting shadows with a 256-texel map, PCF 5 and bilinear filtering."""
    return {**light, "cast_shadows": True,
            "shadow": {**(light.get("shadow") or {}), "resolution": 256, "pcf": 5, "filter": "bilinear"}}


def _json_bytes(scene):
    """A scene as the file the soak writes (indented JSON)."""
    return (json.dumps(scene, indent=2, ensure_ascii=False) + "\n").encode()


def scene_variants(lab, base):
    """The good and the broken scene files the soak writes for LAB, from its scene file BASE.

    Returns (goods, brokens), lists of (name, bytes); goods[0] is the lab's own scene. The good ones
    add an object; from lab 2 on they add and remove lights (down to none); from lab 4 on they
    switch every light's shadow off and on (with other PCF, filter and map size), take every
    object's shadow away and make every material translucent. The broken ones: the scene cut in
    half, a negative near plane."""
    text = base.read_bytes()
    scene = json.loads(text)
    own = (base.stem, text)
    objects, lights = scene.get("objects") or [], scene.get("lights") or []
    torus = {"mesh": "torus", "material": sorted(scene["materials"])[0], "position": [0, 2.5, 0]}
    goods = [own, ("good_object", _json_bytes(_changed(scene, objects=objects + [torus])))]
    if not lab.startswith("lab1_"):  # from lab 2 on: lights come and go through the scene file
        added = {"type": "point", "position": [0, 3, 2], "color": [1, 0.6, 0.3], "intensity": 3}
        two = [{"type": "point", "position": [0, 3, 2], "intensity": 3},
               {"type": "spot", "position": [2, 4, 2], "direction": [-1, -2, -1], "intensity": 5}]
        goods += [("good_light_added", _json_bytes(_changed(scene, lights=lights + [added]))),
                  own,
                  ("good_two_added", _json_bytes(_changed(scene, lights=lights + two))),
                  ("good_light_removed", _json_bytes(_changed(scene, lights=lights[1:]))),
                  ("good_no_lights", _json_bytes(_changed(scene, lights=[])))]
    if not re.match(r"lab[123]_", lab):  # from lab 4 on: shadows off and on, filtered, translucent
        goods += [("good_shadows_off", _json_bytes(_each_changed(scene, "lights", cast_shadows=False))),
                  own,
                  ("good_shadows_all_pcf5",
                   _json_bytes(_changed(scene, lights=[_shadows_all_pcf5(light) for light in lights]))),
                  ("good_no_casters", _json_bytes(_each_changed(scene, "objects", cast_shadows=False))),
                  ("good_translucent", _json_bytes(_each_changed(scene, "materials", opacity=0.5)))]
    brokens = [("broken_truncated", text[:len(text) // 2]),
               ("broken_near", _json_bytes(_changed(scene, camera={**scene.get("camera", {}), "near": -1})))]
    return goods, brokens


# ---------------------------------------------------------------- one lab

class LabSoak:
    """One lab's soak: its X server, window manager, the lab, the inputs, the checks, the report."""

    def __init__(self, lab, settings):
        self.lab, self.s = lab, settings
        self.exe = settings.build / lab / lab
        self.work = Path(tempfile.mkdtemp(prefix="soak_%s." % lab, dir=os.environ.get("TMPDIR") or "/tmp"))
        self.status, self.stdout, self.stderr = self.work / "status", self.work / "stdout", self.work / "stderr"
        self.rss_log, self.rss_rest = self.work / "rss", self.work / "rss_rest"
        self.xvfb = self.wm = self.proc = None
        self.sampler, self.sampler_stop = None, threading.Event()
        self.failure = ""
        self.frame = self.width = self.height = 0
        self.idle = False
        self.before = 0                      # the frame count when the input was sent
        self.want = (0, 0)                   # the size a resize asked for
        self.out_lines = self.err_lines = 0  # "reloaded" / "reload failed" lines before a reload
        self.count, self.worst = {}, {}      # answers per kind: how many, the slowest
        self.not_idle = 0
        self.wid = ""
        self.random = random.Random(settings.seed)
        self.started = time.time()

    # ---- failures and processes
    def fail(self, reason):
        """Records and prints a failure; returns the StepFailed to raise."""
        self.failure = reason
        say(self.lab, "FAIL: " + reason)
        return StepFailed(reason)

    def alive(self):
        """Whether the lab is still running."""
        return self.proc is not None and self.proc.poll() is None

    def died(self):
        """How the lab ended and the last lines of its stderr, for a failure."""
        code = self.proc.poll()
        how = "killed by %s" % signal.Signals(-code).name if code is not None and code < 0 else "exit code %s" % code
        return "the lab died (%s): %s" % (how, tail(self.stderr, 3))

    def stop_sampler(self):
        """Stops the every-SOAK_SAMPLE_S sampler and waits until its file is complete."""
        self.sampler_stop.set()
        if self.sampler is not None:
            self.sampler.join()
        self.sampler = None

    def cleanup(self):
        """Stops what this soak started: the lab, the sampler, the window manager, the X server."""
        self.stop_sampler()
        for p in (self.proc, self.wm, self.xvfb):
            if p is not None and p.poll() is None:
                p.terminate()
        for p in (self.proc, self.wm, self.xvfb):
            if p is not None:
                try:
                    p.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
        self.proc = self.wm = self.xvfb = None

    # ---- the X server, the window manager, the lab
    def start_x(self):
        """A private X server (-displayfd picks a free display) and openbox on it; DISPLAY names it.

        -noreset: by default an X server resets when its last client leaves, and refuses
        connections for that moment. The xprop probes below are such last clients, so openbox,
        started right after one, could find the display closed: 44 of 200 starts here, and three tries
        in a row once in CI; with -noreset 0 of 200."""
        display = self.work / "display"
        with open(display, "w") as fd_file, open(self.work / "xvfb.log", "w") as log:
            self.xvfb = subprocess.Popen(
                ["Xvfb", "-displayfd", str(fd_file.fileno()), "-screen", "0", "1280x800x24", "-nolisten", "tcp",
                 "-noreset"],
                stdout=log, stderr=log, pass_fds=(fd_file.fileno(),), preexec_fn=die_with_parent)
        for _ in range(100):
            if display.read_text().strip():
                break
            time.sleep(0.1)
        if not display.read_text().strip():
            raise self.fail("Xvfb did not start: " + tail(self.work / "xvfb.log", 2))
        os.environ["DISPLAY"] = ":" + display.read_text().strip()
        # -displayfd can name the display a moment before it takes connections (seen under load with
        # several servers starting at once): wait until a client gets in, then start the window
        # manager, and start it again if it gave up before the server answered.
        for _ in range(100):
            if subprocess.run(["xprop", "-root"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 0:
                break
            time.sleep(0.1)
        for _ in range(3):
            if self.start_wm():
                return
        raise self.fail("openbox did not start: " + tail(self.work / "openbox.log", 2))

    def start_wm(self):
        """Starts openbox; True once it has taken the screen (False: it gave up or never did)."""
        with open(self.work / "openbox.log", "w") as log:
            self.wm = subprocess.Popen(["openbox", "--sm-disable"], stdout=log, stderr=log, preexec_fn=die_with_parent)
        for _ in range(100):
            check = subprocess.run(["xprop", "-root", "_NET_SUPPORTING_WM_CHECK"],
                                   capture_output=True, text=True)
            if "window id" in check.stdout:
                return True
            if self.wm.poll() is not None:
                break
            time.sleep(0.1)
        self.wm.terminate()
        self.wm.wait()
        return False

    def prepare_scenes(self):
        """The lab's scene in a folder of its own (models/ and textures/ linked) and its variants."""
        scenes = self.work / "scenes"
        scenes.mkdir()
        (scenes / "models").symlink_to(ROOT / "scenes" / "models")
        if (ROOT / "scenes" / "textures").is_dir():  # lab 3's images
            (scenes / "textures").symlink_to(ROOT / "scenes" / "textures")
        base = ROOT / "scenes" / (self.lab + ".json")
        self.goods, self.brokens = scene_variants(self.lab, base)
        for name, text in self.goods[1:] + self.brokens:  # for the record, and to look at by hand
            if name != base.stem:
                (scenes / (name + ".json")).write_bytes(text)
        self.scene = scenes / "scene.json"
        self.scene.write_bytes(self.goods[0][1])
        self.loaded_scene = base.stem  # the scene variant the lab shows now
        self.goods_i = self.brokens_i = 0
        self.next_good = True

    def start_lab(self):
        """The lab with its status file, and the sampler of its resident memory every SOAK_SAMPLE_S."""
        command = [str(self.exe), *(["--validate"] if self.s.validate else []),
                   "--dev-status-file", str(self.status), "--scene", str(self.scene)]
        with open(self.stdout, "w") as out, open(self.stderr, "w") as err:
            self.proc = subprocess.Popen(command, stdout=out, stderr=err, preexec_fn=die_with_parent)
        self.sampler = threading.Thread(target=self.sample_memory, daemon=True)
        self.sampler.start()
        self.started = time.time()

    def sample_memory(self):
        """The sampler: "time VmRSS RssAnon" every SOAK_SAMPLE_S seconds while the lab runs."""
        pid = self.proc.pid
        with open(self.rss_log, "w") as log:
            while not self.sampler_stop.is_set() and Path("/proc/%d" % pid).exists():
                rss, anon = vm_rss(pid)
                if rss:
                    log.write("%.6f %s %s\n" % (time.time(), rss, anon))
                    log.flush()
                self.sampler_stop.wait(self.s.sample_s)

    def find_window(self):
        """The lab's window (it may take a while to appear: Vulkan start-up with validation)."""
        for _ in range(300):
            try:
                found = subprocess.run(["xdotool", "search", "--onlyvisible", "--pid", str(self.proc.pid)],
                                       capture_output=True, text=True, timeout=5).stdout.split()
            except subprocess.TimeoutExpired:
                found = []
            if found:
                self.wid = found[0]
                return
            if not self.alive():
                break
            time.sleep(0.1)
        raise self.fail("no window appeared: " + tail(self.stderr, 3))

    # ---- what the lab said last, and waiting for an answer
    def read_status(self):
        """Reads the status file: frame count, size drawn at, idle (the old values when unreadable)."""
        try:
            match = STATUS_LINE.search(self.status.read_text())
        except OSError:
            match = None
        if match:
            self.frame, self.width, self.height = int(match[1]), int(match[2]), int(match[3])
            self.idle = bool(match[4])

    def mark(self):
        """Remembers the frame count before an input."""
        self.read_status()
        self.before = self.frame

    def frame_after(self):
        """A frame was drawn after the input."""
        return self.frame > self.before

    def size_is(self):
        """A frame was drawn after the input, at the size asked for."""
        return (self.width, self.height) == self.want and self.frame > self.before

    def reload_seen(self):
        """A "reloaded" line on stdout or a "reload failed" line on stderr since the input."""
        return (count_lines(self.stdout, "reloaded ") > self.out_lines
                or count_lines(self.stderr, "reload failed") > self.err_lines)

    def is_iconic(self):
        """The window manager shows the window minimized."""
        try:
            state = subprocess.run(["xprop", "-id", self.wid, "WM_STATE"], capture_output=True, text=True, timeout=5)
        except subprocess.TimeoutExpired:
            return False
        return "Iconic" in state.stdout

    def answered(self, kind, condition, limit=None):
        """Waits until CONDITION holds (at most LIMIT, default SOAK_ANSWER_S, seconds); records the time it took."""
        limit = self.s.answer_s if limit is None else limit
        t0 = time.time()
        while True:
            self.read_status()
            if condition():
                break
            if not self.alive():
                raise self.fail("%s: %s" % (kind, self.died()))
            if elapsed(t0) > limit:
                failed = self.fail("%s: no answer within %g s (status: %s)" % (kind, limit, tail(self.status, 1)))
                self.backtrace()
                raise failed
            time.sleep(0.05)
        took = elapsed(t0)
        self.count[kind] = self.count.get(kind, 0) + 1
        self.worst[kind] = max(self.worst.get(kind, 0.0), took)

    def backtrace(self):
        """Where a hanging lab hangs, for the report (when gdb is installed)."""
        if not shutil.which("gdb"):
            return
        with open(self.work / "hang_backtrace.txt", "w") as out:
            try:
                subprocess.run(["gdb", "-batch", "-p", str(self.proc.pid), "-ex", "thread apply all bt"],
                               stdout=out, stderr=subprocess.STDOUT, timeout=60)
            except subprocess.TimeoutExpired:
                pass
        say(self.lab, "backtraces of the hanging lab in %s" % (self.work / "hang_backtrace.txt"))

    def rest_sample(self):
        """Resident memory at rest, with the scene variant loaded, after an input answered by a frame.

        Not after a reload: a new renderer's images take memory only when first written (lab 4's
        shadow maps, about 100 MB, at its first frame), and the every-SOAK_SAMPLE_S sampler also
        catches moments in the middle of a reload, when the old and the new renderer both exist.
        Its quarters' medians therefore move with how many of its samples fell just before or into
        a reload (lab 4: 320 or 420 MB). At rest means idle: the lab marks its status line " idle"
        once it has finished its frames and given freed memory back (malloc_trim,
        common/app/lab_app.cpp); the sample waits for that (at most 2 s; a sample that never saw it
        is still taken and counted in not_idle). Read straight after the frame instead, a sample
        caught up to ~40 MB of freed but not yet trimmed heap in lab 3 (peaks 193 MB against
        155 MB), and the quarters' medians moved by that, not by what is kept."""
        t0 = time.time()
        while True:
            self.read_status()
            if self.idle:
                break
            if elapsed(t0) > 2:
                self.not_idle += 1
                break
            time.sleep(0.02)
        rss, _ = vm_rss(self.proc.pid)
        if rss:
            with open(self.rss_rest, "a") as log:
                log.write("%.6f %s %s\n" % (time.time(), rss, self.loaded_scene))

    # ---- the inputs
    def activate(self):
        """Gives the window the focus (keys and the pointer go to it)."""
        xdo("windowactivate", "--sync", self.wid, quiet=True)

    def resize(self, width, height):
        """Resizes the window; answered by a frame at the new size."""
        self.want = (width, height)
        self.mark()
        xdo("windowsize", self.wid, width, height)
        self.answered("resize", self.size_is)

    def key_hold(self, key, seconds):
        """A key held down for SECONDS, as a user walks the camera; answered by a frame."""
        self.activate()
        self.mark()
        xdo("keydown", key)
        time.sleep(seconds)
        xdo("keyup", key)
        self.answered("key " + key, self.frame_after)

    def drag(self):
        """A left-button drag in the lower right of the window, away from the UI panels."""
        self.activate()
        x = self.width * (55 + self.random.randrange(30)) // 100
        y = self.height * (60 + self.random.randrange(30)) // 100
        self.mark()
        xdo("mousemove", "--window", self.wid, x, y, "mousedown", 1)
        for _ in range(6):
            xdo("mousemove_relative", "--", self.random.randrange(41) - 20, self.random.randrange(31) - 15)
            time.sleep(0.03)
        xdo("mouseup", 1)
        self.answered("drag", self.frame_after)

    def wheel(self):
        """A wheel step up or down over the scene."""
        self.activate()
        self.mark()
        xdo("mousemove", "--window", self.wid, self.width * 3 // 4, self.height * 3 // 4,
            "click", 4 + self.random.randrange(2))
        self.answered("wheel", self.frame_after)

    def minimize_restore(self):
        """Minimizes the window (answered when the window manager shows it iconic), then restores it."""
        xdo("windowminimize", self.wid)
        self.answered("minimize", self.is_iconic)
        time.sleep(0.5)
        if not self.alive():
            raise self.fail("minimized: " + self.died())
        self.mark()
        if not xdo("windowactivate", "--sync", self.wid, quiet=True):
            xdo("windowmap", self.wid)
        self.answered("restore", self.frame_after)

    def count_reloads(self):
        """Remembers how many reloads and rejections the lab has reported so far."""
        self.out_lines = count_lines(self.stdout, "reloaded ")
        self.err_lines = count_lines(self.stderr, "reload failed")

    def write_scene(self):
        """Alternately a good and a broken scene, written whole (rename) like an editor.

        A good scene must load and a broken one must be rejected (not just answered)."""
        if self.next_good:
            self.goods_i = (self.goods_i + 1) % len(self.goods)
            name, text = self.goods[self.goods_i]
        else:
            name, text = self.brokens[self.brokens_i]
            self.brokens_i = (self.brokens_i + 1) % len(self.brokens)
        good, self.next_good = self.next_good, not self.next_good
        self.count_reloads()
        temporary = self.scene.with_suffix(".json.tmp")
        temporary.write_bytes(text)
        temporary.replace(self.scene)
        self.answered("scene " + name, self.reload_seen)
        loaded = count_lines(self.stdout, "reloaded ") > self.out_lines
        if good and not loaded:
            rejected = [line for line in lines_of(self.stderr) if line.startswith("reload failed")]
            raise self.fail("good scene %s.json rejected: %s" % (name, rejected[-1] if rejected else ""))
        if not good and loaded:
            raise self.fail("broken scene %s.json was loaded" % name)
        if good:
            self.loaded_scene = name

    def reload_key(self):
        """The reload key (R); answered by "reloaded" or "reload failed"."""
        self.activate()
        self.count_reloads()
        xdo("key", "r")
        self.answered("key r (reload)", self.reload_seen)

    def step(self, action):
        """Sends one input of kind ACTION and waits for its answer."""
        pick = self.random.randrange
        if action == "resize":
            self.resize(*SIZES[pick(len(SIZES))])
            self.resize(*RESTORED_SIZE)
        elif action == "tiny":
            self.resize(1, 1)
            self.resize(*RESTORED_SIZE)
        elif action == "minimize":
            self.minimize_restore()
        elif action == "key":
            self.key_hold(CAMERA_KEYS[pick(len(CAMERA_KEYS))], (1 + pick(4)) / 10)
        elif action == "drag":
            self.drag()
        elif action == "wheel":
            self.wheel()
        elif action == "mode":
            self.key_hold("c", 0.05)
        elif action == "scene":
            self.write_scene()
        elif action == "reload":
            self.reload_key()
        elif action == "pause":
            time.sleep(0.5)  # nothing to answer (a lab that draws on demand may draw nothing)

    # ---- the soak
    def walk(self):
        """A fixed pseudo-random walk through the inputs until the time is up; returns the inputs sent."""
        steps = 0
        with open(self.work / "actions", "a") as log:
            while elapsed(self.started) < self.s.seconds:
                action = self.s.actions[self.random.randrange(len(self.s.actions))]
                log.write("%.2f %s\n" % (elapsed(self.started), action))
                log.flush()
                try:
                    self.step(action)
                except StepFailed:
                    break
                if not self.alive():
                    self.fail(self.died())
                    break
                validation = [line for line in lines_of(self.stderr) if "validation" in line.lower()]
                if validation:
                    self.fail("validation message: " + validation[0])
                    break
                steps += 1
                if action in FRAME_ACTIONS:
                    self.rest_sample()
        return steps

    def close(self):
        """Closes the window as a user does (Alt+F4 through the window manager); the lab must exit 0."""
        self.activate()
        xdo("key", "alt+F4")
        try:
            code = self.proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.fail("did not exit within 30 s of Alt+F4")
            return
        if code != 0:
            code = 128 - code if code < 0 else code  # a signal, as the shell reports it
            others = [line for line in lines_of(self.stderr) if not line.startswith("reload failed")]
            self.fail("exit code %d after closing: %s" % (code, "\n".join(others[-3:])))

    def check_stderr(self):
        """Anything on stderr but the expected "reload failed" lines (broken scenes) is a finding."""
        unexpected = "\n".join(line for line in lines_of(self.stderr)
                               if not line.startswith(EXPECTED_STDERR)).rstrip("\n")
        if not self.failure and unexpected:
            self.fail("unexpected stderr: " + "\n".join(unexpected.split("\n")[:3]))

    def check_memory(self):
        """The memory figures: gated on the samples at rest, reported on the every-SOAK_SAMPLE_S ones.

        The limit: SOAK_MEMORY_GATE percent (default 1, the issue's rule for the minutes after the
        first; 0 = report only, for looking at a run by hand). The one-minute CTest runs use 2: their
        40-s window moves with the scene variant loaded at its start and at its end (lab 3's resident
        memory steps between about 175 and 180 MB with it), so fixed labs measured -1.43 ... +0.53 %
        there (16 runs); a 1 % gate would fail now and then on nothing. 2 % still catches a leak of
        lab 3's old size (2.6-3 % in a minute); slower leaks show in the 10-minute run, which keeps 1 %."""
        rest = read_samples(self.rss_rest) if self.rss_rest.exists() else []
        growth = None
        try:
            figure = memory_figure(rest, self.started, self.s.warmup, self.s.min_samples, by_scene=True)
            figures, growth = figure.text, figure.printed_growth
        except TooFewSamples as reason:
            figures = str(reason)
            if not self.failure:
                self.fail("memory: " + figures)
        sampled = read_samples(self.rss_log) if self.rss_log.exists() else []
        try:
            every = memory_figure(sampled, self.started, self.s.warmup, 10).text
        except TooFewSamples as reason:
            every = str(reason)
        if self.s.gate == 0:
            say(self.lab, "memory growth %s %% reported, not gated (SOAK_MEMORY_GATE=0)"
                % ("?" if growth is None else "%.3f" % growth))
        elif not self.failure and growth is not None and growth >= self.s.gate:
            self.fail("resident memory grew by %.3f %% after the warm-up (limit %g %%)" % (growth, self.s.gate))
        return figures, every, per_minute_medians(sampled, self.started)

    def report(self, steps, figures, every, per_minute):
        """Prints the lab's figures."""
        answers = ", ".join("%s=%dx/max%.2fs" % (kind, n, self.worst[kind]) for kind, n in self.count.items())
        say(self.lab, "%.2f s, %d inputs, warm-up %d s; at rest (after the idle trim; %d samples did not see it "
            "within 2 s): %s" % (elapsed(self.started), steps, self.s.warmup, self.not_idle, figures))
        say(self.lab, "every %g s (reported, not gated): %s" % (self.s.sample_s, every))
        say(self.lab, "resident memory per minute (KiB, medians): " + per_minute)
        say(self.lab, "answers (count, slowest): " + answers)
        say(self.lab, "%d reloads, %d rejected scenes; last %s" % (
            count_lines(self.stdout, "reloaded "), count_lines(self.stderr, "reload failed"), tail(self.status, 1)))

    def run(self):
        """The whole soak of this lab; True when it passed."""
        try:
            self.start_x()
            self.prepare_scenes()
            self.start_lab()
            self.find_window()
            # The first frame: start-up (shader compilation, uploads, lab 4's shadow pipelines), not
            # an answer to an input, so it gets SOAK_START_S on a loaded machine.
            self.before = 0
            self.answered("start", self.frame_after, limit=self.s.start_s)
        except StepFailed:
            self.cleanup()
            say(self.lab, "FAILED (%s); files kept in %s" % (self.failure, self.work))
            return False
        steps = self.walk()
        if not self.failure:
            self.close()
        self.stop_sampler()
        self.check_stderr()
        figures, every, per_minute = self.check_memory()
        self.report(steps, figures, every, per_minute)
        self.cleanup()
        if self.failure:
            say(self.lab, "FAILED (%s); files kept in %s" % (self.failure, self.work))
            return False
        if self.s.keep:
            say(self.lab, "files kept in %s" % self.work)
        else:
            shutil.rmtree(self.work, ignore_errors=True)
        if not self.s.validate:
            say(self.lab, "checks passed WITHOUT validation (SOAK_NO_VALIDATE: a diagnosis run, not a pass)")
            return False
        say(self.lab, "PASS")
        return True


def soak_lab(lab, settings):
    """Soaks one lab; True when it passed. Whatever it started is stopped, however it ends."""
    exe = settings.build / lab / lab
    if not os.access(exe, os.X_OK):
        say(lab, "not built (%s)" % exe)
        return False
    soak = LabSoak(lab, settings)
    try:
        return soak.run()
    finally:
        soak.cleanup()


def main(argv):
    """Soaks the labs named (or every lab built); 0 when all passed, 1 otherwise, 2 for bad usage."""
    if argv[:1] in (["-h"], ["--help"]):
        print(__doc__.strip())
        return 0
    try:
        settings, labs = parse_settings(argv, os.environ)
    except UsageError as error:
        print("soak: error: %s" % error, file=sys.stderr)
        return 2
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(1))  # stopped: clean up (finally) and fail
    try:
        results = [soak_lab(lab, settings) for lab in labs]
    except KeyboardInterrupt:
        return 1
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
