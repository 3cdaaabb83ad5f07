"""`scripts/bench shadows` side by side at map 2048: VTK's vtkShadowMapPass
(the worker shadow_vtk.py under xvfb-run, LP_NUM_THREADS=1), ours 1-SM+PCF1/4/9
and 2-SM+PCF4, and the Embree exact mode, on the same scenes and images."""
import json
import os
import shutil
import subprocess

from ..lib.common import worker_env
from .shadow_metrics import darker_pixels
from .shadow_runs import log, render, render_best, shadows_block, stats_row
from .shadow_scenes import scene_json, vtk_job


def vtk_available():
    if not shutil.which("xvfb-run"):
        return "xvfb-run is missing (apt-get install xvfb)"
    r = subprocess.run(["/usr/bin/python3", "-c", "import vtk"], capture_output=True)
    if r.returncode != 0:
        return "/usr/bin/python3 has no vtk (python3-vtk9)"
    return ""


def vs_vtk(a, scenes):
    why = "--no-vtk" + (" (implied by --quick)" if a.quick else "") if a.no_vtk else vtk_available()
    rows = []
    if why:
        log(f"VTK side by side skipped: {why}")
        return rows, why
    for name, s, w in [(n, sc, int(z)) for z in str(a.vtk_size).split(",") for n, sc in scenes.items()]:
        h = w
        base = {"scene": name, "width": w, "height": h, "map_size": a.vtk_map}
        job = vtk_job(s, w, h, a.vtk_map, a.vtk_repeat, os.path.join(a.out, f"vtk-{name}-{w}.png"))
        jp = os.path.join(a.out, "scenes", f"vtk-{name}-{w}.json")
        with open(jp, "w") as f:
            json.dump(job, f, indent=1)
        env = worker_env(LP_NUM_THREADS="1")
        cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "/usr/bin/python3", "-m",
               "benchmarks.shadows.shadow_vtk", jp]
        vt = None
        try:
            r = subprocess.run(cmd, capture_output=True, text=True, timeout=a.timeout, env=env)
            if r.returncode == 0:
                vt = json.loads(r.stdout.strip().splitlines()[-1])
            else:
                log(f"  VTK on {name} failed (exit {r.returncode}): {r.stderr.strip()[-300:]}")
        except subprocess.TimeoutExpired:
            log(f"  VTK on {name}: more than {a.timeout:.0f} s")
        # Timed with PNG output: RGBA frames, as VTK's; an EXR frame (Z and
        # lit channels too) gives the darkened pixels and its own time.
        plain, ppng = render_best(a, f"vtk-{name}-{w}-noshadow", scene_json(s, w, h, False), a.ours_repeat,
                                  a.rounds, ext="png")
        os.remove(ppng)
        plain_ms = stats_row(plain)["time_ms"]
        _, pexr = render(a, f"vtk-{name}-{w}-noshadow", scene_json(s, w, h, False))
        ours = []
        for label, d, sel, k in [("1-SM+PCF1", 1, None, 1), ("1-SM+PCF4", 1, None, 4), ("1-SM+PCF9", 1, None, 9),
                                 ("2-SM(max)+PCF4", 2, "max", 4), ("exact", 0, None, 0)]:
            sh = shadows_block("exact") if d == 0 else shadows_block("map", a.vtk_map, d, sel, k)
            st, png = render_best(a, f"vtk-{name}-{w}-{label}", scene_json(s, w, h, sh), a.ours_repeat, a.rounds,
                                  ext="png")
            os.remove(png)
            sx, exr = render(a, f"vtk-{name}-{w}-{label}", scene_json(s, w, h, sh), a.ours_repeat)
            sr = stats_row(st)
            ours.append(dict(base, renderer="zsweep" if d else "zsweep (Embree exact)", config=label,
                             frame_ms=sr["time_ms"], frame_cached_ms="", frame_plain_ms=plain_ms,
                             frame_exr_ms=stats_row(sx)["time_ms"],
                             shadow_part_ms=round(sr["time_ms"] - plain_ms, 3), runs=a.ours_repeat * a.rounds,
                             peak_rss_mb=sr["peak_rss_mb"], darker_pixels=darker_pixels(exr, pexr),
                             pixels=w * h, triangles=st["triangles"]["total"]))
            os.remove(exr)
            log(f"  {name} {label} {w}²: {sr['time_ms']:.1f} ms")
        os.remove(pexr)
        exact_dark = ours[-1]["darker_pixels"]
        if vt:
            rows.append(dict(base, renderer="VTK vtkShadowMapPass", config="1 map, VTK's PCF",
                             frame_ms=vt["frame_ms"], frame_cached_ms=vt["frame_cached_ms"], frame_exr_ms="",
                             frame_plain_ms=vt["frame_plain_ms"],
                             shadow_part_ms=round(vt["frame_ms"] - vt["frame_plain_ms"], 3), runs=len(vt["frames_ms"]),
                             peak_rss_mb=round(vt["peak_rss_mb"] or 0, 1),
                             darker_pixels=vt["shadow_check"]["darker_pixels"], pixels=w * h,
                             triangles=vt["triangles"]))
            log(f"  {name} VTK {w}²: {vt['frame_ms']:.1f} ms (cached map {vt['frame_cached_ms']:.1f} ms)")
        rows += ours
        for r in rows:
            if r["scene"] == name and r["width"] == w:
                r["darker_vs_exact"] = round(r["darker_pixels"] / exact_dark, 3) if exact_dark else ""
    return rows, ""
