"""`scripts/bench spheres --translucent`'s summary per set, its Markdown
tables (translucent-results.md; with --doc the block between the
bench-spheres-translucent markers of docs/spheres-bench.md) and its plots
(translucent-errors-SET.png: time vs RMSE against sorted exact;
translucent-modes.png: the Table 5 analogue's times). The runs are
translucent.py's."""
import datetime
import os

from ..lib.common import ROOT, cpu_name, cpu_vector_isa, fmt, isnum, replace_block
from ..lib.plots import pyplot, save, set_bars
from .translucent_runs import FLOOR, TABLE5

DOC_NAME = "bench-spheres-translucent"
DOC_HEADING = "## Translucency (`--translucent`)"


def mean_of(rows, label, k="ms"):
    v = [r[k] for r in rows if r.get("label") == label and r.get("exit_status") == 0 and isnum(r.get(k))]
    return sum(v) / len(v) if v else float("nan")


def summarize(name, count, size, mode_rows, err_rows, astats, vtk_rows, emb, budget):
    nan = float("nan")
    s = {"set": name, "spheres": count, "size": size, **astats}
    for label, *_ in TABLE5:
        lk = label.replace(" ", "_")
        s[f"{lk}_ms"] = mean_of(mode_rows, label)
        s[f"{lk}_peak_rss_mb"] = max([r["peak_rss_mb"] for r in mode_rows if r["label"] == label
                                      and isnum(r.get("peak_rss_mb"))] or [nan])
    s["sorted_peak_rss_mb"] = max([r["peak_rss_mb"] for r in mode_rows if r["mode"] == "sorted"
                                   and isnum(r.get("peak_rss_mb"))] or [nan])
    s["failures"] = sum(1 for r in mode_rows + err_rows if r.get("exit_status") not in (0, "") and
                        not str(r.get("exit_status")).startswith(("timeout", "skipped")))
    s["timeouts"] = len({(r["frame"], r["mode"], r["t"], r["cap"], r.get("surfaces", "both"))
                         for r in mode_rows + err_rows
                         if str(r.get("exit_status")).startswith(("timeout", "skipped"))})
    s["bound_violations"] = sum(1 for r in err_rows if r.get("violation"))
    vt = [r for r in vtk_rows if r["set"] == name]
    ok = [r for r in vt if r.get("exit_status") == 0 and isnum(r.get("ms"))]
    if vt:
        s["vtk_ms"] = sum(r["ms"] for r in ok) / len(ok) if ok else nan
        s["vtk_frames"] = f"{len(ok)}/{len(vt)}"
        s["vtk_error"] = next((r["exit_status"] for r in vt if r.get("exit_status") != 0), "")
        s["vtk_depth_peeling"] = "yes" if ok and all(r.get("depth_peeling") == 1 for r in ok) else "no"
        s["vtk_peak_rss_mb"] = max([r["peak_rss_mb"] for r in ok] or [nan])
        s["vtk_warmup_s"] = next((r["warmup_s"] for r in vt if "warmup_s" in r), nan)
        s["vtk_load_s"] = next((r["load_s"] for r in vt if "load_s" in r), nan)
        a = next((r for r in vt if r.get("png")), {})
        s["vtk_rmse_vs_opaque"] = a.get("rmse_vs_opaque", nan)
        s["vtk_rgb_max_abs_vs_front_exact"] = a.get("rgb_vs_front_exact_max_abs", nan)
        s["vtk_rgb_rmse_vs_front_exact"] = a.get("rgb_vs_front_exact_rmse", nan)
        frames = {r["frame"] for r in ok}
        for lk, label in (("sorted", "sorted"), ("sorted_front", "sorted front")):
            ours = mean_of([r for r in mode_rows if r["frame"] in frames], label)
            s[f"vtk_over_{lk}"] = s["vtk_ms"] / ours if ok else nan
            s[f"goal_vtk_20x_{lk}"] = ("yes" if s[f"vtk_over_{lk}"] >= 20 else "no") if ok else "not shown"
    if emb:
        s["embree_build_ms"] = emb.get("build_ms", nan)
        s["embree_trace_ms"] = emb.get("trace_ms", nan)
        s["embree_peak_rss_mb"] = emb.get("peak_rss_mb", nan)
        s["embree_error"] = emb.get("error", "")
        s["embree_vs_exact_max_abs"] = emb.get("vs_exact_max_abs", nan)
        auto = [r for r in mode_rows if r["frame"] == "auto"]
        s["trace_over_sorted"] = s["embree_trace_ms"] / mean_of(auto, "sorted")
        s["trace_over_sorted_exact"] = s["embree_trace_ms"] / mean_of(auto, "sorted exact")
        s["goal_faster_than_embree"] = "yes" if s["trace_over_sorted"] > 1 else \
            ("no" if isnum(s["trace_over_sorted"]) else "not shown")
    s["goal_memory"] = "yes" if s["sorted_peak_rss_mb"] <= budget else "no"
    return s


def ok_mark(x):
    return {"yes": "yes", "no": "**no**"}.get(x, x or "–")


def doc_lines(a, summary, mode_rows, err_rows, vtk_rows, emb_rows, size, cams, wall, pngs):
    nfr = len(cams)
    L = [f"Measured {datetime.date.today().isoformat()} on {cpu_name()} ({os.cpu_count()} cores, {cpu_vector_isa()}), "
         f"`{a.command}` ({wall / 60:.1f} min): {size}², perspective, zsweep reference's automatic camera"
         + (f" and {nfr - 1} orbit frames (Table 5 rows: means over the {nfr} frames)" if nfr > 1 else "") +
         f", one thread, `render --frames {a.repeat or 1}`, memory budget {a.memory_budget:g} MiB, "
         f"render timeout {a.render_timeout:g} s"
         + (f" (exact renders and the Embree reference: {a.exact_timeout:g} s)" if a.exact_timeout else "") + ".", "",
         "Table 5 analogue (t: tolerance in 8-bit levels, cap: `max_layers`; sorted takes no cap; passes over "
         "the spheres, summed over tiles; ms/layer = "
         "ms / layers max; layers are counted by the peeling modes only; fragments composited: sorted and "
         "peel count the opaque surface under the layers too, dual_peel and weighted the translucent fragments "
         "only; error vs sorted exact of the same surfaces, max abs and RMSE over R, G, B, A):", "",
         "| set | mode | t | cap | surfaces | ms | passes | layers max | layers mean | ms/layer "
         "| fragments composited | pixels stopped | peak RSS MiB | max abs | RMSE | exit |",
         "| --- | --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
    for s in summary:
        for label, mode, t, cap, surf in TABLE5:
            rs = [r for r in mode_rows if r["set"] == s["set"] and r["label"] == label]
            ok = [r for r in rs if r.get("exit_status") == 0]
            bad = [str(r["exit_status"]) for r in rs if r.get("exit_status") != 0]
            def m(k, f=None):
                v = [r[k] for r in ok if isnum(r.get(k))]
                return (f or (lambda x: sum(x) / len(x)))(v) if v else float("nan")
            lm = m("layers_max", max)
            pl = mode in ("peel", "dual_peel")
            L.append(f"| {s['set'].upper()} | {label} | {t if mode in ('sorted', 'peel') else '–'} | "
                     f"{cap if pl else '–'} | {surf} | {fmt(m('ms'))} | {fmt(m('passes'), 0)} | "
                     f"{fmt(lm, 0) if pl else '–'} | {fmt(m('layers_mean'), 2) if pl else '–'} | "
                     f"{fmt(m('ms') / lm, 2) if pl and lm else '–'} | {fmt(m('fragments_composited'), 0)} | "
                     f"{fmt(m('pixels_stopped'), 0)} | {fmt(m('peak_rss_mb', max), 0)} | "
                     f"{fmt(m('max_abs', max), 6)} | {fmt(m('rmse', max), 7)} | "
                     f"{'; '.join(sorted(set(bad))) or 0} |")
    L += ["", "Error sweep on the automatic camera against sorted exact (t 0, no cap). levels = max abs · 255; "
          "bound = t/2 levels; guaranteed: the tolerance stop alone keeps 1 − A ≤ t/510, and a cap of n layers "
          "keeps it only if every translucent sphere has α ≥ α_n(t) = 1 − (t/510)^(1/n) (t 8, n 32: 0.121767); "
          "sorted has no cap; dual_peel to completion is exact up to rounding (bound 0); capped dual_peel and "
          "weighted have no bound:", ""]
    for s in summary:
        L.append(f"- {s['set'].upper()}: {s['translucent']:,} translucent spheres, α min {fmt(s['alpha_min'], 6)} "
                 f"(= {fmt(s['alpha_min'] * 255, 2)}/255), {s['opaque']:,} opaque, {s['clear']:,} clear.")
    L += ["", "| set | mode | t | cap | ms | layers max | max abs | RMSE | levels | bound | α_n(t) | within | "
          "guaranteed | exit |", "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | :---: "
          "| :---: | --- |"]
    order = {"sorted": 0, "peel": 1, "dual_peel": 2, "weighted": 3}
    capo = lambda c: 10**9 if c in (0, "") else c  # noqa: E731
    for r in sorted(err_rows, key=lambda r: ([s["set"] for s in summary].index(r["set"]), order[r["mode"]],
                                             r["t"] if r["t"] != "" else -1, capo(r["cap"]))):
        flag = " **BOUND VIOLATED**" if r.get("violation") else ""
        L.append(f"| {r['set'].upper()} | {r['mode']}{' (reference)' if r['reference'] else ''} | "
                 f"{fmt(r['t'], 0)} | {fmt(r['cap'], 0) if r['cap'] != 0 else 'none'} | {fmt(r['ms'])} | "
                 f"{fmt(r['layers_max'], 0) if r['mode'] in ('peel', 'dual_peel') else '–'} | "
                 f"{fmt(r['max_abs'], 6)} | {fmt(r['rmse'], 7)} | "
                 f"{fmt(r['max_abs_levels'], 3)} | {fmt(r['bound_levels'])} | {fmt(r['alpha_n'], 6)} | "
                 f"{r['within'] or '–'}{flag} | {r['guaranteed']} | {r['exit_status']} |")
    if vtk_rows:
        L += ["", "VTK 9.1 `vtkOpenGLSphereMapper`, per-sphere RGBA (alpha as direct scalars), depth peeling "
              "(`SetUseDepthPeeling(1)`, 32 peels, occlusion ratio 0, alpha bit planes, no multisampling) on "
              "Mesa llvmpipe, `LP_NUM_THREADS=1`; frame = `Render()` + `WaitForCompletion()` after a warm-up "
              "frame. Its sphere mapper draws front surfaces only, so ours is shown with `surfaces: front` too. "
              "Image check on the automatic camera: VTK's image vs the same VTK frame with every alpha 255 "
              "(RMSE, must be > 0), and vs our exact front-surfaces image (`zsweep compare --rgb`; different "
              "shading, so only indicative):", "",
              "| set | VTK ms | frames | depth peeling used | load s, warm-up s | VTK peak RSS MiB | ours sorted ms | "
              "VTK / sorted | ours sorted front ms | VTK / sorted front | vs opaque VTK (RMSE) | "
              "vs ours front exact (max abs, RMSE) |",
              "| --- | ---: | :---: | :---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
        for s in summary:
            if "vtk_ms" not in s:
                continue
            err = f" ({s['vtk_error']})" if s.get("vtk_error") else ""
            L.append(f"| {s['set'].upper()} | {fmt(s['vtk_ms'])} | {s['vtk_frames']}{err} | {s['vtk_depth_peeling']} | "
                     f"{fmt(s['vtk_load_s'])}, {fmt(s['vtk_warmup_s'])} | {fmt(s['vtk_peak_rss_mb'], 0)} | {fmt(s['sorted_ms'])} | "
                     f"{fmt(s['vtk_over_sorted'], 1)}× | {fmt(s['sorted_front_ms'])} | "
                     f"{fmt(s['vtk_over_sorted_front'], 1)}× | {fmt(s['vtk_rmse_vs_opaque'], 4)} | "
                     f"{fmt(s['vtk_rgb_max_abs_vs_front_exact'], 3)}, {fmt(s['vtk_rgb_rmse_vs_front_exact'], 4)} |")
    if emb_rows:
        L += ["", "Embree reference (`zsweep reference SCENE.json --threads 1` on the sorted-exact scene: every "
              "surface crossing, composited exactly) against ours on the same camera; peak RSS by "
              "`/usr/bin/time -f %M`:", "",
              "| set | build ms | trace ms | peak RSS MiB | ours sorted ms (t 8) | trace / sorted | "
              "ours sorted exact ms | trace / sorted exact | image vs sorted exact (max abs) |",
              "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
        for s in summary:
            if "embree_trace_ms" not in s:
                continue
            auto = [r for r in mode_rows if r["set"] == s["set"] and r["frame"] == "auto"]
            L.append(f"| {s['set'].upper()} | {fmt(s['embree_build_ms'])} | {fmt(s['embree_trace_ms'])} "
                     f"{s['embree_error']} | {fmt(s['embree_peak_rss_mb'], 0)} | {fmt(mean_of(auto, 'sorted'))} | "
                     f"{fmt(s['trace_over_sorted'], 2)}× | {fmt(mean_of(auto, 'sorted exact'))} | "
                     f"{fmt(s['trace_over_sorted_exact'], 2)}× | {fmt(s['embree_vs_exact_max_abs'], 7)} |")
    L += ["", f"Goals (sorted: t 8, default cap; memory: peak RSS of every sorted run within --memory-budget "
          f"{a.memory_budget:g} MiB, the goal is on C4):", "",
          "| set | sorted ≥ 20× faster than VTK's peeling (both surfaces; front) | sorted faster than Embree's "
          "trace | sorted peak RSS within budget | bound violations | failed runs | timed out or skipped |",
          "| --- | --- | --- | --- | ---: | ---: | ---: |"]
    for s in summary:
        vt = (f"{ok_mark(s['goal_vtk_20x_sorted'])} ({fmt(s['vtk_over_sorted'], 1)}×); "
              f"{ok_mark(s['goal_vtk_20x_sorted_front'])} ({fmt(s['vtk_over_sorted_front'], 1)}×)"
              if "vtk_ms" in s else "not run")
        em = (f"{ok_mark(s['goal_faster_than_embree'])} ({fmt(s['trace_over_sorted'], 2)}×)"
              if "embree_trace_ms" in s else "not run")
        L.append(f"| {s['set'].upper()} | {vt} | {em} | {ok_mark(s['goal_memory'])} "
                 f"({fmt(s['sorted_peak_rss_mb'], 0)} MiB) | {s['bound_violations']} | {s['failures']} | "
                 f"{s['timeouts']} |")
    if pngs:
        L += ["", " ".join(f"![{os.path.basename(p)[:-4]}](bench/{os.path.basename(p)})" for p in pngs)]
    return L


def plots(summary, mode_rows, err_rows, vtk_rows, emb_rows, outdir):
    plt = pyplot()
    import matplotlib.ticker
    files = []
    styles = {"sorted": ("o", "C0"), "peel": ("s", "C1"), "dual_peel": ("^", "C2"), "weighted": ("D", "C3")}
    for s in summary:
        fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=80)
        rows = [r for r in err_rows if r["set"] == s["set"] and isnum(r.get("ms")) and isnum(r.get("rmse"))]
        for mode, (mk, col) in styles.items():
            pts = [r for r in rows if r["mode"] == mode]
            if not pts:
                continue
            ax.scatter([r["ms"] for r in pts], [max(r["rmse"], FLOOR) for r in pts], marker=mk, color=col,
                       s=22, label=mode, alpha=0.8)
            for r in pts:
                lab = ("exact" if r["reference"] else f"t{r['t']}") if mode == "sorted" else \
                    (f"t{r['t']},{r['cap'] or '∞'}" if mode == "peel" else (f"{r['cap'] or '∞'}" if
                                                                          mode == "dual_peel" else ""))
                ax.annotate(lab, (r["ms"], max(r["rmse"], FLOOR)), fontsize=5, xytext=(2, 2),
                            textcoords="offset points")
        ax.axhline(FLOOR, color="grey", lw=0.5, ls=":")
        ax.text(0.01, 0.02, f"RMSE 0 (exact) plotted at {FLOOR:g}", transform=ax.transAxes, fontsize=6)
        ax.set_xscale("log")
        ax.set_yscale("log")
        for axis in (ax.xaxis.set_major_formatter, ax.xaxis.set_minor_formatter):
            axis(matplotlib.ticker.FuncFormatter(lambda x, _: f"{x:g}"))
        ax.tick_params(axis="x", which="minor", labelsize=6)
        ax.set_xlabel("ms per frame, 1 thread")
        ax.set_ylabel("RMSE vs sorted exact")
        ax.set_title(f"{s['set'].upper()} ({s['spheres']:,} spheres), {s['size']}²: time vs error "
                     "(labels: t,cap; dual_peel: cap)", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        files.append(save(fig, os.path.join(outdir, f"translucent-errors-{s['set']}.png")))
    fig, ax = plt.subplots(figsize=(8, 3.6), dpi=80)
    keys = [(f"{label.replace(' ', '_')}_ms", label) for label, *_ in TABLE5]
    keys += [("vtk_ms", "VTK depth peeling (front)"), ("embree_trace_ms", "Embree reference trace")]
    set_bars(ax, summary, keys, 0.85, "ms per frame, 1 thread", fontsize=6, loc="upper left",
             bbox_to_anchor=(1.0, 1.0))
    return files + [save(fig, os.path.join(outdir, "translucent-modes.png"))]


def write_doc_block(lines):
    replace_block(os.path.join(ROOT, "docs", "spheres-bench.md"), DOC_NAME, lines, DOC_HEADING,
                  "scripts/bench-spheres --translucent")
