"""Results: the Pareto front of each group and the CSV (docs/tradeoffs.md, "CSV columns").

A measured configuration is the knob table's dictionary (knobs.config) with, added by
measure.py: `errors` (lab_compare's figures as numbers), the per-round lists `times`, `p95s`,
`cpu` and their summary `median_ms`, `p95_ms`, `spread_ms`, `best_ms`, `cpu_ms`,
`cpu_spread_ms`; mark_front() adds `on_front` and `dominated_by`.
"""
import csv

from . import device as devices
from .knobs import config

ERROR_KEYS = ["mean_abs", "p99_abs", "max_abs", "over_2", "mean_de2000", "p99_de2000"]
# The lab 4 shadow metric's figures (lab_compare --shadow), in every CSV (empty for other labs).
SHADOW_KEYS = ["wrong_side_pct", "shadow_mae"]
CSV_FIELDS = (["lab", "group", "config", "knob", "default", "seed", "cpu_ms", "cpu_spread_ms", "median_ms", "p95_ms",
               "spread_ms", "best_ms", "rounds", "round_ms"]
              + ERROR_KEYS + SHADOW_KEYS + ["on_front", "dominated_by"] + devices.DEVICE_KEYS)
TIME_KEYS = ["median_ms", "p95_ms", "spread_ms", "best_ms", "cpu_ms", "cpu_spread_ms"]


def mark_front(configs, groups, key="mean_abs"):
    """Pareto front per group: no other configuration both cheaper and more accurate (lower
    error `key`). Cheaper = less CPU time per frame (`cpu_ms`; on a shared machine the
    wall-clock frame time mostly measures the other users). `dominated_by` lists those cheaper
    by more than the noise (the larger of the two round-to-round CPU spreads) as well: the
    verdict that survives a re-run. Groups without "front" get empty columns."""
    for c in configs:
        c["on_front"], c["dominated_by"] = "", ""
        if not groups.get(c["group"], {}).get("front"):
            continue
        peers = [o for o in configs if o["group"] == c["group"] and o is not c]
        e = c["errors"][key]
        strict = [o for o in peers if o["cpu_ms"] < c["cpu_ms"] and o["errors"][key] < e]
        robust = [o for o in strict if o["cpu_ms"] + max(o["cpu_spread_ms"], c["cpu_spread_ms"]) < c["cpu_ms"]]
        c["on_front"] = "yes" if not strict else "no"
        c["dominated_by"] = ";".join(o["config"] for o in robust)


def csv_row(lab, c, rounds, device=None):
    """The CSV row of a measured configuration (times to 3 decimals, errors to 4, a missing
    error figure empty) on `device` (device.py's dictionary; None: the device columns empty)."""
    row = {"lab": lab, "group": c["group"], "config": c["config"], "knob": c["knob"],
           "default": "yes" if c["default"] else "", "seed": c["seed"],
           "median_ms": f"{c['median_ms']:.3f}", "p95_ms": f"{c['p95_ms']:.3f}",
           "spread_ms": f"{c['spread_ms']:.3f}", "best_ms": f"{c['best_ms']:.3f}",
           "cpu_ms": f"{c['cpu_ms']:.3f}", "cpu_spread_ms": f"{c['cpu_spread_ms']:.3f}", "rounds": rounds,
           "round_ms": ";".join(f"{t:.2f}" for t in c["times"]),
           "on_front": c["on_front"], "dominated_by": c["dominated_by"]}
    row.update({k: f"{c['errors'][k]:.4f}" if k in c["errors"] else "" for k in ERROR_KEYS + SHADOW_KEYS})
    row.update(devices.of_row(device or {}))
    return row


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def write_rows(path, rows):
    with open(path, "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=CSV_FIELDS)
        wr.writeheader()
        wr.writerows(rows)


def write_csv(lab, configs, path, rounds, device):
    write_rows(path, [csv_row(lab, c, rounds, device) for c in configs])


def from_row(row, known):
    """A configuration measured before, from its CSV row: its roles (default, seed, series, ...)
    from `known` (the knob table's configurations by name), its figures from the row."""
    c = dict(known.get(row["config"], config(row["config"], row["group"], {})))
    c["group"] = row["group"]
    for k in TIME_KEYS:
        c[k] = float(row[k])
    c["errors"] = {k: float(row[k]) for k in ERROR_KEYS + SHADOW_KEYS if row.get(k)}
    c["on_front"], c["dominated_by"] = row["on_front"], row["dominated_by"]
    c["rounds"] = row["rounds"]
    c["device"] = devices.of_row(row)  # all "" in a CSV from before the device was recorded
    return c
