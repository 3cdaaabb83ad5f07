"""`scripts/bench spheres --ao`'s plots: time against error (ao-time-error.png),
error against the map size (ao-error-map.png), Tables 7 and 6 as bars
(ao-table7.png, ao-table6.png), and the AO images side by side
(ao-compare-SET.png)."""
import os

import numpy as np

from ..lib.common import isnum
from ..lib.plots import pyplot, save


def save_bars(fig, ax, ylabel, path):
    """A bar chart's log axis, grid and legend, saved to `path` (returned)."""
    ax.set_yscale("log")
    ax.set_ylabel(ylabel, fontsize=8)
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(fontsize=7)
    return save(fig, path)


def plots(results, tables, c, a, outdir):
    plt = pyplot()
    files = []
    sets = [r for r in results if r["grid"]]
    if not sets:
        return files
    cols = min(3, len(sets))
    nrow = (len(sets) + cols - 1) // cols
    dirs = sorted({g["directions"] for r in sets for g in r["grid"]})
    maps = sorted({g["map_size"] for r in sets for g in r["grid"]})
    colours = {d: plt.cm.viridis(i / max(len(dirs) - 1, 1)) for i, d in enumerate(dirs)}
    marks = dict(zip(maps, "os^Dvp<>"))

    # Time against error vs MC.
    fig, axs = plt.subplots(nrow, cols, figsize=(4.2 * cols, 3.4 * nrow), dpi=80, squeeze=False)
    for ax, r in zip(axs.flat, sets):
        for g in r["grid"]:
            if not (isnum(g.get("vs_mc_mean")) and isnum(g.get("ms"))):
                continue
            ax.plot(g["ms"], g["vs_mc_mean"], marks[g["map_size"]], color=colours[g["directions"]], ms=5)
            if isnum(g.get("amortised_ms")):
                ax.plot(g["amortised_ms"], g["vs_mc_mean"], marks[g["map_size"]], mfc="none",
                        color=colours[g["directions"]], ms=5)
        ta = sorted([v for v in r["versus"] if v["renderer"] == "tachyon" and isnum(v.get("vs_mc_mean"))],
                    key=lambda v: v["samples"])
        if ta:
            ax.plot([v["ms"] for v in ta], [v["vs_mc_mean"] for v in ta], "k.--", lw=1, label="Tachyon (4…S samples)")
            for v in ta:
                ax.annotate(str(int(v["samples"])), (v["ms"], v["vs_mc_mean"]), fontsize=6)
        vt = [v for v in r["versus"] if v["renderer"] == "vtk-ssao" and isnum(v.get("vs_mc_mean"))]
        if vt:
            ax.plot([v["ms"] for v in vt], [v["vs_mc_mean"] for v in vt], "rx", ms=7,
                    label="VTK vtkSSAOPass (radius in r̄)")
            for v in vt:
                if isnum(v.get("radius")):
                    ax.annotate(f"{v['radius']:g}", (v["ms"], v["vs_mc_mean"]), fontsize=6, color="r")
        if isnum(r.get("noise_floor")):
            ax.axhline(r["noise_floor"], color="grey", ls=":", lw=1, label="MC reference noise")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{r['set'].upper()} ({r['spheres']:,} spheres)", fontsize=9)
        ax.set_xlabel("ms per frame, 1 thread (hollow: + maps / %g)" % getattr(a, "amortise", 100), fontsize=7)
        ax.set_ylabel("mean |ΔAO| vs Monte Carlo", fontsize=7)
        ax.grid(True, which="both", alpha=0.3)
        ax.tick_params(labelsize=7)
    for ax in list(axs.flat)[len(sets):]:
        ax.axis("off")
    handles = [plt.Line2D([], [], color=colours[d], marker="o", ls="", label=f"{d} directions") for d in dirs]
    handles += [plt.Line2D([], [], color="k", marker=marks[m], ls="", mfc="none", label=f"map {m}²") for m in maps]
    seen = {}
    for ax in axs.flat:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            seen.setdefault(lab, h)
    fig.tight_layout()
    fig.legend(handles + list(seen.values()), [x.get_label() for x in handles] + list(seen), fontsize=7,
               loc="center left", bbox_to_anchor=(1.0, 0.5))
    files.append(os.path.join(outdir, "ao-time-error.png"))
    fig.savefig(files[-1], bbox_inches="tight")
    plt.close(fig)

    # Error vs the exact directions, against the map size.
    fig, axs = plt.subplots(nrow, cols, figsize=(4.2 * cols, 3.2 * nrow), dpi=80, squeeze=False)
    for ax, r in zip(axs.flat, sets):
        for d in dirs:
            pts = sorted((g["map_size"], g["vs_exact_mean"]) for g in r["grid"]
                         if g["directions"] == d and isnum(g.get("vs_exact_mean")))
            if pts:
                ax.plot(*zip(*pts), "o-", color=colours[d], label=f"{d} directions", ms=4)
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_title(f"{r['set'].upper()}", fontsize=9)
        ax.set_xlabel("map size (texels per side)", fontsize=7)
        ax.set_ylabel("mean |ΔAO| vs exact directions", fontsize=7)
        ax.grid(True, which="both", alpha=0.3)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6)
    for ax in list(axs.flat)[len(sets):]:
        ax.axis("off")
    files.append(save(fig, os.path.join(outdir, "ao-error-map.png")))

    # Table 7: the maps' time per direction count; Table 6: Phong against AO.
    t7 = tables.get("ao-table7.csv") or []
    fig, ax = plt.subplots(figsize=(6, 3.4), dpi=80)
    wbar = 0.8 / max(len(dirs), 1)
    for i, d in enumerate(dirs):
        ys = [next((t["maps_ms"] for t in t7 if t["set"] == r["set"] and t["directions"] == d
                    and isnum(t.get("maps_ms"))), float("nan")) for r in sets]
        ax.bar([j + i * wbar for j in range(len(sets))], ys, wbar, label=f"{d} directions", color=colours[d])
    ax.set_xticks([j + 0.4 - wbar / 2 for j in range(len(sets))])
    ax.set_xticklabels([f"{r['set'].upper()}\n{r['spheres']:,}" for r in sets], fontsize=8)
    files.append(save_bars(fig, ax, f"ms to build the maps ({c['tmap']}², 1 thread)", os.path.join(outdir, "ao-table7.png")))
    t6 = tables.get("ao-table6.csv") or []
    if t6:
        fig, ax = plt.subplots(figsize=(6, 3.4), dpi=80)
        xs = np.arange(len(t6))
        for i, (k, lab) in enumerate([("phong_ms", "Phong"), ("ao_ms", "AO frame"), ("maps_ms", "AO maps (once)")]):
            ax.bar(xs + i * 0.27, [t.get(k) if isnum(t.get(k)) else float("nan") for t in t6], 0.27, label=lab)
        ax.set_xticks(xs + 0.27)
        ax.set_xticklabels([f"{t['set'].upper()}\n{int(t['spheres']):,}" for t in t6], fontsize=8)
        files.append(save_bars(fig, ax, f"ms, 1 thread, {int(t6[0]['size'])}²", os.path.join(outdir, "ao-table6.png")))
    return files


def compare_png(path, panels, name):
    """AO images side by side (grey: 0 black, 1 white; off the spheres blue)."""
    plt = pyplot()
    panels = [(t, im) for t, im in panels if im is not None]
    if not panels:
        return None
    fig, axs = plt.subplots(1, len(panels), figsize=(2.6 * len(panels), 2.9), dpi=90, squeeze=False)
    for ax, (t, im) in zip(axs[0], panels):
        rgb = np.repeat(np.clip(np.where(np.isfinite(im), im, 0), 0, 1)[..., None], 3, axis=2)
        rgb[~np.isfinite(im)] = (0.2, 0.3, 0.6)
        ax.imshow(rgb, interpolation="nearest")
        ax.set_title(t, fontsize=7)
        ax.axis("off")
    fig.suptitle(f"{name.upper()}: AO", fontsize=9)
    return save(fig, path)
