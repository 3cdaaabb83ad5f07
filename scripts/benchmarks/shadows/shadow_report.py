"""Charts and summary.md of scripts/bench shadows."""
import datetime
import math
import os
import platform
import subprocess

import numpy as np

from ..lib.plots import pyplot, save

PAIRS = [("3-SM+PCF4", "1-SM+PCF9"), ("2-SM(max)+PCF9", "1-SM+PCF16"), ("3-SM+PCF9", "1-SM+PCF16")]
Q_R = (9, 5)  # the thesis's q (3×3 neighbourhood) and r = 9 − 4


def cell(x, nd=1):
    """A table cell as this summary writes it: floats with nd decimals, no
    thousands separators; "–" for no value."""
    if x is None or x == "":
        return "–"
    if isinstance(x, float):
        return f"{x:.{nd}f}"
    return str(x)


def table(head, rows):
    out = ["| " + " | ".join(head) + " |", "|" + "|".join("---" for _ in head) + "|"]
    out += ["| " + " | ".join(cell(c) for c in r) + " |" for r in rows]
    return out


def config_table(cfgs, maps, get, text):
    """Configurations (rows) by map size (columns); text(row): a cell."""
    body = [[c] + [text(get[(c, m)]) if (c, m) in get else "–" for m in maps] for c in cfgs]
    return table(["config"] + [f"map {m}" for m in maps], body)


def machine():
    model = "unknown CPU"
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        for line in out.splitlines():
            if line.startswith("Model name:"):
                model = line.split(":", 1)[1].strip()
    except OSError:
        pass
    return f"{model}, nproc {len(os.sched_getaffinity(0))}, {platform.system()} {platform.release()}"


# ---------------------------------------------------------------- crossover

def cross_analysis(cross):
    """Per config: f, shadow-part time; the measured crossover (where
    1-SM+PCF9 becomes slower than 2-SM+PCF4, linear between sizes) and the
    crossover of the least-squares lines."""
    by = {}
    for r in cross:
        by.setdefault(r["config"], []).append(r)
    two, one = by.get("2-SM(max)+PCF4", []), by.get("1-SM+PCF9", [])
    res = {"measured": None, "fit": None, "lines": {}}
    if not two or not one:
        return res
    f = np.array([r["f"] for r in two], dtype=float)
    t2 = np.array([r["shadow_part_ms"] for r in two], dtype=float)
    t1 = np.array([r["shadow_part_ms"] for r in one], dtype=float)
    d = t1 - t2  # > 0: the 2-SM is cheaper
    for i in range(1, len(f)):
        if d[i - 1] <= 0 < d[i]:
            res["measured"] = float(f[i - 1] + (f[i] - f[i - 1]) * (-d[i - 1]) / (d[i] - d[i - 1]))
            break
    if res["measured"] is None and len(d) and d[0] > 0:
        res["measured_note"] = "2-SM+PCF4 already cheaper at the smallest image"
    if len(f) >= 2:
        for name, t in (("2-SM(max)+PCF4", t2), ("1-SM+PCF9", t1)):
            s, b = np.polyfit(f, t, 1)
            res["lines"][name] = (float(s), float(b))
        s2, b2 = res["lines"]["2-SM(max)+PCF4"]
        s1, b1 = res["lines"]["1-SM+PCF9"]
        if s1 > s2:
            res["fit"] = (b2 - b1) / (s1 - s2)
    return res


# ---------------------------------------------------------------- charts

def plots(out, rows, cross):
    plt = pyplot()
    import matplotlib.ticker
    markers = {1: "o", 4: "s", 9: "^", 16: "D"}
    for scene in sorted({r["scene"] for r in rows}):
        rs = [r for r in rows if r["scene"] == scene and r["kind"] == "map"]
        ex = [r for r in rows if r["scene"] == scene and r["kind"] == "exact"]
        fig, ax = plt.subplots(figsize=(10, 5.5))
        configs = sorted({(r["depths"], r["select"]) for r in rs})
        cmap = plt.get_cmap("tab10")
        for ci, (d, sel) in enumerate(configs):
            for k in sorted({r["pcf"] for r in rs}):
                pts = [r for r in rs if r["depths"] == d and r["select"] == sel and r["pcf"] == k]
                if not pts:
                    continue
                sizes = [20 + 15 * math.log2(r["map_size"] / 256) ** 1.5 for r in pts]
                lab = f"{d}-SM" + (f"({sel})" if d == 2 else "") + f"+PCF{k}"
                ax.scatter([r["time_ms"] for r in pts], [r["band_rmse"] for r in pts], s=sizes, marker=markers.get(k, "x"),
                           color=cmap(ci % 10), alpha=0.75, label=lab)
        for r in ex:
            ax.scatter([r["time_ms"]], [0.0], s=90, marker="*", color="k", label="exact (Embree rays)")
        ax.set_xscale("log")
        plain = matplotlib.ticker.FuncFormatter(lambda v, _pos: f"{v:g}")
        ax.xaxis.set_major_formatter(plain)
        ax.xaxis.set_minor_formatter(plain)
        ax.tick_params(axis="x", which="minor", labelsize=7)
        ax.set_xlabel("frame time, ms (one thread)")
        ax.set_ylabel("RMSE of lit0 within the edge band")
        ax.set_title(f"{scene}: time vs edge-band error (marker size = map size)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        save(fig, os.path.join(out, f"scatter-{scene}.png"), dpi=110)
    if cross:
        fig, ax = plt.subplots(figsize=(7.5, 5))
        res = cross_analysis(cross)
        for name, col in (("2-SM(max)+PCF4", "C0"), ("1-SM+PCF9", "C1")):
            pts = [r for r in cross if r["config"] == name]
            f = np.array([r["f"] for r in pts], dtype=float)
            ax.plot(f, [r["shadow_part_ms"] for r in pts], "o", color=col, label=name + " (total − shadows off)")
            ax.plot(f, [r["total_ms"] for r in pts], "x", color=col, alpha=0.5, label=name + " total")
            if name in res["lines"]:
                s, b = res["lines"][name]
                ff = np.array([0, f.max()])
                ax.plot(ff, s * ff + b, "-", color=col, alpha=0.6)
        q, r = Q_R
        pred = q * cross[0]["map_size"] ** 2 / r
        ax.axvline(pred, color="gray", ls="--", label=f"Eq. 5.6: f = q·h·w/r = {pred:,.0f}")
        if res["measured"]:
            ax.axvline(res["measured"], color="C3", ls=":", label=f"measured crossover {res['measured']:,.0f}")
        ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _pos: f"{v:,.0f}"))
        ax.set_xlabel("f = shadow tests (lit pixel lookups)")
        ax.set_ylabel("ms, one thread")
        ax.set_title(f"Eq. 5.6/5.7 on bars, map {cross[0]['map_size']}²")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        save(fig, os.path.join(out, "crossover.png"), dpi=110)


# ---------------------------------------------------------------- summary.md

def summary(a, argv, scenes, rows, cross, cross_note, vtk_rows, vtk_note, notes, fails, seconds, zsweep):
    L = ["# bench-shadows", ""]
    L += [f"- Machine: {machine()}", f"- Date: {datetime.datetime.now().strftime('%Y-%m-%d %H:%M')}",
          f"- Command: `{' '.join(['scripts/bench-shadows'] + list(argv))}` (zsweep: `{zsweep}`)",
          f"- Every render one thread (`--threads 1`); grid images {a.size}², each time the best of {a.frames} "
          f"frame(s) in one process, best of {a.rounds} process(es); band = {a.band:g} map texels of an exact shadow edge. Run time {seconds:.0f} s.",
          "- Times are `time_ms.total` of `--stats` (setup: projection, binning, map raster, n-SM pass; then the "
          "tiles), not the mesh load."]
    L += [f"- {n}" for n in notes]
    L += ["", "## Checks", ""]
    L += [f"- FAILED: {f}" for f in fails] or ["- All passed: levels ≤ n·k+1 on every render; at the largest map "
                                                f"({max(a.maps)}) band RMSE < 0.5 and far errors ≤ "
                                                f"{a.far_tolerance:.1%} of the surface pixels; acne and "
                                                "peter-panning detected on `tilted`."]
    for scene in scenes:
        L += scene_section(a, scene, [r for r in rows if r["scene"] == scene])
    L += pairs_section(a, rows)
    L += cross_section(a, cross, cross_note)
    L += vtk_section(a, vtk_rows, vtk_note)
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write("\n".join(L) + "\n")


def scene_section(a, scene, rs):
    ex = next(r for r in rs if r["kind"] == "exact")
    maps = sorted({r["map_size"] for r in rs if r["kind"] == "map"})
    cfgs = []
    for r in rs:
        if r["kind"] == "map" and r["config"] not in cfgs:
            cfgs.append(r["config"])
    get = {(r["config"], r["map_size"]): r for r in rs if r["kind"] == "map"}
    L = ["", f"## {scene}", "",
         f"Exact (Embree shadow rays): {ex['time_ms']:.1f} ms (BVH build {ex['rays_build_ms']:.1f} ms), "
         f"{ex['surface_pixels']} surface pixels, {ex['edge_pixels']} exact edge pixels. "
         f"![scatter](scatter-{scene}.png)", "",
         "Band RMSE / band max / frame ms per map size:", ""]
    L += config_table(cfgs, maps, get, lambda r: f"{r['band_rmse']:.3f} / {r['band_max']:.2f} / {r['time_ms']:.0f}")
    first = {m: get[(cfgs[0], m)] for m in maps if (cfgs[0], m) in get}
    L += ["", "Band size (its pixels, and its half-width of " + f"{a.band:g}" + " texels in pixels at the median surface depth): "
          + "; ".join(f"map {m}: {r['band_pixels']} px, {band_px(a, r):.1f} px" for m, r in first.items()) + "."]
    L += ["", "Outside the band: wrongly lit / wrongly shadowed pixels; levels found / n·k+1 "
          "(✓ = bound reached):", ""]
    L += config_table(cfgs, maps, get, lambda r: f"{r['far_wrong_lit']} / {r['far_wrong_shadowed']}; "
                      f"{r['levels']}/{r['max_levels']}" + (" ✓" if r["levels_reached"] else ""))
    mp = [r for r in rs if r["kind"] == "map"]
    if scene == "bars" and mp:
        reached = sorted({r["config"] for r in mp if r["levels_reached"]}, key=cfgs.index)
        never = [c for c in cfgs if c not in reached]
        L += ["", f"n·k+1 reached (at some map size) by {len(reached)} of {len(cfgs)} configurations"
              + (f"; not by {', '.join(never)}." if never else ".")]
    big = max(mp, key=lambda r: r["map_size"]) if mp else None
    if big:
        m = big["map_size"]
        hi = max((r for r in mp if r["map_size"] == m), key=lambda r: r["peak_rss_mb"])
        L += ["", f"Peak RSS at map {m}: up to {hi['peak_rss_mb']:.0f} MB ({hi['config']}); exact mode "
              f"{ex['peak_rss_mb']:.0f} MB. n-SM pass ({hi['config']}): {hi['multi_depth_ms']:.1f} ms, "
              f"map raster {hi['raster_ms']:.1f} ms."]
    if scene == "tilted":
        L += tilted_section(rs)
    return L


def band_px(a, r):
    """The band's half-width in pixels at the median surface pixel depth."""
    return a.band * float(r["texel"]) / r["footprint_median"] if r.get("footprint_median") else float("nan")


def tilted_section(rs):
    chk = [r for r in rs if r["kind"] in ("acne_check", "peter_check")]
    if not chk:
        return []
    c = chk[0]
    base = next((r for r in rs if r["kind"] == "map" and r["config"] == c["config"] and r["map_size"] == c["map_size"]),
                None)
    body = []
    for r in ([base] if base else []) + chk:
        body.append([{"map": "default", "acne_check": "slope_bias 0", "peter_check": "large bias"}[r["kind"]],
                     r["config"], r["map_size"], f"{r['bias']:g}", f"{r['slope_bias']:g}", r["far_wrong_shadowed"],
                     r["wrong_lit_all"], f"{r['band_rmse']:.3f}"])
    L = ["", "Acne (wrongly shadowed outside the band) and peter-panning (wrongly lit anywhere) on `tilted`; "
         "at the default bias every configuration's acne is the far wrongly-shadowed count above:", ""]
    L += table(["run", "config", "map", "bias (world)", "slope_bias (texels)", "acne px", "peter-panning px",
                "band RMSE"], body)
    return L


def pairs_section(a, rows):
    L = ["", "## The seed's pairings (smaller PCF on an n-SM vs larger PCF on a 1-SM)", "",
         "Band RMSE, band max and frame time (ms) of each side, per scene and map size.", ""]
    get = {(r["scene"], r["config"], r["map_size"]): r for r in rows if r["kind"] == "map"}
    body = []
    for scene in sorted({r["scene"] for r in rows}):
        for m in a.maps:
            for x, y in PAIRS:
                rx, ry = get.get((scene, x, m)), get.get((scene, y, m))
                if not rx or not ry:
                    continue
                body.append([scene, m, f"{x} vs {y}", f"{rx['band_rmse']:.3f} / {ry['band_rmse']:.3f}",
                             f"{rx['band_max']:.2f} / {ry['band_max']:.2f}", f"{rx['time_ms']:.0f} / {ry['time_ms']:.0f}",
                             f"{rx['levels']}/{rx['max_levels']} vs {ry['levels']}/{ry['max_levels']}"])
    if not body:
        return L + ["No pairing in this run (it needs PCF 16 or 3-SM; --quick leaves PCF 16 out)."]
    L += table(["scene", "map", "pair", "band RMSE", "band max", "ms", "levels"], body)
    L += [""]
    for x, y in PAIRS:
        ps = [(get[(s, x, m)], get[(s, y, m)]) for (s, c, m) in get if c == x and (s, y, m) in get]
        if not ps:
            continue
        e = np.exp(np.mean([np.log(p[0]["band_rmse"] / p[1]["band_rmse"]) for p in ps if p[1]["band_rmse"] > 0]))
        t = np.exp(np.mean([np.log(p[0]["time_ms"] / p[1]["time_ms"]) for p in ps]))
        L += [f"- {x} vs {y}: band RMSE {e:.2f}×, time {t:.2f}× (geometric means over {len(ps)} scene × map cases)."]
    return L


def cross_section(a, cross, note):
    L = ["", "## Eq. 5.6/5.7 crossover (deferred shading, f = shadow tests)", ""]
    if not cross:
        return L + [f"Not run ({note})."]
    q, r = Q_R
    m = cross[0]["map_size"]
    pred = q * m * m / r
    res = cross_analysis(cross)
    L += [f"`bars` seen from above so that ground fills every pixel, map {m}², images "
          f"{', '.join(str(s) for s in sorted({x['width'] for x in cross}))} square; each time the best of "
          f"{cross[0]['frames']} frames in one process, best of {cross[0]['rounds']} processes. Time = the shadow part of the frame: "
          "time_ms.total minus a shadows-off render of the same image (totals in crossover.csv). "
          "![crossover](crossover.png)", ""]
    if note:
        L += [f"Note: {note}.", ""]
    body = []
    by = {}
    for x in cross:
        by.setdefault(x["width"], {})[x["config"]] = x
    for w in sorted(by):
        t = by[w].get("2-SM(max)+PCF4")
        o = by[w].get("1-SM+PCF9")
        if t and o:
            body.append([f"{w}²", t["f"], f"{t['shadow_part_ms']:.1f}", f"{o['shadow_part_ms']:.1f}",
                         f"{t['multi_depth_ms']:.1f}", f"{t['total_ms']:.1f}", f"{o['total_ms']:.1f}",
                         f"{t['off_ms']:.1f}"])
    L += table(["image", "f", "2-SM+PCF4 shadow ms", "1-SM+PCF9 shadow ms", "n-SM pass ms", "2-SM total",
                "1-SM total", "shadows off"], body)
    meas = f"{res['measured']:,.0f}" if res["measured"] else res.get("measured_note", "no crossover in range")
    L += ["", f"- Predicted (Eq. 5.6, texel fetches): f = q·h·w/r = {q}·{m}²/{r} = {pred:,.0f}; "
          f"counting depth comparisons instead (a 2-SM+PCF4 test compares 8 depths, a 1-SM+PCF9 test 9: r = 1) "
          f"f = {q * m * m:,}.", f"- Measured (interpolated between image sizes): {meas}."]
    if res["lines"]:
        s2, b2 = res["lines"]["2-SM(max)+PCF4"]
        s1, b1 = res["lines"]["1-SM+PCF9"]
        fit = f"{res['fit']:,.0f}" if res["fit"] else "none (the 2-SM line is not flatter)"
        L += [f"- Least-squares lines: 2-SM+PCF4 {b2:.2f} ms + {s2 * 1e6:.1f} ns·f; 1-SM+PCF9 {b1:.2f} ms + "
              f"{s1 * 1e6:.1f} ns·f; they cross at f = {fit}."]
    return L


def vtk_section(a, vtk_rows, note):
    L = ["", f"## Side by side, one thread: map {a.vtk_map}, images {a.vtk_size} (square)", ""]
    if not vtk_rows:
        return L + [f"Skipped: {note}."]
    L += ["VTK: vtkShadowMapPass (+ vtkShadowMapBakerPass) on Mesa llvmpipe, LP_NUM_THREADS=1 under xvfb-run; "
          f"frame = best of {a.vtk_repeat} Render() calls that each re-bake the map (the light is touched), "
          "cached = best frame reusing the map; plain = the same scene without shadows; shadow part = frame − plain "
          "(the cost of the shadow-map pass). Ours: best of "
          f"{a.ours_repeat} frames' time_ms.total in one process, best of {a.rounds} process(es) (map rebuilt every "
          "frame), written to PNG: RGBA frames, as VTK's; EXR ms: the same with the Z and lit channels (one process). "
          "Darker pixels: luminance ≥ 0.1 "
          "lower than the same renderer without shadows (VTK's shadow_check); ratio to our exact mode.", ""]
    body = [[r["scene"], f"{r['width']}²", r["renderer"], r["config"], f"{r['frame_ms']:.1f}",
             f"{r['frame_cached_ms']:.1f}" if r["frame_cached_ms"] != "" else "–",
             f"{r['frame_exr_ms']:.1f}" if r.get("frame_exr_ms", "") != "" else "–", f"{r['frame_plain_ms']:.1f}",
             f"{r['shadow_part_ms']:.1f}", r["peak_rss_mb"],
             r["darker_pixels"], r.get("darker_vs_exact", "")] for r in vtk_rows]
    return L + table(["scene", "image", "renderer", "config", "frame ms", "cached-map ms", "EXR ms", "plain ms",
                      "shadow part ms", "peak RSS MB", "darker px",
                      "vs exact"], body)
