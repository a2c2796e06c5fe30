"""The quick run's checks (--quick, CTest tradeoff_quick_*): data, never timing.

The CSV must be well-formed (the header, one row per configuration, finite non-negative
numbers, a frame time, a default, one device named on every row); along every tessellation series the error must grow when
the tessellation drops; and the knob table's `order` pairs (lab 3: trilinear below nearest)
must hold.
"""
import math

from . import device
from .knobs import KNOBS
from .results import CSV_FIELDS, ERROR_KEYS, read_rows

NUMBER_KEYS = ["cpu_ms", "cpu_spread_ms", "median_ms", "p95_ms", "spread_ms", "best_ms"] + ERROR_KEYS


def csv_problems(rows, n_configs):
    """What is wrong with the CSV rows of a run of n_configs configurations."""
    problems = []
    if rows and list(rows[0].keys()) != CSV_FIELDS:
        problems.append(f"header {list(rows[0].keys())} != {CSV_FIELDS}")
    if len(rows) != n_configs:
        problems.append(f"{len(rows)} rows for {n_configs} configurations")
    for row in rows:
        for k in NUMBER_KEYS:
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
    return problems + device.problems(rows)


def series_problems(configs):
    """Along every series (ordered by knob, finer = larger) the mean |error| must strictly grow
    as the tessellation drops."""
    problems = []
    for series in sorted({c["series"] for c in configs if c["series"]}):
        pts = sorted([c for c in configs if c["series"] == series], key=lambda c: c["knob"])
        for finer, coarser in zip(pts[1:], pts[:-1]):
            if not coarser["errors"]["mean_abs"] > finer["errors"]["mean_abs"]:
                problems.append(f"series {series}: error at {coarser['knob']} ({coarser['errors']['mean_abs']}) "
                                f"not above error at {finer['knob']} ({finer['errors']['mean_abs']})")
    return problems


def order_problems(configs, pairs):
    """Every (better, worse) pair of configuration names, both measured: better's mean |error|
    must be below worse's."""
    problems = []
    by_name = {c["config"]: c for c in configs}
    for better, worse in pairs:
        if better in by_name and worse in by_name and \
                not by_name[better]["errors"]["mean_abs"] < by_name[worse]["errors"]["mean_abs"]:
            problems.append(f"error of {better} ({by_name[better]['errors']['mean_abs']}) not below error of "
                            f"{worse} ({by_name[worse]['errors']['mean_abs']})")
    return problems


def check(lab, csv_path, configs):
    """Prints every problem of the quick run (CSV at csv_path, measured configs); true if none."""
    problems = (csv_problems(read_rows(csv_path), len(configs)) + series_problems(configs)
                + order_problems(configs, KNOBS[lab].get("order", [])))
    for p in problems:
        print(f"tradeoff check: {p}")
    return not problems
