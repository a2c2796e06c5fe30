"""The command line of bench/tradeoff.py: parse the options, measure (or --replot), write the
CSV, the plot and (full runs of labs 1 and 2) the heatmaps, print the defaults' figures and,
with --quick, run the checks (exit code 1 when one fails)."""
import argparse
import os
import shutil
import sys
import time

from . import device, knobs
from .check import check
from .heatmaps import heatmaps
from .measure import measure
from .plot import plot
from .results import from_row, mark_front, read_rows, write_csv, write_rows
from .scenes import ROOT


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


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description="frame time against error for a lab's knobs")
    ap.add_argument("lab", choices=sorted(knobs.KNOBS))
    ap.add_argument("--quick", action="store_true", help="a few configurations at 320x180, then check the CSV")
    ap.add_argument("--build", default=os.environ.get("LAB_BUILD_DIR", os.path.join(ROOT, "build")))
    ap.add_argument("--out-dir", help="default: docs/tradeoffs (quick: BUILD/tradeoff_quick)")
    ap.add_argument("--frames", type=int, help="benchmark frames per run (default: 61 lab 1, 21 lab 2; quick 3)")
    ap.add_argument("--rounds", type=int, help="interleaved rounds (default 3; quick 1)")
    ap.add_argument("--threads", type=int, default=2, help="LP_NUM_THREADS (default 2; lavapipe's threads, "
                                                                "recorded on a CPU device)")
    ap.add_argument("--no-heatmaps", action="store_true")
    ap.add_argument("--replot", action="store_true", help="only draw LAB.png again from LAB.csv")
    ap.add_argument("--exe", help="the lab binary (default: BUILD/LAB/LAB)")
    ap.add_argument("--only", help="only the configurations whose name matches this regular expression")
    ap.add_argument("--group", help="only this group's configurations (e.g. two groups in two processes, "
                                    "then --replot on the concatenated CSV)")
    args = ap.parse_args(argv)
    args.build = os.path.abspath(args.build)
    args.rounds_given = args.rounds is not None
    if args.frames is None:
        args.frames = knobs.frames(args.lab, args.quick)
    if args.rounds is None:
        args.rounds = 1 if args.quick else 3
    if args.out_dir is None:
        args.out_dir = (os.path.join(args.build, "tradeoff_quick") if args.quick
                        else os.path.join(ROOT, "docs", "tradeoffs"))
    return args


def title_note(lab, args):
    """The plot's second title line: how it was measured (the device is in the title)."""
    w, h = knobs.size(lab, args.quick)
    note = f"{w}x{h}, {args.rounds} interleaved rounds x {args.frames} frames; bars: round-to-round spread"
    if knobs.KNOBS[lab].get("time_args"):
        note += (f"; time: a frame that re-renders every shadow map ({' '.join(knobs.KNOBS[lab]['time_args'])}), "
                 f"error: the static picture")
    return note


def replot(lab, csv_path, png_path, note, quick):
    """Draws LAB.png again from LAB.csv, the configurations' roles from the knob table, and
    rewrites the CSV's front columns from the front recomputed with the lab's error figure
    (several CSVs may have been joined)."""
    known = {c["config"]: c for c in knobs.KNOBS[lab]["configs"](quick)}
    rows = read_rows(csv_path)
    mixed = [p for p in device.problems(rows) if p.startswith("several devices")]
    if mixed:  # one front per device: joined CSVs must come from one device
        print(f"tradeoff: {csv_path}: {mixed[0]} (each device has its own front: plot them apart)", file=sys.stderr)
        sys.exit(2)
    configs = [from_row(row, known) for row in rows]
    mark_front(configs, knobs.KNOBS[lab]["groups"], knobs.error_key(lab))
    changed = False
    for row, c in zip(rows, configs):
        changed |= (row["on_front"], row["dominated_by"]) != (c["on_front"], c["dominated_by"])
        row["on_front"], row["dominated_by"] = c["on_front"], c["dominated_by"]
    if changed:  # else the CSV stays byte for byte as measured
        write_rows(csv_path, rows)
    plot(lab, configs, png_path, note, configs[0]["device"] if configs else None)


def print_defaults(lab, configs):
    key = knobs.error_key(lab)
    for c in configs:
        if c["default"]:
            print(f"  default {c['group']} | {c['config']}: cpu {c['cpu_ms']:.2f} ms/frame (spread {c['cpu_spread_ms']:.2f}), "
                  f"wall median {c['median_ms']:.2f} ms (spread {c['spread_ms']:.2f}, best {c['best_ms']:.2f}), "
                  f"{key} {c['errors'][key]:.4f}, on front: {c['on_front'] or 'n/a'}"
                  + (f", dominated beyond noise by {c['dominated_by']}" if c["dominated_by"] else ""))


def main(argv=None):
    ensure_matplotlib()
    args = parse_args(argv)
    lab = args.lab
    os.makedirs(args.out_dir, exist_ok=True)
    csv_path = os.path.join(args.out_dir, lab + ".csv")
    png_path = os.path.join(args.out_dir, lab + ".png")
    if args.replot and not args.rounds_given:  # the note names the rounds the CSV was measured in
        rounds = {row["rounds"] for row in read_rows(csv_path)}
        if len(rounds) == 1:
            args.rounds = int(rounds.pop())
    note = title_note(lab, args)
    if args.replot:
        replot(lab, csv_path, png_path, note, args.quick)
        return
    wall = time.time()
    configs, runner = measure(lab, args)
    write_csv(lab, configs, csv_path, args.rounds, runner.device)
    plot(lab, configs, png_path, note, runner.device)
    if not args.quick and not args.no_heatmaps:
        heatmaps(lab, runner, args.out_dir)
    print(f"tradeoff: wrote {csv_path} and {lab}.png in {time.time() - wall:.0f} s on {device.label(runner.device)}")
    print_defaults(lab, configs)
    shutil.rmtree(runner.tmp, ignore_errors=True)
    if args.quick and not check(lab, csv_path, configs):
        sys.exit(1)
