"""soak_memory.py — how much a soaked lab's resident memory grew after the warm-up.

Used by bench/soak.py; tested on its own by tests/test_soak.py (CTest soak_memory_figure).

    memory_figure(samples, t0, warm, min_samples, by_scene)  ->  MemoryFigure(growth_pct, text)

SAMPLES: one (TIME, RSS_KIB, SCENE) per sample, TIME in seconds (time.time()); read_samples()
reads them from a file of "TIME RSS_KIB [SCENE]" lines. Samples before t0 + warm (the warm-up)
only count for rss_start_kib and rss_peak_kib.

Like is compared with like. Resident memory depends on the scene variant loaded (lab 4 with every
shadow switched off is about 115 MB lighter than with its own scene) and, in steps of a few MB, on
what was loaded before it (lab 4's scene sits at 288 MB after the shadowless variant, 292-303 MB
after the translucent one): a figure from one variant's samples moves with which of those steps
fell at the start and at the end. So with by_scene every sample is divided by the median of its
own variant's samples (its usual level), and the figure uses all of them:

    growth_pct = 100 * (median of the ratios in the last quarter of the time after the warm-up
                        / median of the ratios in the first quarter  - 1)

A leak adds to every variant and shows in every ratio; a variant loaded more often at one end
than at the other does not. Each quarter takes at least 5 samples (the first or last 5 when its
time holds fewer). Without by_scene all samples are one variant: the same as comparing medians.
For the record the text also gives the most-seen variant alone, in KiB (the older figure).
TooFewSamples (with the reason as its message) when fewer than min_samples follow the warm-up.

The arithmetic is that of the former bench/soak_memory.awk, step for step (doubles, medians of
sorted copies, printf-style truncation and rounding), so the same samples give the same text.
"""
from dataclasses import dataclass

# The fewest samples a quarter of the measured time takes.
QUARTER_MIN = 5


class TooFewSamples(Exception):
    """Fewer samples after the warm-up than a figure needs (the message says how many)."""


@dataclass
class MemoryFigure:
    """The growth figure and the line the soak prints for it."""
    growth_pct: float
    text: str

    @property
    def printed_growth(self):
        """The growth as printed (three decimals): what the soak's gate compares."""
        return float("%.3f" % self.growth_pct)


def median(values):
    """The median of VALUES (the mean of the middle two for an even count)."""
    b = sorted(values)
    n = len(b)
    return b[(n - 1) // 2] if n % 2 else (b[n // 2 - 1] + b[n // 2]) / 2


def read_samples(path):
    """The samples of a file of "TIME RSS_KIB [SCENE]" lines, as (time, rss, scene) tuples."""
    samples = []
    with open(path) as f:
        for line in f:
            fields = line.split()
            if len(fields) >= 2:
                samples.append((float(fields[0]), float(fields[1]), fields[2] if len(fields) > 2 else ""))
    return samples


def _quarters(times, ratios):
    """The ratios of the first and of the last quarter of the time, at least QUARTER_MIN each."""
    n = len(times)
    quarter = (times[-1] - times[0]) / 4
    k = min(n, QUARTER_MIN)
    first, last = [], []
    for i in range(n):
        if times[i] < times[0] + quarter or len(first) < k:
            first.append(ratios[i])
    for i in reversed(range(n)):
        if times[i] > times[-1] - quarter or len(last) < k:
            last.append(ratios[i])
    return first, last


def _most_seen_alone(by_variant):
    """The most-seen variant's own figure (first against last quarter of its samples), for the record."""
    best = None
    for name, values in by_variant.items():  # a tie goes to the variant seen first after the warm-up
        if best is None or len(values) > len(by_variant[best]):
            best = name
    values = by_variant[best]
    m = len(values)
    q = min(max(m // 4, QUARTER_MIN), m)
    base, last = median(values[:q]), median(values[m - q:])
    return " variants=%d; most seen alone: scene=%s (%d samples) %d -> %d KiB, %+.3f %%" % (
        len(by_variant), best, m, base, last, 100 * (last - base) / base)


def memory_figure(samples, t0, warm, min_samples, by_scene=False):
    """The growth of resident memory after the warm-up (module docstring), as a MemoryFigure."""
    first = low = None
    peak = 0.0
    n_all = 0
    times, rss, scenes = [], [], []
    for time, kib, scene in samples:
        t = time - t0
        if t < 0:
            continue
        n_all += 1
        if n_all == 1:
            first = kib
        peak = max(peak, kib)
        if t < warm:
            continue
        times.append(t)
        rss.append(kib)
        scenes.append(scene if by_scene else "-")
        low = kib if low is None else min(low, kib)
    n = len(times)
    if n < min_samples or n == 0:
        raise TooFewSamples("too few samples after the warm-up (%d, at least %d)" % (n, min_samples))
    # Each variant's usual level, and every sample as a ratio to it.
    by_variant = {}
    for kib, scene in zip(rss, scenes):
        by_variant.setdefault(scene, []).append(kib)
    level = {scene: median(values) for scene, values in by_variant.items()}
    ratios = [kib / level[scene] for kib, scene in zip(rss, scenes)]
    first_quarter, last_quarter = _quarters(times, ratios)
    growth = 100 * (median(last_quarter) / median(first_quarter) - 1)
    text = "rss_start_kib=%d rss_min_kib=%d rss_peak_kib=%d growth_pct=%.3f samples=%d quarters=%d/%d" % (
        first, low, peak, growth, n_all, len(first_quarter), len(last_quarter))
    if by_scene:
        text += _most_seen_alone(by_variant)
    else:
        text += " rss_after_warmup_kib=%d rss_end_kib=%d" % (
            median(first_quarter) * level["-"], median(last_quarter) * level["-"])
    return MemoryFigure(growth, text)


def per_minute_medians(samples, t0):
    """Resident memory minute by minute since t0: each minute's (lower) median in KiB, space-separated."""
    minutes = {}
    for time, kib, _ in samples:
        t = time - t0
        if t >= 0:
            minutes.setdefault(int(t / 60), []).append(kib)
    return "".join("%s%d" % (" " if minute else "", sorted(values)[(len(values) + 1) // 2 - 1])
                   for minute, values in sorted(minutes.items()))


if __name__ == "__main__":
    import sys
    # A module, not a command: --help shows what it computes; bench/soak.py is what runs it.
    if sys.argv[1:2] in (["-h"], ["--help"]):
        print(__doc__.strip())
        sys.exit(0)
    print("soak_memory: a module of bench/soak.py, not a command (see --help)", file=sys.stderr)
    sys.exit(2)
