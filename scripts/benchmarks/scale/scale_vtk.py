"""VTK side by side in `scripts/bench scale`, on one grid (--vtk-tets, 10 M by
default) as .vtu: one scene (lib/volume.scene_for: orthographic camera,
blue-white-red ramp, --size²) given to zsweep (`zsweep render SCENE.json
--threads T --frames F --stats`) and to VTK 9.1's
vtkUnstructuredGridVolumeRayCastMapper (SetNumberOfThreads(T), LP_NUM_THREADS=T)
and vtkUnstructuredGridVolumeZSweepMapper (single-threaded; bounded by
--vtk-zsweep-timeout), each VTK mapper in its own worker process
(scale_vtk_worker.py) so its peak RSS is its own. VTK's first frame (with its
cache build) and frames 2..--frames (the second, and the best of them, as
zsweep's later frame) are timed apart. zsweep's and the ray caster's
images are compared (`zsweep compare --rgb`: informative only)."""
import json
import os
import sys

from ..lib.common import ZSWEEP, worker_env
from ..lib.volume import scene_for
from .scale_runs import budget_mib, cells_for, generate, label, mesh_info, render, tets_of, timed, too_big


def vtu_for(a, work, keep_path=None):
    """The .vtu of the --vtk-tets grid: `keep_path` when the main runs left
    it, else generated here (the generator is deterministic: the same cells
    and seed give the same mesh in any format). (path, gen columns, or the
    reason it was not made)."""
    n = cells_for(a.vtk_tets)
    path = keep_path or os.path.join(work, f"grid-{n}.vtu")
    if os.path.exists(path):
        return path, {}, None
    why = too_big(n, work)
    if why:
        return None, {}, why
    g = generate(n, path, a.timeout)
    return (path, g, None) if g["gen_status"] == 0 else (None, g, f"generation failed: {g.get('gen_error', '')}")


def worker(a, vtu, scene_path, mapper, frames, out, timeout):
    """One VTK worker's row: status, error, load, first frame (load + first
    Render()), first render, second frame, later frame (the best of frames
    2..F, as zsweep's), peak RSS (/usr/bin/time's, else the worker's VmHWM)."""
    job = {"vtu": vtu, "scene": scene_path, "mapper": mapper, "threads": a.vtk_threads, "frames": frames,
           "out": out}
    env = worker_env(LP_NUM_THREADS=str(a.vtk_threads), OMP_NUM_THREADS=str(a.vtk_threads))
    row, stdout = timed([sys.executable, "-m", "benchmarks.scale.scale_vtk_worker", json.dumps(job)], timeout, env)
    r = {"status": row["exit_status"], "error": row.get("error", ""), "process_s": row["wall_s"],
         "peak_rss_bytes": row.get("peak_rss_bytes")}
    lines = stdout.strip().splitlines()
    if row["exit_status"] == 0 and lines:
        w = json.loads(lines[-1])
        # As zsweep's: first frame = load + the first Render() (VTK's cache
        # build is in it); first_render_s without the load.
        later = w["later_s"] or [float("nan")]
        r.update(load_s=w["load_s"], first_render_s=w["first_s"], first_frame_s=w["load_s"] + w["first_s"],
                 second_frame_s=later[0], later_frame_s=min(later))
        r["peak_rss_bytes"] = r["peak_rss_bytes"] or int(w["peak_rss_mb"] * 2**20)
    return r


def compare(a_img, b_img):
    """`zsweep compare A B --rgb --json`: (max_abs, rmse), or NaNs."""
    row, out = timed([ZSWEEP, "compare", a_img, b_img, "--rgb", "--json"], 120)
    if row["exit_status"] != 0:
        return float("nan"), float("nan")
    c = json.loads(out)
    return c.get("max_abs", float("nan")), c.get("rmse", float("nan"))


def vtk_side(a, work, keep_path=None):
    """The rows: zsweep on the scene, VTK's ray caster, VTK's ZSweep mapper
    (renderer column), each with the mesh's tets and points."""
    n = cells_for(a.vtk_tets)
    base = {"mesh": label(tets_of(n)), "cells": n, "tets": tets_of(n), "threads": a.vtk_threads}
    vtu, gen, why = vtu_for(a, work, keep_path)
    if not vtu:
        print(f"VTK side by side on {base['mesh']}: skipped ({why})", flush=True)
        return [dict(base, renderer="vtk-raycast", status=f"skipped: {why}", **gen)]
    info = mesh_info(vtu, a.timeout)
    if info is None:
        print(f"VTK side by side on {base['mesh']}: skipped (zsweep mesh info failed)", flush=True)
        return [dict(base, renderer="vtk-raycast", status="skipped: zsweep mesh info failed", **gen)]
    base["points"] = info["points"]
    scene_path = os.path.join(work, "vtk-scene.json")
    with open(scene_path, "w") as f:
        json.dump(scene_for(info, vtu, a.size, "span"), f)
    rows = []
    z = render(scene_path, a.vtk_threads, a, work, "vtk-zsweep-scene", budget_mib(a))
    if z["status"] == 0:
        z["first_render_s"] = z["first_frame_s"] - z["load_s"]
    rows.append(dict(base, renderer="zsweep", **gen, **{k: v for k, v in z.items() if k != "image"}))
    show(rows[-1])
    ray_png = os.path.join(work, "vtk-raycast.png")
    r = worker(a, vtu, scene_path, "raycast", a.frames, ray_png, a.timeout)
    if r["status"] == 0 and z["status"] == 0:
        r["max_abs_vs_zsweep"], r["rmse_vs_zsweep"] = compare(z["image"], ray_png)
    rows.append(dict(base, renderer="vtk-raycast", **r))
    show(rows[-1])
    if a.vtk_zsweep:
        r = worker(a, vtu, scene_path, "zsweep", 1, os.path.join(work, "vtk-zsweep.png"), a.vtk_zsweep_timeout)
        rows.append(dict(base, renderer="vtk-zsweep", threads=1, **r))
        show(rows[-1])
    return rows


def show(r):
    if r["status"] != 0:
        print(f"{r['mesh']:>9s} {r['renderer']:12s}: {r['status']} {r.get('error', '')}", flush=True)
        return
    later = f", later {r['later_frame_s']:.2f} s" if r["later_frame_s"] == r["later_frame_s"] else ""
    print(f"{r['mesh']:>9s} {r['renderer']:12s} {r['threads']} thread(s): first frame {r['first_frame_s']:.2f} s"
          f"{later}, peak RSS {r['peak_rss_bytes'] / 1e9:.2f} GB", flush=True)
