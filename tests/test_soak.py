#!/usr/bin/env python3
"""test_soak.py — the window soak's memory figure (bench/soak_memory.py) on made-up samples whose
right answer is known: it must pass memory that only moves with the scene loaded, and it must
catch a leak that the 1 % gate is there to catch. Also: bench/soak.py's bad usage exits 2 with
one line. CTest runs it as soak_memory_figure (label common); no X server or lab needed.

    python3 tests/test_soak.py
"""
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree for the import below
from soak_memory import TooFewSamples, memory_figure  # noqa: E402

failures = 0


def check(name, got, op, limit):
    """Prints ok/FAIL for GOT against LIMIT; OP: '>' above, '~' equal (within 0.001), '+-' within ±LIMIT."""
    global failures
    passed = {">": got > limit, "~": abs(got - limit) < 0.001, "+-": -limit < got < limit}[op]
    print("%s %s: %.3f %% (%s%s %g)"
          % ("ok  " if passed else "FAIL", name, got, "" if passed else "expected ", op, limit))
    failures += not passed


class GlibcRandom:
    """glibc's random() after srandom(seed) (the TYPE_3 additive generator): what Debian's mawk's
    rand() draws from (rand() = random() / RAND_MAX), so these samples are the ones the awk version
    of this test made, value for value."""

    def __init__(self, seed):
        r = [seed or 1]
        for _ in range(1, 31):
            r.append(16807 * r[-1] % 2147483647)
        r += r[:3]  # r[31..33] = r[0..2]
        for i in range(34, 344):
            r.append((r[i - 31] + r[i - 3]) & 0xFFFFFFFF)
        self.r = r

    def rand(self):
        """The next random() / RAND_MAX, in [0, 1]."""
        r = self.r
        r.append((r[-31] + r[-3]) & 0xFFFFFFFF)
        return (r[-1] >> 1) / 2147483647


def make_samples(leak_kib_s, leak_pct):
    """A 10-minute soak in miniature: a sample at rest every 2 s, the scene variant changed every 20 s
    through a cycle of three (levels 288 000, 173 000 and 222 000 KiB), and each time a variant is
    loaded it sits a few MB above its level depending on the history (0, 4, 10 or 15 MB, a fixed
    pseudo-random order) — what lab 4's samples look like. LEAK_KIB_S: a leak in KiB per second
    (0: none); LEAK_PCT: a proportional leak in % over the run (0: none)."""
    level = (288000, 173000, 222000)
    name = ("lab4", "shadows_off", "light_removed")
    step = (0, 4000, 10000, 15000, 4000, 0, 15000, 10000, 0, 0, 4000, 15000, 10000, 4000, 0)
    rng = GlibcRandom(7)
    samples = []
    for t in range(0, 600, 2):
        episode = t // 20
        v = episode % 3
        rss = level[v] + step[(episode * 7) % 15] + int(rng.rand() * 600)
        rss += leak_kib_s * t + rss * leak_pct / 100 * t / 600
        samples.append((float(1000 + t), float(int(rss)), name[v]))
    return samples


def growth(samples, by_scene=True):
    """The figure the soak gates on, for samples starting at t = 1000 with a 60-s warm-up."""
    return memory_figure(samples, 1000, 60, 10, by_scene).growth_pct


def test_memory_figure():
    """The figure on samples with a known answer."""
    # (The most-seen variant alone reads -1.55 % on these samples: which steps fell in its quarters.)
    check("history steps, no leak", growth(make_samples(0, 0)), "+-", 1)
    # A leak of 8 KiB a second (4.8 MB in 10 minutes): the centres of the first and the last quarter
    # of the 540 s measured are 405 s apart, 3.2 MB, which is 1.1 % of the heaviest variant and 1.9 %
    # of the lightest — it must read above 1 %.
    check("leak of 8 KiB/s", growth(make_samples(8, 0)), ">", 1)
    # +2 % of every variant over the run: the quarters' centres see 2 % x 405 / 600 = 1.35 % of it.
    check("leak of 2 % over the run", growth(make_samples(0, 2)), ">", 1.1)

    # By hand: one variant, 100 000 KiB in the first quarter of the measured time, 102 000 in the last.
    by_hand = [(1000.0 + t, float(500000 if t < 60 else 100000 if t < 85 else 101000 if t < 135 else 102000), "x")
               for t in range(0, 161, 2)]
    check("by hand, +2 % (warm-up ignored)", growth(by_hand), "~", 2)
    check("by hand, without scenes", growth(by_hand, by_scene=False), "~", 2)

    # Too few samples after the warm-up: no figure, and the reason.
    global failures
    try:
        figure = memory_figure(by_hand[:35], 1000, 60, 10, True)
        print("FAIL too few samples: a figure (%s)" % figure.text)
        failures += 1
    except TooFewSamples as reason:
        passed = str(reason) == "too few samples after the warm-up (5, at least 10)"
        print("%s too few samples: %s" % ("ok  " if passed else "FAIL", reason))
        failures += not passed


def test_bad_usage():
    """bench/soak.py with a bad MINUTES or setting: exit 2 and one line on stderr, before starting anything."""
    global failures
    cases = ((["ten"], {}, "soak: error: MINUTES must be a number, got 'ten'"),
             (["-1"], {}, "soak: error: MINUTES must be a number, got '-1'"),
             (["1"], {"SOAK_MEMORY_GATE": "1%"}, "soak: error: SOAK_MEMORY_GATE must be a percentage, got '1%'"),
             (["1"], {"SOAK_ACTIONS": "jump"}, "soak: error: SOAK_ACTIONS='jump' names none of: "))
    for args, env, expected in cases:
        run = subprocess.run([sys.executable, str(ROOT / "bench" / "soak.py"), *args], capture_output=True, text=True,
                             env={**os.environ, **env}, timeout=60)
        lines = run.stderr.splitlines()
        passed = run.returncode == 2 and len(lines) == 1 and lines[0].startswith(expected) and not run.stdout
        print("%s bad usage %s %s: exit %d, %s" % ("ok  " if passed else "FAIL", " ".join(args),
                                                 " ".join("%s=%s" % kv for kv in env.items()), run.returncode,
                                                 run.stderr.strip() or "(no message)"))
        failures += not passed


if __name__ == "__main__":
    if sys.argv[1:2] in (["-h"], ["--help"]):
        print(__doc__.strip())
        sys.exit(0)
    test_memory_figure()
    test_bad_usage()
    print("test_soak: all passed" if failures == 0 else "test_soak: %d failed" % failures)
    sys.exit(1 if failures else 0)
