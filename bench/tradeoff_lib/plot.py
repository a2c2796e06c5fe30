"""The time-against-error plots (matplotlib, imported only when drawing).

One figure per lab, LAB.png: one panel per group. A group with a front gets CPU time against
error on log axes with its Pareto front (and, when it has single-primitive variants, a second
panel zoomed around its default where they are labelled); lab 3's sampler group labels every
point; lab 2's light count and lighting models get a cost curve and bars.
"""
import statistics

from .knobs import KNOBS, error_key, error_label

CPU_LABEL = "CPU time per frame (ms, all threads, log)"


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


def plot(lab, configs, path, title_note):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    todo = panels(lab, configs)
    ratios = [1.5 if kind in ("front", "zoom") else 2.0 if kind == "labelled" else 1.0 for _, _, kind in todo]
    fig, axes = plt.subplots(1, len(todo), figsize=(5.6 * sum(ratios), 5.6), squeeze=False,
                             gridspec_kw={"width_ratios": ratios})
    key = error_key(lab)
    for ax, (group, cs, kind) in zip(axes[0], todo):
        if kind == "count":
            plot_count(ax, group, cs, key)
        elif kind == "bars":
            plot_bars(ax, group, cs, key)
        else:
            plot_front(ax, group, cs, kind, key, error_label(lab))
        if kind == "labelled":
            plain_log_axes(ax)
            ax.set_ylabel(f"mean |error| vs {KNOBS[lab].get('truth_name', 'ideal')} (1/255, log)")
    fig.suptitle(f"{lab}: time against error\n{title_note}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def plain_log_axes(ax):
    """Plain numbers (not powers of ten) on both log axes, minor ticks labelled too."""
    from matplotlib.ticker import ScalarFormatter
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(ScalarFormatter())
        axis.set_minor_formatter(ScalarFormatter())
    ax.tick_params(which="minor", labelsize=7)


def plot_front(ax, group, cs, kind, key, ylabel):
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
    if kind == "labelled":
        label_clusters(ax, cs, key)
    else:
        label_points(ax, cs, kind, key)
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
    ax.legend(fontsize=7, loc="upper right")


def point_label(c):
    """A series' point by its knob, anything else by name; the default and the seeds named."""
    text = str(c["knob"]) if c["series"] else c["config"]
    if c["default"]:
        text = f"{c['config']} (default)"
    if c["seed"]:
        text += f" = {c['seed']}"
    return text


def label_points(ax, cs, kind, key):
    """Labels the points (those off the series only in the zoomed panel)."""
    for c in cs:
        if not c["series"] and kind == "front":
            continue  # labelled in the zoomed panel
        special = c["default"] or c["seed"]
        ax.annotate(point_label(c), (c["cpu_ms"], c["errors"][key]), textcoords="offset points", xytext=(5, 4),
                    fontsize=8 if special else 7, fontweight="bold" if c["default"] else "normal",
                    color="darkred" if special else "black")


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
                    xytext=(-8, 8), ha="right", fontsize=8, color="darkred" if special else "black")


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
    ax.legend(fontsize=7, loc="upper left")
    ax.set_xticks(xs)
    ax.set_xticklabels([str(x) for x in xs])
    ax.set_xlabel("lights (directional, point, spot in turn)")
    ax.set_ylabel(CPU_LABEL)
    for c in cs:
        ax.annotate(f"{c['cpu_ms']:.0f} ms\nerr {c['errors'][key]:.2f}", (c["knob"], c["cpu_ms"]),
                    textcoords="offset points", xytext=(-10, 8), fontsize=7, color="0.25")
    ax.set_title(f"{group}\n(error vs each count's own ideal)")
    ax.grid(True, alpha=0.3)


def plot_bars(ax, group, cs, key):
    """Lab 2's lighting models: one bar of CPU time each, the default in red."""
    ys = list(range(len(cs)))
    ax.barh(ys, [c["cpu_ms"] for c in cs], xerr=[c["cpu_spread_ms"] / 2 for c in cs],
            color=["tab:red" if c["default"] else "tab:blue" for c in cs], alpha=0.75, capsize=2)
    ax.set_yticks(ys)
    ax.set_yticklabels([full_name(c) for c in cs], fontsize=8)
    ax.invert_yaxis()
    for y, c in zip(ys, cs):
        ax.annotate(f" {c['cpu_ms']:.1f} ms, err {c['errors'][key]:.2f}", (c["cpu_ms"] + c["cpu_spread_ms"] / 2, y),
                    va="center", fontsize=7)
    ax.set_xlabel("CPU time per frame (ms, all threads)")
    ax.set_title(f"{group} (equal scene;\nerror vs each model's own ideal)")
    ax.grid(True, axis="x", alpha=0.3)
    ax.set_xlim(0, max(c["cpu_ms"] for c in cs) * 1.45)
