"""The time-against-error plots (matplotlib, imported only when drawing).

One figure per lab, LAB.png: one panel per group. A group with a front gets CPU time against
error on log axes with its Pareto front (and, when it has single-primitive variants, a second
panel zoomed around its default where they are labelled); lab 3's sampler group labels every
point; lab 2's light count and lighting models get a cost curve and bars.

Readable where it is shown: the course site draws a plot about 900 px wide, so the panels go two
to a row (not all in one row), the figure is 14 in wide at 120 dpi (1680 px) and the smallest text
is 11 pt (about 10 px on the page). Only what the reader needs is written on the points: a group
with many series (lab 4's eight filters) names its knob once in a corner instead of at every point.
"""
import math
import statistics
import textwrap

from .device import title_parts
from .knobs import KNOBS, error_key, error_label

CPU_LABEL = "CPU time per frame (ms, all threads, log)"
WIDTH_IN, PANEL_HEIGHT_IN, DPI = 14.0, 6.0, 120
STYLE = {"font.size": 13, "axes.titlesize": 15, "axes.labelsize": 13, "xtick.labelsize": 12,
         "ytick.labelsize": 12, "legend.fontsize": 11, "figure.titlesize": 16}
SMALL = 11  # annotations: the smallest text in a plot
MANY_SERIES = 3  # more series than this: no knob value at every point


def panels(lab, configs):
    """(group, its configurations, kind) per panel, in the groups' order of appearance."""
    out = []
    for group in dict.fromkeys(c["group"] for c in configs):
        cs = [c for c in configs if c["group"] == group]
        style = KNOBS[lab]["groups"].get(group, {})
        if style.get("label_all"):
            out.append((group, cs, "labelled"))
        elif style.get("front"):
            out.append((group, cs, "front"))
            if any(not c["series"] for c in cs):
                out.append((group, cs, "zoom"))
        elif group == "light count":
            out.append((group, cs, "count"))
        else:
            out.append((group, cs, "bars"))
    return out


def plot(lab, configs, path, title_note, device):
    """LAB.png; the title names the device (device.py's dictionary: each device has its own front)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    todo = panels(lab, configs)
    columns = 1 if len(todo) == 1 else 2
    rows = math.ceil(len(todo) / columns)
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(rows, columns, figsize=(WIDTH_IN, PANEL_HEIGHT_IN * rows + 1.2), squeeze=False)
        for ax in axes.flat[len(todo):]:
            ax.set_visible(False)
        legend = draw_panels(lab, todo, axes.flat)
        height = PANEL_HEIGHT_IN * rows + 1.2
        on, machine = title_parts(device)
        note = textwrap.fill(f"{machine}; {title_note}" if machine else title_note, 120)
        fig.suptitle(f"{lab}: time against error on {on}", y=0.995)
        fig.text(0.5, 1 - 0.45 / height, note, ha="center", va="top", fontsize=SMALL, color="0.25")
        bottom = 0.0
        if legend:  # many series: one legend for the figure, under the panels, not over the points
            handles, labels = legend.get_legend_handles_labels()
            fig.legend(handles, labels, loc="lower center", ncol=5, frameon=False)
            bottom = (0.2 + 0.35 * math.ceil(len(labels) / 5)) / height
        fig.tight_layout(rect=(0, bottom, 1, 1 - (0.6 + 0.2 * note.count("\n")) / height))
        for ax in axes.flat:  # once the panels have their final size and limits
            spread_labels(ax)
        fig.savefig(path, dpi=DPI)
    plt.close(fig)


def draw_panels(lab, todo, axes):
    """Draws every panel; returns the axes whose legend the figure shows (groups with many
    series), or None when each panel has its own."""
    key = error_key(lab)
    figure_legend = None
    for ax, (group, cs, kind) in zip(axes, todo):
        if kind == "count":
            plot_count(ax, group, cs, key)
        elif kind == "bars":
            plot_bars(ax, group, cs, key)
        else:
            many = plot_front(ax, group, cs, kind, key, error_label(lab),
                              KNOBS[lab]["groups"].get(group, {}).get("knob", "knob"))
            if many and figure_legend is None:
                figure_legend = ax
        if kind == "labelled":
            ax.set_ylabel(f"mean |error| vs {KNOBS[lab].get('truth_name', 'ideal')} (1/255, log)")
        if kind in ("front", "zoom", "labelled"):
            plain_log_axes(ax)
    return figure_legend


def annotate(ax, text, xy, dx=6, dy=5, **kw):
    """A label next to a data point, on the side with room (left of a point in the right third
    of the panel), left out of the layout so that a long label never shrinks the panel."""
    x_axes = ax.transAxes.inverted().transform(ax.transData.transform(xy))[0]
    if x_axes > 0.66:
        dx, kw["ha"] = -abs(dx), "right"
    label = ax.annotate(text, xy, textcoords="offset points", xytext=(dx, dy), fontsize=kw.pop("fontsize", SMALL), **kw)
    label.set_in_layout(False)
    return label


def plain_log_axes(ax):
    """Plain numbers (20, 30, 0.5; not 2×10¹) on both log axes. Minor ticks are labelled only
    where an axis spans at most two decades, and then only 2, 3 and 5 where it spans more
    than half a decade: more labels would run into each other."""
    from matplotlib.ticker import FuncFormatter

    def plain(v, _pos=None):
        return f"{v:g}"

    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(FuncFormatter(plain))

        def minor(v, _pos=None, axis=axis):
            lo, hi = sorted(axis.get_view_interval())  # at drawing time: the final limits
            decades = math.log10(hi / lo) if lo > 0 else 99
            if decades > 2.0:
                return ""
            mantissa = round(v / 10 ** math.floor(math.log10(v) + 1e-9), 6)
            return plain(v) if decades <= 0.6 or mantissa in (2, 3, 5) else ""

        axis.set_minor_formatter(FuncFormatter(minor))
    ax.tick_params(which="minor", labelsize=SMALL)


def plot_front(ax, group, cs, kind, key, ylabel, knob="knob"):
    """CPU time against error: the series as lines, the rest as crosses, the front as a step,
    the default circled. kind: "front", "zoom" (around the default) or "labelled"."""
    markers = {"flat": "s", "gouraud": "^", "phong": "o", "all": "o"}
    for s in dict.fromkeys(c["series"] for c in cs):
        pts = [c for c in cs if c["series"] == s]
        if s:
            pts.sort(key=lambda c: c["knob"])
            ax.plot([c["cpu_ms"] for c in pts], [c["errors"][key] for c in pts], marker=markers.get(s, "o"),
                    linestyle="-", alpha=0.8, label=f"{s} (segments)" if s == "all" else s)
        else:
            label = "one primitive varied, others at default" if kind != "labelled" else "configuration"
            if all(c["seed"] for c in pts):
                label = "the seed's configuration"
            ax.scatter([c["cpu_ms"] for c in pts], [c["errors"][key] for c in pts], marker="x", color="0.3",
                       zorder=3, label=label)
    front = sorted([c for c in cs if c["on_front"] == "yes"], key=lambda c: c["cpu_ms"])
    ax.step([c["cpu_ms"] for c in front], [c["errors"][key] for c in front], where="post", color="black",
            linewidth=1.2, alpha=0.7, label="Pareto front")
    for c in cs:
        ax.errorbar(c["cpu_ms"], c["errors"][key], xerr=c["cpu_spread_ms"] / 2, fmt="none", ecolor="0.6",
                    elinewidth=0.8, capsize=2)
        if c["default"]:
            ax.scatter([c["cpu_ms"]], [c["errors"][key]], s=170, facecolors="none", edgecolors="red",
                       linewidths=1.6, zorder=4)
    series = [s for s in dict.fromkeys(c["series"] for c in cs) if s]
    if kind == "labelled":
        label_clusters(ax, cs, key)
    else:
        label_points(ax, cs, kind, key, len(series))
    if len(series) > MANY_SERIES and kind == "front":
        knobs = sorted({c["knob"] for c in cs if c["series"]})
        ax.text(0.02, 0.02, f"along each line: {knob} {knobs[0]} to {knobs[-1]}",
                transform=ax.transAxes, fontsize=SMALL, color="0.25")
    ax.set_xscale("log")
    ax.set_yscale("log")
    if kind == "zoom":
        zoom_on_default(ax, cs, key)
        ax.set_title(f"{group}: around the default")
    else:
        ax.set_title(group)
    ax.set_xlabel(CPU_LABEL)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    many = len(series) > MANY_SERIES
    if kind != "zoom" and not many:  # the zoomed panel has the same lines as the one before it
        ax.legend(loc="best")
    return many



def point_label(c):
    """A series' point by its knob, anything else by name; the default and the seeds named."""
    text = str(c["knob"]) if c["series"] else c["config"]
    if c["default"]:
        text = f"{c['config']} (default)"
    if c["seed"]:  # the seed's own configuration is named in the legend
        text = c["seed"] if text.startswith("seed") else f"{text} = {c['seed']}"
    return text


def label_points(ax, cs, kind, key, n_series):
    """Labels the points: those off the series only in the zoomed panel; a series' knob values
    at every point when it is the only one, at its two ends when there are a few, and not at all
    when there are many (the corner note names the knob); the default and the seeds always."""
    ends = {}
    for c in cs:
        if c["series"]:
            ends.setdefault(c["series"], []).append(c["knob"])
    for c in cs:
        special = c["default"] or c["seed"]
        if not c["series"] and kind == "front" and not special:
            continue  # labelled in the zoomed panel
        if c["series"] and not special and (n_series > MANY_SERIES or (
                n_series > 1 and c["knob"] not in (min(ends[c["series"]]), max(ends[c["series"]])))):
            continue
        annotate(ax, point_label(c), (c["cpu_ms"], c["errors"][key]),
                 fontweight="bold" if c["default"] else "normal", color="darkred" if special else "black")


def spread_labels(ax, tries=8):
    """Moves a label down, a line at a time, while it covers one placed before it (from the top)."""
    renderer = ax.figure.canvas.get_renderer()
    labels = sorted((t for t in ax.texts if hasattr(t, "xyann")), key=lambda t: -t.get_window_extent(renderer).y0)
    placed = []
    for label in labels:
        for _ in range(tries):
            box = label.get_window_extent(renderer)
            if not any(box.overlaps(other) for other in placed):
                break
            x, y = label.xyann
            label.xyann = (x, y - box.height * 72 / ax.figure.dpi - 1)
        placed.append(label.get_window_extent(renderer))


def zoom_on_default(ax, cs, key):
    """The axes' limits around the points off the series and the default."""
    near = [c for c in cs if not c["series"] or c["default"]]
    xs = [c["cpu_ms"] for c in near]
    ys = [c["errors"][key] for c in near]
    ax.set_xlim(min(xs) / 1.08, max(xs) * 1.15)
    ax.set_ylim(min(ys) / 1.3, max(ys) * 1.3)


def full_name(c):
    """The configuration's name, "(default)" and its seed added."""
    return c["config"] + (" (default)" if c["default"] else "") + (f" = {c['seed']}" if c["seed"] else "")


def label_clusters(ax, cs, key):
    """Labels every configuration; those with the same error (the same picture: lab 3's
    anisotropy 2 … 16 on lavapipe) and about the same cost share one label."""
    clusters = []
    for c in sorted(cs, key=lambda c: c["cpu_ms"]):
        for cl in clusters:
            if cl[0]["errors"][key] == c["errors"][key] and abs(cl[0]["cpu_ms"] - c["cpu_ms"]) < 0.2 * cl[0]["cpu_ms"]:
                cl.append(c)
                break
        else:
            clusters.append([c])
    for cl in clusters:
        cl.sort(key=lambda c: cs.index(c))
        special = any(c["default"] or c["seed"] for c in cl)
        x = statistics.median(c["cpu_ms"] for c in cl)
        ax.annotate("\n".join(full_name(c) for c in cl), (x, cl[0]["errors"][key]), textcoords="offset points",
                    xytext=(-8, 8), ha="right", fontsize=SMALL, color="darkred" if special else "black")


def plot_count(ax, group, cs, key):
    """Lab 2's light count: CPU time against the number of lights, with a line ∝ lights."""
    xs = [c["knob"] for c in cs]
    ax.errorbar(xs, [c["cpu_ms"] for c in cs], yerr=[c["cpu_spread_ms"] / 2 for c in cs], fmt="o-",
                color="tab:blue", capsize=3, label="measured")
    # Cost proportional to the number of lights, through the largest count: a straight line of slope 1.
    last = max(cs, key=lambda c: c["knob"])
    ax.plot(xs, [last["cpu_ms"] * x / last["knob"] for x in xs], ":", color="0.5", label="∝ lights")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.legend(loc="upper left")
    ax.set_xticks(xs)
    ax.set_xticklabels([str(x) for x in xs])
    ax.set_xlabel("lights (directional, point, spot in turn)")
    ax.set_ylabel(CPU_LABEL)
    for c in cs:
        ax.annotate(f"{c['cpu_ms']:.0f} ms", (c["knob"], c["cpu_ms"]),
                    textcoords="offset points", xytext=(-12, 8), ha="right", fontsize=SMALL, color="0.25")
    ax.set_title(f"{group}: cost per frame")
    ax.grid(True, alpha=0.3)


def plot_bars(ax, group, cs, key):
    """Lab 2's lighting models: one bar of CPU time each, the default in red."""
    ys = list(range(len(cs)))
    ax.barh(ys, [c["cpu_ms"] for c in cs], xerr=[c["cpu_spread_ms"] / 2 for c in cs],
            color=["tab:red" if c["default"] else "tab:blue" for c in cs], alpha=0.75, capsize=2)
    ax.set_yticks(ys)
    ax.set_yticklabels([full_name(c) for c in cs])
    ax.invert_yaxis()
    for y, c in zip(ys, cs):
        ax.annotate(f" {c['cpu_ms']:.1f} ms, err {c['errors'][key]:.2f}", (c["cpu_ms"] + c["cpu_spread_ms"] / 2, y),
                    va="center", fontsize=SMALL)
    ax.set_xlabel("CPU time per frame (ms, all threads)")
    ax.set_title(f"{group} (equal scene;\nerror vs each model's own ideal)")
    ax.grid(True, axis="x", alpha=0.3)
    ax.set_xlim(0, max(c["cpu_ms"] for c in cs) * 1.6)
