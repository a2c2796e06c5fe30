#!/usr/bin/env python3
"""tradeoff.py — frame time against error for one lab's knobs (docs/tradeoffs.md).

    python3 bench/tradeoff.py LAB [--quick] [--build DIR] [--out-dir DIR] [--frames N] [--rounds R]
    python3 bench/tradeoff.py LAB --replot    # draw LAB.png again from the committed LAB.csv
    python3 bench/tradeoff.py --help          # every option

For every configuration in the lab's knob table (bench/tradeoff_lib/knobs.py) the script writes
a scene file, runs the lab headless with --benchmark (LP_NUM_THREADS fixed; the same process
writes its last frame to a PNG) and compares that PNG with the ideal reference
(`lab_reference --ideal`: exact curved surfaces, per-pixel exact normals; lab 3: the
supersampled texture, `lab_reference --supersample 16`; lab 4: the ray-traced shadows with the
shadow error metric, `lab_compare --shadow`) using `lab_compare`, in interleaved rounds.

Writes OUT_DIR/LAB.csv and OUT_DIR/LAB.png (CPU time per frame against error, the Pareto front
drawn, the default and the seeds' configurations labelled), and in a full run the README
heatmaps. --quick: a handful of configurations at 320×180 with validation on, written to
BUILD/tradeoff_quick/, then checks that the CSV is well-formed and that the error grows when
the tessellation drops (lab 3: that trilinear filtering beats nearest) (exit code 1
otherwise). CTest runs it.

This file is the entry point only; the code is the package bench/tradeoff_lib/ (its
__init__.py lists the modules). Unit tests: tests/test_tradeoff.py.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from tradeoff_lib.cli import main  # noqa: E402

if __name__ == "__main__":
    main()
