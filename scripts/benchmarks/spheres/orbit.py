"""zsweep's sphere renderer on the test sets C1-C4: an orbit of frames with
culling ("optimized") and without (--no-culling, "basic"), interleaved, and
side by side, one thread each, VTK's sphere impostor mapper
(vtkOpenGLSphereMapper on Mesa llvmpipe, LP_NUM_THREADS=1) and the Embree
reference (`zsweep reference`, primary rays).

Run through scripts/bench spheres (alias scripts/bench-spheres; it picks a
python with numpy and matplotlib, and a virtual X display when --vtk is given).

Timing discipline:
- ours: one process per frame and mode (each orbit frame has its own camera),
  `render --frames R`, best of the R whole frames (setup, visibility, binning,
  tiles; the set's loading and the grid, built once per set, are not in it);
- VTK: one worker process per set, kept alive over the orbit and fed one
  camera at a time, so its frames interleave with ours; each frame is the best
  of R Render() + WaitForCompletion() calls after a warm-up frame (which
  compiles the shaders and uploads the points); the worker is bounded by
  --vtk-timeout (load + warm-up) and --vtk-frame-timeout (per frame);
- Embree: `zsweep reference` is run on the set file, so it frames the set
  itself: it is timed on its own automatic perspective camera, and ours is
  rendered on that same camera (written into a scene) for the comparison; the
  two images are compared to show the cameras agree.
"""
import json
import os
import re
import subprocess
import sys
import time

from ..lib.common import ROOT, ZSWEEP, all_cols, copy_to_docs, fmt, replace_block, write_csv
from ..lib.sphere_sets import QUICK, auto_camera, bounds, compare, ensure_set, orbit, scene
from ..lib.sphere_vtk import VtkProcess, vtk_worker
from ..lib.spheres_cli import parse, sets_and_counts
from .orbit_report import doc_lines, plots, replot, summarize


def run_ours(scene_path, out, threads, basic, repeat, budget):
    stats = out + ".stats.json"
    cmd = [ZSWEEP, "render", scene_path, "-o", out, "--threads", str(threads), "--frames", str(repeat),
           "--stats", stats, "--memory-budget", str(budget)]
    if basic:
        cmd.append("--no-culling")
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    row = {"exit_status": p.returncode, "process_s": round(wall, 3)}
    if p.returncode != 0:
        sys.stderr.write(f"zsweep failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}\n")
        return row
    with open(stats) as f:
        j = json.load(f)
    t = j["time_ms"]
    cul = j.get("culling", {})
    row.update({
        "ms": t["total"], "setup_ms": t.get("setup"), "visibility_ms": t.get("visibility"),
        "view_culling_ms": t.get("view_culling"), "occlusion_culling_ms": t.get("occlusion_culling"),
        "pyramid_ms": t.get("pyramid"), "binning_ms": t.get("binning"),
        "tiles_ms": t["total"] - t.get("setup", 0.0),
        "grid_ms": t.get("grid"), "load_ms": t.get("load"),
        "cells_view_culled": cul.get("cells_view_culled"), "cells_occluded": cul.get("cells_occluded"),
        "spheres_view_culled": cul.get("spheres_view_culled"),
        "spheres_in_occluded_cells": cul.get("spheres_in_occluded_cells"),
        "spheres_pyramid_culled": cul.get("spheres_pyramid_culled"),
        "spheres_pixel_culled": cul.get("spheres_pixel_culled"),
        "spheres_offscreen": cul.get("spheres_offscreen"),
        "spheres_visible": cul.get("spheres_visible"),
        "fragments": j.get("fragments"), "rendered_pixels": j.get("rendered_pixels"),
        "fragments_early_rejected": j.get("fragments_early_rejected"),
        "peak_rss_mb": round(j.get("peak_rss_bytes", 0) / 2**20, 1),
        "frame_ms": " ".join(f"{x:.1f}" for x in j.get("frame_ms", [t["total"]])),
    })
    return row


def run_embree(path, size, out):
    cmd = [ZSWEEP, "reference", path, "-o", out, "--width", str(size), "--height", str(size),
           "--threads", "1", "--projection", "perspective"]
    t0 = time.perf_counter()
    p = subprocess.run(["/usr/bin/time", "-f", "MAXRSS %M"] + cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        return {"error": f"exit {p.returncode}: {p.stderr.strip()[-200:]}"}
    m = re.search(r"BVH ([0-9.]+) ms, trace ([0-9.]+) ms", p.stdout)
    rss = re.search(r"MAXRSS (\d+)", p.stderr)
    return {"bvh_ms": float(m.group(1)), "trace_ms": float(m.group(2)), "process_s": wall,
            "peak_rss_mb": round(int(rss.group(1)) / 1024, 1) if rss else float("nan")}


def main(argv):
    a, ap = parse(argv)
    if a.vtk_worker:
        return vtk_worker(a.vtk_worker, a.size, a.repeat, a.vtk_translucent)
    if a.replot:
        return replot(a.replot, a.doc)
    size = a.size or (256 if a.quick else 1024)
    nframes = a.frames or (3 if a.quick else 4)
    repeat = a.repeat or 1
    sets, counts = sets_and_counts(a, ap, QUICK)
    threads = sorted({1} | {int(t) for t in (a.threads or ("1" if a.quick else "1,2")).split(",")})
    os.makedirs(a.out, exist_ok=True)
    img = os.path.join(a.out, "images")
    os.makedirs(img, exist_ok=True)
    started = time.perf_counter()
    rows, summary = [], []
    for name, count in zip(sets, counts):
        path = ensure_set(a.out, name, count)
        lo, hi = bounds(path)
        cams = orbit(lo, hi, nframes)
        vtkp = VtkProcess(path, size, repeat, a.vtk_timeout, a.vtk_frame_timeout, a.vtk_budget) if a.vtk else None
        set_rows = []
        vtk_warm = {}
        if vtkp:  # load, shaders and upload before our frames, not while they run
            vtk_warm = vtkp.frame(dict(cams[0], _warmup=True))
            print(f"{name}: VTK " + (f"loaded in {vtk_warm['load_s']:.1f} s, warm-up frame {vtk_warm['warmup_s']:.1f} s"
                                     if "error" not in vtk_warm else vtk_warm["error"]), flush=True)
        for k, cam in enumerate(cams):
            sp = os.path.join(a.out, f"{name}-{count}-f{k:03d}.json")
            with open(sp, "w") as f:
                json.dump(scene(path, cam, size, a.memory_budget), f, indent=1)
            base = os.path.join(img, f"{name}-f{k:03d}")
            # Interleaved: the order of basic and optimized alternates frame by frame.
            order = [True, False] if k % 2 == 0 else [False, True]
            res = {}
            for basic in order:
                res[(basic, 1)] = run_ours(sp, f"{base}-{'basic' if basic else 'opt'}-t1.exr", 1, basic, repeat,
                                           a.memory_budget)
            for t in threads[1:]:
                res[(False, t)] = run_ours(sp, f"{base}-opt-t{t}.exr", t, False, repeat, a.memory_budget)
            common = {"set": name, "spheres": count, "size": size, "frame": k,
                      "angle_deg": round(cam["_angle_deg"], 1), "distance_rel": round(cam["_distance_rel"], 3)}
            for (basic, t), r in res.items():
                row = dict(common, renderer="zsweep-basic" if basic else "zsweep-optimized", threads=t)
                row.update(r)
                if not basic:
                    m, rmse = compare(f"{base}-opt-t{t}.exr", f"{base}-basic-t1.exr")
                    row["max_abs_vs_basic"] = m
                    row["same_as_basic"] = "yes" if m == 0 else "NO"
                else:
                    row["max_abs_vs_basic"] = 0.0
                    row["same_as_basic"] = "yes"
                set_rows.append(row)
            if vtkp:
                c = dict(cam)
                if k == 0 or k == nframes // 2:
                    c["_png"] = f"{base}-vtk.png"
                v = vtkp.frame(c)
                row = dict(common, renderer="vtk", threads=1)
                if "error" in v:
                    row.update({"exit_status": v["error"]})
                else:
                    row.update({"ms": v["ms"], "peak_rss_mb": v["peak_rss_mb"], "exit_status": 0,
                                "rendered_pixels": v.get("pixels_hit", "")})
                    if k == 0 and "warmup_s" in vtk_warm:
                        row["setup_ms"] = vtk_warm["warmup_s"] * 1000
                        row["load_ms"] = vtk_warm["load_s"] * 1000
                set_rows.append(row)
            o, b = res[(False, 1)], res[(True, 1)]
            line = (f"{name} frame {k:2d}/{nframes} d={cam['_distance_rel']:.2f}: basic {fmt(b.get('ms'))} ms, "
                    f"optimized {fmt(o.get('ms'))} ms" +
                    "".join(f", {t} threads {fmt(res[(False, t)].get('ms'))} ms" for t in threads[1:]) +
                    f", same image: {set_rows[-2 if vtkp else -1]['same_as_basic']}")
            if vtkp:
                line += f", VTK {fmt(set_rows[-1].get('ms'))} ms" if "ms" in set_rows[-1] else \
                    f", VTK: {set_rows[-1]['exit_status']}"
            print(line, flush=True)
        if vtkp:
            vtkp.close()
        # Embree on its automatic camera, and ours on the same camera.
        emb = {}
        if a.embree:
            e = run_embree(path, size, os.path.join(img, f"{name}-embree.exr"))
            cam = auto_camera(lo, hi, size, size)
            sp = os.path.join(a.out, f"{name}-{count}-auto.json")
            with open(sp, "w") as f:
                json.dump(scene(path, cam, size, a.memory_budget), f, indent=1)
            ours = run_ours(sp, os.path.join(img, f"{name}-auto-opt.exr"), 1, False, repeat, a.memory_budget)
            common = {"set": name, "spheres": count, "size": size, "frame": "auto", "angle_deg": 0.0,
                      "distance_rel": 1.0}
            row = dict(common, renderer="embree", threads=1)
            if "error" in e:
                row["exit_status"] = e["error"]
            else:
                m, rmse = compare(os.path.join(img, f"{name}-auto-opt.exr"), os.path.join(img, f"{name}-embree.exr"))
                row.update({"ms": e["trace_ms"], "setup_ms": e["bvh_ms"], "peak_rss_mb": e["peak_rss_mb"],
                            "exit_status": 0, "max_abs_vs_ours": m, "rmse_vs_ours": rmse})
                emb = dict(e, ours_ms=ours.get("ms"), max_abs=m, rmse=rmse)
            set_rows.append(row)
            set_rows.append(dict(common, renderer="zsweep-optimized", threads=1, **ours))
            print(f"{name} Embree (auto camera): BVH {fmt(e.get('bvh_ms'))} ms, trace {fmt(e.get('trace_ms'))} ms; "
                  f"ours optimized {fmt(ours.get('ms'))} ms; images: max abs {fmt(emb.get('max_abs'), 3)}, "
                  f"RMSE {fmt(emb.get('rmse'), 4)}", flush=True)
        rows += set_rows
        summary.append(summarize(name, count, size, set_rows, threads, emb, a.vtk))
        # After every set: a run cut short keeps the sets it finished.
        write_csv(os.path.join(a.out, "spheres-frames.csv"), all_cols(rows))
        write_csv(os.path.join(a.out, "spheres-summary.csv"), all_cols(summary))
    files = plots(rows, summary, a.out, "spheres-")
    wall = time.perf_counter() - started
    lines = doc_lines(summary, a, size, nframes, repeat, threads, wall)
    with open(os.path.join(a.out, "results.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    print(f"wrote {a.out}/spheres-frames.csv, spheres-summary.csv, results.md, " +
          ", ".join(os.path.basename(f) for f in files))
    if a.doc:
        copy_to_docs(files + [os.path.join(a.out, "spheres-summary.csv"), os.path.join(a.out, "spheres-frames.csv")])
        replace_block(os.path.join(ROOT, "docs", "spheres-bench.md"), "bench-spheres", lines, "## Results")
    bad = [r for r in rows if r.get("same_as_basic") == "NO"]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
