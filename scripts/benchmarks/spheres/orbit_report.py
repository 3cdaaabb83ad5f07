"""The orbit benchmark's summary per set, its Markdown tables (results.md;
with --doc the block between the bench-spheres markers of
docs/spheres-bench.md) and its plots (spheres-SET.png: ms per orbit frame;
spheres-mean.png: the means per set); --replot draws the plots again from a
run's CSVs."""
import datetime
import os

from ..lib.common import copy_to_docs, cpu_name, cpu_vector_isa, fmt, isnum, read_csv
from ..lib.plots import pyplot, save, set_bars


def plots(rows, summary, outdir, prefix):
    plt = pyplot()
    files = []
    for s in summary:
        name = s["set"]
        fig, ax = plt.subplots(figsize=(6, 3.4), dpi=80)
        def series(renderer, threads):
            pts = [(r["frame"], r["ms"]) for r in rows
                   if r["set"] == name and r["renderer"] == renderer and r["threads"] == threads
                   and r["frame"] != "auto" and isinstance(r.get("ms"), float)]
            return [p[0] for p in pts], [p[1] for p in pts]
        for renderer, threads, label, style in [("zsweep-basic", 1, "basic (--no-culling), 1 thread", "o-"),
                                                ("zsweep-optimized", 1, "optimized (culling), 1 thread", "s-"),
                                                ("zsweep-optimized", 2, "optimized, 2 threads", "^--"),
                                                ("vtk", 1, "VTK vtkOpenGLSphereMapper, llvmpipe 1 thread", "x:")]:
            x, y = series(renderer, threads)
            if x:
                ax.plot(x, y, style, label=label, markersize=4)
        if isnum(s.get("embree_trace_ms")):
            ax.axhline(s["embree_trace_ms"], color="grey", ls="-.", lw=1,
                       label="Embree reference trace (auto camera), 1 thread")
        ax.set_yscale("log")
        ax.set_xlabel("orbit frame (0: whole set in view; middle: closest)")
        ax.set_ylabel("ms per frame")
        ax.set_title(f"{name.upper()} ({s['spheres']:,} spheres), {s['size']}²", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        files.append(save(fig, os.path.join(outdir, f"{prefix}{name}.png")))
    fig, ax = plt.subplots(figsize=(6, 3.4), dpi=80)
    keys = [("basic_ms", "basic, 1 thread"), ("optimized_ms", "optimized, 1 thread"),
            ("optimized_2t_ms", "optimized, 2 threads"), ("vtk_ms", "VTK sphere mapper, 1 thread"),
            ("embree_trace_ms", "Embree trace, 1 thread (auto camera)")]
    set_bars(ax, summary, keys, 0.8, "mean ms per frame over the orbit", fontsize=7)
    return files + [save(fig, os.path.join(outdir, f"{prefix}mean.png"))]


def replot(d, doc):
    """The plots again from DIR's CSVs (with --doc: into docs/bench)."""
    rows = read_csv(d, "spheres-frames.csv")
    for r in rows:  # ms is a float in the rows the run builds
        if isinstance(r.get("ms"), int):
            r["ms"] = float(r["ms"])
        if isinstance(r.get("frame"), float):
            r["frame"] = int(r["frame"])
    files = plots(rows, read_csv(d, "spheres-summary.csv"), d, "spheres-")
    if doc:
        copy_to_docs(files)
    print("wrote", ", ".join(files))
    return 0


def summarize(name, count, size, rows, threads, emb, with_vtk):
    nan = float("nan")

    def mean(renderer, t, key="ms"):
        v = [r[key] for r in rows if r["renderer"] == renderer and r["threads"] == t and r["frame"] != "auto"
             and isinstance(r.get(key), (int, float))]
        return sum(v) / len(v) if v else nan

    def mx(renderer, key):
        v = [r[key] for r in rows if r["renderer"] == renderer and isinstance(r.get(key), (int, float))]
        return max(v) if v else nan

    orbit_rows = [r for r in rows if r["frame"] != "auto" and r["renderer"].startswith("zsweep")]
    s = {"set": name, "spheres": count, "size": size,
         "basic_ms": mean("zsweep-basic", 1), "optimized_ms": mean("zsweep-optimized", 1)}
    s["culling_speedup"] = s["basic_ms"] / s["optimized_ms"]
    for t in threads[1:]:
        s[f"optimized_{t}t_ms"] = mean("zsweep-optimized", t)
        s[f"threads_{t}_speedup"] = s["optimized_ms"] / s[f"optimized_{t}t_ms"]
    for k in ("setup_ms", "visibility_ms", "pyramid_ms", "occlusion_culling_ms", "binning_ms", "tiles_ms",
              "spheres_visible", "fragments"):
        s[f"optimized_{k}"] = mean("zsweep-optimized", 1, k)
        s[f"basic_{k}"] = mean("zsweep-basic", 1, k)
    s["frames_same_as_basic"] = f"{sum(r.get('same_as_basic') == 'yes' for r in orbit_rows if r['renderer'] == 'zsweep-optimized')}/" \
                                f"{sum(1 for r in orbit_rows if r['renderer'] == 'zsweep-optimized')}"
    s["zsweep_failures"] = sum(1 for r in orbit_rows if r.get("exit_status") != 0)
    s["zsweep_peak_rss_mb"] = mx("zsweep-optimized", "peak_rss_mb")
    s["zsweep_basic_peak_rss_mb"] = mx("zsweep-basic", "peak_rss_mb")
    if with_vtk:
        vt = [r for r in rows if r["renderer"] == "vtk"]
        ok = [r for r in vt if isinstance(r.get("ms"), float)]
        s["vtk_ms"] = mean("vtk", 1)
        s["vtk_frames"] = f"{len(ok)}/{len(vt)}"
        s["vtk_error"] = next((r["exit_status"] for r in vt if r.get("exit_status") not in (0, None)), "")
        s["vtk_warmup_ms"] = next((r["setup_ms"] for r in vt if "setup_ms" in r), nan)
        s["vtk_peak_rss_mb"] = mx("vtk", "peak_rss_mb")
        # Ratio over the frames both rendered (VTK may have stopped part way).
        both = [r["frame"] for r in ok]
        ours = [r["ms"] for r in rows if r["renderer"] == "zsweep-optimized" and r["threads"] == 1
                and r["frame"] in both and isinstance(r.get("ms"), float)]
        s["vtk_over_ours"] = (sum(r["ms"] for r in ok) / sum(ours)) if ours and ok else nan
    if emb:
        s["embree_bvh_ms"] = emb.get("bvh_ms", nan)
        s["embree_trace_ms"] = emb.get("trace_ms", nan)
        s["embree_peak_rss_mb"] = emb.get("peak_rss_mb", nan)
        s["ours_auto_ms"] = emb.get("ours_ms") if emb.get("ours_ms") is not None else nan
        s["embree_trace_over_ours"] = s["embree_trace_ms"] / s["ours_auto_ms"]
        s["embree_total_over_ours"] = (s["embree_trace_ms"] + s["embree_bvh_ms"]) / s["ours_auto_ms"]
        s["embree_vs_ours_max_abs"] = emb.get("max_abs", nan)
        s["embree_vs_ours_rmse"] = emb.get("rmse", nan)
    return s


def doc_lines(summary, a, size, nframes, repeat, threads, wall):
    lines = [
        f"Measured {datetime.date.today().isoformat()} on {cpu_name()} ({os.cpu_count()} cores, {cpu_vector_isa()}), "
        f"`{a.command}` ({wall / 60:.1f} min): {size}², perspective, {nframes} orbit frames, each the best of "
        f"{repeat} whole frames (`render --frames {repeat}`), basic and optimized interleaved frame by frame, "
        f"memory budget {a.memory_budget:g} MiB.",
        "",
        "| set | spheres | basic ms | optimized ms | culling gain | optimized = basic | "
        + " | ".join(f"{t} threads ms | {t}-thread speedup" for t in threads[1:]) + " | peak RSS MiB (opt / basic) |",
        "| --- | ---: | ---: | ---: | ---: | :---: | " + " ---: | ---: |" * len(threads[1:]) + " ---: |",
    ]
    for s in summary:
        lines.append(f"| {s['set'].upper()} | {s['spheres']:,} | {fmt(s['basic_ms'])} | {fmt(s['optimized_ms'])} | "
                     f"{fmt(s['culling_speedup'], 2)}× | {s['frames_same_as_basic']} | " +
                     "".join(f"{fmt(s[f'optimized_{t}t_ms'])} | {fmt(s[f'threads_{t}_speedup'], 2)}× | "
                             for t in threads[1:]) +
                     f"{fmt(s['zsweep_peak_rss_mb'], 0)} / {fmt(s['zsweep_basic_peak_rss_mb'], 0)} |")
    lines += ["", "Optimized frames, mean phase times (ms) and counts over the orbit (basic in parentheses):", "",
              "| set | setup | of which visibility | pyramid | occlusion | binning | tiles (total − setup) | "
              "spheres drawn | fragments |",
              "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for s in summary:
        lines.append(f"| {s['set'].upper()} | {fmt(s['optimized_setup_ms'])} ({fmt(s['basic_setup_ms'])}) | "
                     f"{fmt(s['optimized_visibility_ms'])} | {fmt(s['optimized_pyramid_ms'])} | "
                     f"{fmt(s['optimized_occlusion_culling_ms'])} | {fmt(s['optimized_binning_ms'])} "
                     f"({fmt(s['basic_binning_ms'])}) | {fmt(s['optimized_tiles_ms'])} ({fmt(s['basic_tiles_ms'])}) | "
                     f"{fmt(s['optimized_spheres_visible'], 0)} ({fmt(s['basic_spheres_visible'], 0)}) | "
                     f"{fmt(s['optimized_fragments'], 0)} ({fmt(s['basic_fragments'], 0)}) |")
    if a.vtk:
        lines += ["", "VTK's `vtkOpenGLSphereMapper` (Mesa llvmpipe, `LP_NUM_THREADS=1`), same spheres, orbit and size; "
                  "ratio = VTK's mean / ours (optimized, 1 thread) over the frames VTK rendered; goal ≥ 10×:", "",
                  "| set | VTK ms | frames | warm-up s (shaders, upload) | VTK peak RSS MiB | ours ms | VTK / ours | ≥ 10× |",
                  "| --- | ---: | :---: | ---: | ---: | ---: | ---: | :---: |"]
        for s in summary:
            r = s.get("vtk_over_ours", float("nan"))
            ok = "–" if r != r else ("yes" if r >= 10 else "**no**")
            err = f" ({s['vtk_error']})" if s.get("vtk_error") else ""
            lines.append(f"| {s['set'].upper()} | {fmt(s.get('vtk_ms'))} | {s.get('vtk_frames')}{err} | "
                         f"{fmt(s.get('vtk_warmup_ms', float('nan')) / 1000, 1)} | {fmt(s.get('vtk_peak_rss_mb'), 0)} | "
                         f"{fmt(s['optimized_ms'])} | {fmt(r, 2)}× | {ok} |")
    if a.embree:
        lines += ["", "Embree reference (`zsweep reference --threads 1 --projection perspective`, its automatic camera) "
                  "and ours (optimized, 1 thread) on that same camera; goal on C3 and C4: ours faster per frame than "
                  "Embree's trace:", "",
                  "| set | Embree BVH ms | Embree trace ms | Embree peak RSS MiB | ours ms | trace / ours | "
                  "(BVH + trace) / ours | images: max abs, RMSE |",
                  "| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
        for s in summary:
            lines.append(f"| {s['set'].upper()} | {fmt(s.get('embree_bvh_ms'))} | {fmt(s.get('embree_trace_ms'))} | "
                         f"{fmt(s.get('embree_peak_rss_mb'), 0)} | {fmt(s.get('ours_auto_ms'))} | "
                         f"{fmt(s.get('embree_trace_over_ours'), 2)}× | {fmt(s.get('embree_total_over_ours'), 1)}× | "
                         f"{fmt(s.get('embree_vs_ours_max_abs'), 3)}, {fmt(s.get('embree_vs_ours_rmse'), 4)} |")
    return lines
