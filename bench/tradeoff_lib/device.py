"""The device a sweep measured: each device has its own front (a CPU rasterizer such as lavapipe
and a GPU favour different settings), so the CSV and the plot say which one made the figures.

The lab's `benchmark` line names it (`device=NAME device_type=TYPE`, the name's spaces printed
as `_`: common/dev/benchmark.h). On a CPU device the CPU and its thread count are the machine
too: LP_NUM_THREADS (lavapipe's rasterizer threads) and the CPU's model from /proc/cpuinfo.
A CSV written before the device was recorded has none of these columns: "not recorded".
"""
DEVICE_KEYS = ["device", "device_type", "lp_num_threads", "cpu_model"]
DEVICE_TYPES = ["cpu", "integrated", "discrete", "virtual", "other"]


def cpu_model(cpuinfo_text):
    """The first `model name` of /proc/cpuinfo's text ("" when it has none: not x86)."""
    for line in cpuinfo_text.splitlines():
        key, _, value = line.partition(":")
        if key.strip() == "model name":
            return " ".join(value.split())
    return ""


def read_cpu_model(path="/proc/cpuinfo"):
    try:
        with open(path) as f:
            return cpu_model(f.read())
    except OSError:
        return ""


def of_benchmark(fields, env, cpuinfo_model):
    """The device of one run: its benchmark line's fields (strings), the environment it ran in
    and the CPU's model. Exits when the line names no device (a lab built before it did)."""
    import sys
    if "device" not in fields or "device_type" not in fields:
        sys.exit("tradeoff: the lab's benchmark line names no device (device=… device_type=…): rebuild the lab")
    # The lab printed the name's spaces as `_` (a name's own `_` reads as a space too).
    d = {"device": fields["device"].replace("_", " "), "device_type": fields["device_type"],
         "lp_num_threads": "", "cpu_model": ""}
    if d["device_type"] == "cpu":
        d["lp_num_threads"] = env.get("LP_NUM_THREADS", "unset")
        d["cpu_model"] = cpuinfo_model or "unknown"
    return d


def of_row(row):
    """The device of a CSV row; "" for a column the CSV lacks (written before it was recorded)."""
    return {k: row.get(k) or "" for k in DEVICE_KEYS}


def label(d):
    """One line for a title: "NAME (TYPE; CPU, LP_NUM_THREADS=N)", or "device not recorded"."""
    if not d or not d.get("device"):
        return "device not recorded"
    text = f"{d['device']} ({d['device_type'] or 'type not recorded'}"
    if d.get("cpu_model") or d.get("lp_num_threads"):
        text += f"; {d['cpu_model']}, LP_NUM_THREADS={d['lp_num_threads']}"
    return text + ")"


def title_parts(d):
    """A plot's (title, note) halves of the label: "NAME (TYPE)" for the title, and on a CPU
    device "CPU model, LP_NUM_THREADS=N" for the note under it ("" otherwise)."""
    if not d or not d.get("device"):
        return "device not recorded", ""
    machine = f"{d['cpu_model']}, LP_NUM_THREADS={d['lp_num_threads']}" if d.get("cpu_model") or d.get("lp_num_threads") else ""
    return f"{d['device']} ({d['device_type'] or 'type not recorded'})", machine


def problems(rows):
    """What is wrong with the CSV rows' device: each row names a device and a known type, a CPU
    device its threads and model, and every row the same device (one device, one front)."""
    out = []
    for row in rows:
        d = of_row(row)
        if not d["device"]:
            out.append(f"{row.get('config')}: no device")
        if d["device_type"] not in DEVICE_TYPES:
            out.append(f"{row.get('config')}: device_type {d['device_type']!r} is not one of {DEVICE_TYPES}")
        if d["device_type"] == "cpu" and not (d["lp_num_threads"] and d["cpu_model"]):
            out.append(f"{row.get('config')}: a CPU device without LP_NUM_THREADS or CPU model")
    labels = sorted({label(of_row(row)) for row in rows})
    if len(labels) > 1:
        out.append(f"several devices in one CSV: {'; '.join(labels)}")
    return out
