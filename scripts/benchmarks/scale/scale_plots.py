"""The plots of `scripts/bench scale`, log–log against tets: scale-time.png
(seconds per phase, one colour per phase, solid for the most threads, dashed
and dotted for fewer) and scale-memory.png (peak RSS, measured and
estimated; bytes per tet above the baseline, with the 100 bytes/tet line)."""
import math
import os

from ..lib.common import isnum
from ..lib.plots import pyplot, save
from .scale_runs import PHASES

STYLES = ["-", "--", ":", "-."]


def ok_rows(rows):
    return [r for r in rows if r.get("status") == 0 and r.get("renderer") == "zsweep"]


def by_threads(rows):
    """{threads: rows sorted by tets}, most threads first."""
    out = {}
    for r in ok_rows(rows):
        out.setdefault(int(r["threads"]), []).append(r)
    return {t: sorted(out[t], key=lambda r: r["tets"]) for t in sorted(out, reverse=True)}


def series(rs, key, scale=1.0):
    pts = [(r["tets"], r[key] * scale) for r in rs if isnum(r.get(key)) and r[key] > 0]
    return [p[0] for p in pts], [p[1] for p in pts]


def time_plot(rows, path, size):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 5.5))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    groups = by_threads(rows)
    for i, (t, rs) in enumerate(groups.items()):
        for j, (key, name) in enumerate(PHASES):
            x, y = series(rs, key)
            if x:
                ax.plot(x, y, STYLES[i % len(STYLES)], marker="o", ms=3, color=colours[j % len(colours)],
                        label=name if i == 0 else None)
    for i, t in enumerate(groups):
        ax.plot([], [], STYLES[i % len(STYLES)], color="grey", label=f"{t} thread{'s' if t > 1 else ''}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("tets")
    ax.set_ylabel("seconds")
    ax.set_title(f"zsweep render per phase, grid meshes, {size}²")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return save(fig, path, dpi=110)


def memory_plot(rows, path):
    plt = pyplot()
    from matplotlib.ticker import FuncFormatter
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.5))
    groups = by_threads(rows)
    for i, (t, rs) in enumerate(groups.items()):
        style = STYLES[i % len(STYLES)]
        x, y = series(rs, "peak_rss_bytes", 1e-9)
        ax.plot(x, y, style, marker="o", ms=3, color="C0", label=f"peak RSS, {t} thread(s)")
        x, y = series(rs, "bytes_per_tet")
        bx.plot(x, y, style, marker="o", ms=3, color="C0", label=f"measured, {t} thread(s)")
    # The estimate (`zsweep mesh info`) does not depend on threads; the
    # baseline added to it is the most threads' (the first group).
    est = {}
    for rs in groups.values():
        for r in rs:
            if isnum(r.get("est_peak_bytes")) and r["tets"] not in est:
                est[r["tets"]] = (r["est_peak_bytes"] + (r.get("baseline_rss_bytes") or 0), r["est_bytes_per_tet"])
    x = sorted(est)
    if x:
        ax.plot(x, [est[t][0] / 1e9 for t in x], ":", marker="x", color="C1", label="estimate (mesh info) + baseline")
        bx.plot(x, [est[t][1] for t in x], ":", marker="x", color="C1", label="estimate (mesh info)")
    bx.axhline(100, color="grey", lw=1, ls="--", label="100 bytes/tet")
    ax.set_xscale("log")
    ax.set_yscale("log")
    # Plain numbers, and on the minor ticks only 2 and 5 (× a power of 10).
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_formatter(FuncFormatter(
        lambda v, _: f"{v:g}" if v > 0 and round(v / 10 ** math.floor(math.log10(v))) in (2, 5) else ""))
    ax.tick_params(axis="y", which="minor", labelsize=7)
    ax.set_ylabel("peak RSS (GB)")
    bx.set_xscale("log")
    top = max([r["bytes_per_tet"] for rs in groups.values() for r in rs if isnum(r.get("bytes_per_tet"))] + [100])
    bx.set_ylim(0, top * 1.25)
    bx.set_ylabel("bytes per tet (peak RSS − baseline)")
    for a in (ax, bx):
        a.set_xlabel("tets")
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=8)
    return save(fig, path, dpi=110)


def plots(rows, d, size):
    """Both plots into directory d; their paths (none without a measured row)."""
    if not ok_rows(rows):
        return []
    os.makedirs(d, exist_ok=True)
    return [time_plot(rows, os.path.join(d, "scale-time.png"), size),
            memory_plot(rows, os.path.join(d, "scale-memory.png"))]
