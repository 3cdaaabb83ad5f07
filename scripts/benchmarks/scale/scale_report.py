"""What `scripts/bench scale` writes: the CSV (zsweep rows per mesh × threads,
then the VTK comparison's rows), the plots (scale_plots.py), and the section
of docs/scaling.md between the bench-scale markers: the machine and command,
the table per mesh × threads, the VTK table, each phase's growth between
consecutive meshes, and issue 41's goals, measured and met or not."""
import math
import os

from ..lib.common import ROOT, all_cols, fmt, isnum, replace_block, write_csv
from .scale_plots import by_threads, plots
from .scale_runs import PHASES, label

GOAL_TETS = 41e6          # the mesh: first frame, later frame, RSS at 2 threads
GOAL_FIRST_S, GOAL_LATER_S, GOAL_RSS = 15, 8, 4.5e9
GOAL_GROWTH = 4.6         # per 4× tets, every phase
GOAL_VS_VTK, GOAL_VTK_TETS = 3, 10e6   # later frames vs VTK ray caster's (after its first) there


def growth(rows):
    """Per thread count and consecutive pair of measured meshes: {threads,
    pair, q (tets ratio), phase column: (ratio, ratio normalised to 4× tets
    = ratio^(ln 4 / ln q))}."""
    out = []
    for t, rs in by_threads(rows).items():
        for lo, hi in zip(rs, rs[1:]):
            q = hi["tets"] / lo["tets"]
            g = {"threads": t, "pair": f"{label(lo['tets'])}→{label(hi['tets'])}", "q": q}
            for key, _ in PHASES:
                if isnum(lo.get(key)) and isnum(hi.get(key)) and lo[key] > 0 and q > 1:
                    r = hi[key] / lo[key]
                    g[key] = (r, r ** (math.log(4) / math.log(q)))
            out.append(g)
    return out


def status(r):
    s = r.get("status")
    if s == 0:
        return "ok"
    # One table cell: no pipe from an error line.
    return (f"{s}" + (f": {r['error']}" if r.get("error") else "")).replace("|", "\\|")


def met(ok):
    return "yes" if ok else "**no**"


def goals(rows, vtk_rows, grow):
    """[(goal, measured, met)] of issue 41."""
    out = []
    at41 = [r for r in rows if r.get("renderer") == "zsweep" and r.get("threads") == 2
            and abs(r["tets"] - GOAL_TETS) < 0.05 * GOAL_TETS]
    r = at41[0] if at41 else None
    for key, name, limit, unit, scale in (("first_frame_s", "first frame", GOAL_FIRST_S, "s", 1),
                                          ("later_frame_s", "later frame", GOAL_LATER_S, "s", 1),
                                          ("peak_rss_bytes", "peak RSS", GOAL_RSS, "GB", 1e-9)):
        goal = f"41 M tets, 2 threads: {name} ≤ {limit * scale:g} {unit}"
        if r is None or r.get("status") != 0 or not isnum(r.get(key)):
            # A render that failed has not met it; a size skipped (or not asked) is not measured.
            failed = r is not None and not str(r.get("status")).startswith("skipped")
            out.append((goal, "not measured" if r is None else status(r), "**no**" if failed else "–"))
        else:
            out.append((goal, f"{r[key] * scale:.2f} {unit} ({r['tets']:,} tets)", met(r[key] <= limit)))
    worst = None
    for g in grow:
        for key, name in PHASES:
            if key in g and (worst is None or g[key][1] > worst[0]):
                worst = (g[key][1], name, g)
    if worst:
        out.append((f"4× tets: ≤ {GOAL_GROWTH:g}× time in every phase",
                    f"worst ×{worst[0]:.2f} per 4× tets: {worst[1]}, {worst[2]['pair']}, {worst[2]['threads']} "
                    f"thread(s)", met(worst[0] <= GOAL_GROWTH)))
    else:
        out.append((f"4× tets: ≤ {GOAL_GROWTH:g}× time in every phase", "not measured", "–"))
    zs = next((v for v in vtk_rows if v["renderer"] == "zsweep" and v.get("status") == 0), None)
    ray = next((v for v in vtk_rows if v["renderer"] == "vtk-raycast" and v.get("status") == 0), None)
    goal = f"later frames ≥ {GOAL_VS_VTK}× faster than VTK's ray caster's (after its first), 10 M tets"
    if zs and ray:
        x = ray["later_frame_s"] / zs["later_frame_s"]
        on = f"{x:.2f}× ({zs['mesh']} tets, {zs['threads']} threads)"
        if abs(zs["tets"] - GOAL_VTK_TETS) < 0.05 * GOAL_VTK_TETS:
            out.append((goal, on, met(x >= GOAL_VS_VTK)))
        else:
            out.append((goal, on + ", not the 10 M mesh", "–"))
    else:
        out.append((goal, "not measured", "–"))
    big = [r for r in rows if r.get("status") == 0 and r["tets"] >= 100e6]
    if big:
        b = max(big, key=lambda r: r["tets"])
        out.append(("a mesh of ≥ 100 M tets renders", f"{b['tets']:,} tets, first frame {b['first_frame_s']:.1f} s, "
                    f"peak RSS {b['peak_rss_bytes'] / 1e9:.1f} GB", "yes"))
    else:
        tried = [r for r in rows if r["tets"] >= 100e6]
        out.append(("a mesh of ≥ 100 M tets renders", status(tried[0]) if tried else "not run",
                    "**no**" if tried else "–"))
    return out


def gb(x):
    return fmt(x / 1e9, 2) if isnum(x) else "–"


def doc_lines(a, rows, vtk_rows, meta, grow, plots_dir):
    plots_rel = os.path.relpath(plots_dir, os.path.join(ROOT, "docs"))
    out = [
        f"Measured {meta['date']} on {meta['cpu']} ({meta['cores']} cores, {meta['isa']}, "
        f"{meta['ram'] / 1e9:.1f} GB RAM, {meta['available'] / 1e9:.1f} GB available at the start), zsweep "
        f"`{meta['commit']}`: `{meta['command']}`. Grids: `zsweep mesh generate grid --cells N --jitter 0.15 "
        f"--field gaussians` as `.{a.format}`; each render one process, `--frames {a.frames}`, {a.size}², "
        "automatic camera and transfer function. Seconds; GB = 10⁹ bytes; bytes/tet = (peak RSS − the same "
        "render's on a 2³ grid) / tets; estimate = `zsweep mesh info` `render_memory.bytes_per_tet`. "
        f"CSV: `{os.path.relpath(a.csv, os.path.join(ROOT, 'docs'))}`.",
        "",
        "| mesh | tets | points | threads | generate | load | topology | per-view set-up | sweep | first frame "
        "| later frame | peak RSS (GB) | bytes/tet | estimate | status |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |",
    ]
    for r in rows:
        t = [fmt(r.get(k), 2) for k, _ in PHASES]
        out.append(f"| {r['mesh']}{' (largest)' if r.get('largest') else ''} | {r['tets']:,} | "
                   f"{fmt(r.get('points'), 0)} | {fmt(r.get('threads'), 0)} | {fmt(r.get('gen_s'), 1)} | "
                   + " | ".join(t) + f" | {gb(r.get('peak_rss_bytes'))} | {fmt(r.get('bytes_per_tet'), 0)} | "
                   f"{fmt(r.get('est_bytes_per_tet'), 0)} | {status(r)} |")
    out += ["", "First frame = load + topology + the first frame's per-view set-up and sweep; later frame = the "
            "best of the others (each a whole per-view set-up and sweep); per-view set-up and sweep: the last "
            "frame's (which also writes the PNG).", "",
            f"![time per phase]({plots_rel}/scale-time.png)", "",
            f"![peak RSS and bytes per tet]({plots_rel}/scale-memory.png)"]
    if vtk_rows:
        v0 = vtk_rows[0]
        out += ["", f"**VTK side by side** on the {v0['mesh']} grid ({v0['tets']:,} tets, `.vtu`), one scene "
                f"(orthographic, blue-white-red ramp, {a.size}²) for both; zsweep `render SCENE.json --threads "
                f"{a.vtk_threads}`, VTK 9.1's ray caster with `SetNumberOfThreads({a.vtk_threads})` and "
                f"LP_NUM_THREADS={a.vtk_threads}, " + (f"its ZSweep mapper (one thread, one frame) bounded by "
                f"{a.vtk_zsweep_timeout:g} s" if a.vtk_zsweep else "its ZSweep mapper not run") + "; each in its "
                "own process. VTK's first frame = reading the .vtu + its first Render() (which builds its caches); "
                "\"first render\" leaves the load out (zsweep: topology + first frame); second = the next Render() "
                f"of the same view; later = the best of frames 2–{a.frames} (both renderers).", "",
                "| renderer | threads | load | first frame | first render | second frame | later frame | peak RSS (GB) "
                "| status |",
                "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
        for v in vtk_rows:
            st = status(v)
            if v["renderer"] == "vtk-zsweep" and str(v.get("status", "")).startswith("timeout"):
                st = f"did not finish in {a.vtk_zsweep_timeout:g} s"
            out.append(f"| {v['renderer']} | {fmt(v.get('threads'), 0)} | {fmt(v.get('load_s'), 2)} | "
                       f"{fmt(v.get('first_frame_s'), 2)} | {fmt(v.get('first_render_s'), 2)} | "
                       f"{fmt(v.get('second_frame_s'), 2)} | {fmt(v.get('later_frame_s'), 2)} | "
                       f"{gb(v.get('peak_rss_bytes'))} | {st} |")
        zs = next((v for v in vtk_rows if v["renderer"] == "zsweep" and v.get("status") == 0), None)
        ray = next((v for v in vtk_rows if v["renderer"] == "vtk-raycast" and v.get("status") == 0), None)
        if zs and ray:
            out += ["", f"zsweep's later frame vs VTK's ray caster's (best of frames 2–{a.frames} each): "
                    f"**{ray['later_frame_s'] / zs['later_frame_s']:.2f}×**; images (`zsweep compare --rgb`, "
                    f"informative: VTK samples along rays): max abs {fmt(ray.get('max_abs_vs_zsweep'), 3)}, "
                    f"RMSE {fmt(ray.get('rmse_vs_zsweep'), 4)}."]
    if grow:
        out += ["", "**Growth between consecutive meshes**: time ratio, and in parentheses the ratio normalised "
                "to 4× tets (ratio^(ln 4 / ln q), q the tets ratio).", "",
                "| threads | meshes | tets | " + " | ".join(n for _, n in PHASES) + " |",
                "| ---: | --- | ---: |" + " ---: |" * len(PHASES)]
        for g in grow:
            cells = [f"×{g[k][0]:.2f} (×{g[k][1]:.2f})" if k in g else "–" for k, _ in PHASES]
            out.append(f"| {g['threads']} | {g['pair']} | ×{g['q']:.2f} | " + " | ".join(cells) + " |")
    out += ["", "**Issue 41's goals**", "", "| goal | measured | met |", "| --- | --- | :---: |"]
    out += [f"| {g} | {m} | {ok} |" for g, m, ok in goals(rows, vtk_rows, grow)]
    return out


def report(a, rows, vtk_rows, meta):
    """The CSV, the plots and (without --no-doc) the docs/scaling.md section."""
    if rows or vtk_rows:
        write_csv(a.csv, all_cols(rows + vtk_rows))
    d = a.plots or (os.path.dirname(os.path.abspath(a.csv)) if a.no_doc else os.path.join(ROOT, "docs", "bench"))
    for p in plots(rows, d, a.size):
        print("wrote", p)
    grow = growth(rows)
    for g, m, ok in goals(rows, vtk_rows, grow):
        print(f"goal: {g}: {m} [{ok.strip('*')}]")
    if not a.no_doc:
        replace_block(os.path.join(ROOT, "docs", "scaling.md"), "bench-scale",
                      doc_lines(a, rows, vtk_rows, meta, grow, d), "## Scaling with mesh size")
