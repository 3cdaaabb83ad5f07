"""zsweep's sphere renderer on the test sets C1-C4: an orbit of frames with
culling ("optimized") and without (--no-culling, "basic"), interleaved, and
side by side, one thread each, VTK's sphere impostor mapper
(vtkOpenGLSphereMapper on Mesa llvmpipe, LP_NUM_THREADS=1) and the Embree
reference (`zsweep reference`, primary rays).

Run through scripts/bench-spheres (it picks a python with numpy and
matplotlib, and a virtual X display when --vtk is given).

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
import argparse
import datetime
import json
import math
import os
import re
import select
import shutil
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_common import cpu_name, cpu_vector_isa, replace_block, write_csv  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ZSWEEP = os.environ.get("ZSWEEP", os.path.join(ROOT, "build", "src", "zsweep"))
FULL = {"c1": 1_000_000, "c2": 2_463_048, "c3": 8_000_000, "c4": 27_000_000}
QUICK = {"c1": 20_000, "c2": 20_000, "c3": 20_000, "c4": 27_000}
FOV_Y = 30.0


# ---------------------------------------------------------------- the sets

def read_sphb(path):
    """(xyz float32 N×3, r float32 N, rgba uint8 N×4 or None) from a .sphb."""
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"ZSSPHB1\n":
        raise ValueError(f"{path}: not a .sphb")
    fields, _reserved = np.frombuffer(head[8:16], "<u4")
    count = int(np.frombuffer(head[16:24], "<u8")[0])
    a = np.memmap(path, dtype="<f4", mode="r", offset=24, shape=(count, int(fields)))
    xyz, r = a[:, 0:3], a[:, 3]
    rgba = None
    if fields == 8:
        rgba = (np.clip(a[:, 4:8], 0, 1) * 255 + 0.5).astype(np.uint8)
    return xyz, r, rgba


def bounds(path):
    """Bounding box of the drawable spheres, as zsweep's automatic camera
    computes it (double: c ± r)."""
    xyz, r, _ = read_sphb(path)
    ok = np.isfinite(r) & (r > 0) & np.isfinite(xyz).all(axis=1)
    lo = hi = None
    step = 4_000_000  # chunks: C4 is 27 M spheres
    for i in range(0, len(r), step):
        c = xyz[i:i + step].astype(np.float64)
        rr = r[i:i + step].astype(np.float64)[:, None]
        m = ok[i:i + step]
        l, h = (c - rr)[m].min(axis=0), (c + rr)[m].max(axis=0)
        lo = l if lo is None else np.minimum(lo, l)
        hi = h if hi is None else np.maximum(hi, h)
    return lo, hi


def auto_camera(lo, hi, w, h):
    """zsweep reference's automatic perspective camera (reference_cmd.cpp)."""
    c = 0.5 * (lo + hi)
    e = hi - lo
    aspect = w / h
    diag = max(float(np.linalg.norm(e)), 1e-300)
    half = math.atan(math.tan(FOV_Y * math.pi / 360.0) * min(1.0, aspect))
    return {"projection": "perspective", "eye": [float(c[0]), float(c[1]), float(c[2] + 0.55 * diag / math.sin(half))],
            "target": [float(x) for x in c], "up": [0.0, 1.0, 0.0], "fov_y": FOV_Y,
            "height": float(1.05 * max(e[1], e[0] / aspect))}


def orbit(lo, hi, frames):
    """The thesis's orbit: the camera goes once around the set (about y, a
    little above it), starting where it sees the whole set, moving in to 0.3
    of that distance at the middle of the orbit, then back out."""
    c = 0.5 * (lo + hi)
    diag = float(np.linalg.norm(hi - lo))
    far = 0.55 * diag / math.sin(math.radians(FOV_Y / 2))
    cams = []
    for k in range(frames):
        u = k / max(frames - 1, 1)
        theta = 2 * math.pi * k / frames
        d = far * (1 - 0.7 * math.sin(math.pi * u))
        elev = math.radians(20)
        eye = c + d * np.array([math.cos(elev) * math.sin(theta), math.sin(elev), math.cos(elev) * math.cos(theta)])
        cams.append({"projection": "perspective", "eye": [float(x) for x in eye], "target": [float(x) for x in c],
                     "up": [0.0, 1.0, 0.0], "fov_y": FOV_Y, "height": diag,
                     "_angle_deg": math.degrees(theta), "_distance": d, "_distance_rel": d / far})
    return cams


def scene(path, cam, size, budget):
    return {"spheres": {"path": os.path.abspath(path), "radius_scale": 1},
            "image": {"width": size, "height": size, "background": [0, 0, 0, 0]},
            "camera": {k: v for k, v in cam.items() if not k.startswith("_")},
            "render": {"mode": "opaque", "culling": True, "memory_budget_mb": budget}}


# ---------------------------------------------------------------- ours

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


def compare(a, b, *extra):
    p = subprocess.run([ZSWEEP, "compare", a, b, "--json", *extra], capture_output=True, text=True)
    if p.returncode != 0:
        return float("nan"), float("nan")
    j = json.loads(p.stdout)
    return j["max_abs"], j.get("rmse", float("nan"))


# ---------------------------------------------------------------- VTK

def vtk_worker(path, size, repeat, translucent=False):
    """Reads cameras (one JSON line each) on stdin, renders the set with
    vtkOpenGLSphereMapper, answers one JSON line per camera. `translucent`
    (bench_spheres_translucent.py): the RGBA scalars' alpha makes the actor
    translucent, drawn with depth peeling (32 peels, occlusion ratio 0)."""
    import vtk
    from vtk.util import numpy_support as ns
    vtk.vtkObject.GlobalWarningDisplayOff()
    t0 = time.perf_counter()
    xyz, r, rgba = read_sphb(path)
    pts = vtk.vtkPoints()
    pts.SetData(ns.numpy_to_vtk(np.ascontiguousarray(xyz, dtype=np.float32), deep=True))
    pd = vtk.vtkPolyData()
    pd.SetPoints(pts)
    # One vertex cell per sphere: the mapper draws cells (points alone draw nothing).
    n = len(r)
    verts = vtk.vtkCellArray()
    verts.SetData(ns.numpy_to_vtkIdTypeArray(np.arange(n + 1, dtype=np.int64), deep=True),
                  ns.numpy_to_vtkIdTypeArray(np.arange(n, dtype=np.int64), deep=True))
    pd.SetVerts(verts)
    rad = ns.numpy_to_vtk(np.ascontiguousarray(r, dtype=np.float32), deep=True)
    rad.SetName("radius")
    pd.GetPointData().AddArray(rad)
    if rgba is not None:
        col = ns.numpy_to_vtk(np.ascontiguousarray(rgba), deep=True, array_type=vtk.VTK_UNSIGNED_CHAR)
        col.SetName("rgba")
        pd.GetPointData().SetScalars(col)
    del xyz, r, rgba
    mapper = vtk.vtkOpenGLSphereMapper()
    mapper.SetInputData(pd)
    mapper.SetScaleArray("radius")
    mapper.SetColorModeToDirectScalars()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    ren = vtk.vtkRenderer()
    ren.AddActor(actor)
    ren.SetBackground(0, 0, 0)
    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    if translucent:
        ren.SetUseDepthPeeling(1)
        ren.SetMaximumNumberOfPeels(32)
        ren.SetOcclusionRatio(0.0)
        win.SetAlphaBitPlanes(1)
        win.SetMultiSamples(0)
    win.AddRenderer(ren)
    win.SetSize(size, size)
    load_s = time.perf_counter() - t0
    # On stderr too, so a frame that times out still tells its load time apart.
    print(f"vtk worker: loaded in {load_s:.1f} s", file=sys.stderr, flush=True)
    cam = ren.GetActiveCamera()

    def set_camera(c):
        cam.SetPosition(*c["eye"])
        cam.SetFocalPoint(*c["target"])
        cam.SetViewUp(*c["up"])
        cam.SetViewAngle(c["fov_y"])
        ren.ResetCameraClippingRange()

    first = True
    for line in sys.stdin:
        c = json.loads(line)
        set_camera(c)
        out = {}
        if first:  # shaders, VBO upload
            t = time.perf_counter()
            win.Render()
            win.WaitForCompletion()
            out["warmup_s"] = time.perf_counter() - t
            out["load_s"] = load_s
            out["peak_rss_mb"] = peak_rss_mb()
            first = False
            if c.get("_warmup"):
                sys.stdout.write(json.dumps(out) + "\n")
                sys.stdout.flush()
                continue
        best = float("inf")
        for _ in range(repeat):
            t = time.perf_counter()
            win.Render()
            win.WaitForCompletion()
            best = min(best, time.perf_counter() - t)
            if best > 2.0:  # slow frames (C4): one is enough
                break
        out["ms"] = best * 1000
        if c.get("_png"):
            grab = vtk.vtkWindowToImageFilter()
            grab.SetInput(win)
            grab.ReadFrontBufferOff()
            grab.Update()
            px = ns.vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars())
            out["pixels_hit"] = int((px[:, :3].max(axis=1) > 0).sum())
            w = vtk.vtkPNGWriter()
            w.SetFileName(c["_png"])
            w.SetInputConnection(grab.GetOutputPort())
            w.Write()
        if translucent:
            out["depth_peeling"] = ren.GetLastRenderingUsedDepthPeeling()
            out["translucent_actor"] = actor.HasTranslucentPolygonalGeometry()
            if c.get("_png") and pd.GetPointData().GetScalars() is not None:
                out["peak_rss_mb"] = peak_rss_mb()  # before the check's second upload
                from bench_spheres_translucent import vtk_opaque_check
                out.update(vtk_opaque_check(vtk, ns, win, ren, actor, pd, px, c["_png"]))
        out.setdefault("peak_rss_mb", peak_rss_mb())
        sys.stdout.write(json.dumps(out) + "\n")
        sys.stdout.flush()


def peak_rss_mb():
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM"):
                    return round(int(line.split()[1]) / 1024, 1)
    except OSError:
        pass
    return float("nan")


class VtkProcess:
    """The VTK worker of one set; `frame(cam)` returns its answer, or a dict
    with 'error' once it died or timed out (then it is not asked again)."""

    def __init__(self, path, size, repeat, first_timeout, frame_timeout, budget, extra=()):
        self.spent, self.budget = 0.0, budget
        env = dict(os.environ, LP_NUM_THREADS="1", OMP_NUM_THREADS="1")
        self.p = subprocess.Popen([sys.executable, os.path.abspath(__file__), "--vtk-worker", path,
                                   "--size", str(size), "--repeat", str(repeat), *extra],
                                  stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  text=True, env=env)
        self.first_timeout, self.frame_timeout = first_timeout, frame_timeout
        self.first = True
        self.error = None

    def frame(self, cam):
        if self.error:
            return {"error": self.error}
        if self.spent > self.budget:
            return {"error": f"skipped: VTK's frames of this set took over --vtk-budget {self.budget:g} s"}
        timeout = self.first_timeout if self.first else self.frame_timeout
        self.first = False
        t0 = time.perf_counter()
        if self.p.poll() is not None:  # died between frames
            self.error = f"exit {self.p.returncode}"
            return {"error": self.error}
        try:
            self.p.stdin.write(json.dumps(cam) + "\n")
            self.p.stdin.flush()
        except BrokenPipeError:
            pass
        ready, _, _ = select.select([self.p.stdout], [], [], timeout)
        line = self.p.stdout.readline() if ready else ""
        if not line:
            if not ready:
                self.error = f"timeout after {timeout:.0f} s"
            else:
                self.p.wait()
                err = self.p.stderr.read().strip().splitlines()
                self.error = f"exit {self.p.returncode}" + (f": {err[-1][:200]}" if err else "")
                if self.p.returncode == -9:
                    self.error += " (killed: out of memory?)"
            self.close()
            return {"error": self.error, "wall_s": time.perf_counter() - t0}
        if not cam.get("_warmup"):
            self.spent += time.perf_counter() - t0
        return json.loads(line)

    def close(self):
        if self.p.poll() is None:
            self.p.kill()
            self.p.wait()


# ---------------------------------------------------------------- Embree

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


# ---------------------------------------------------------------- plots

def plots(rows, summary, outdir, prefix):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
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
        fig.tight_layout()
        f = os.path.join(outdir, f"{prefix}{name}.png")
        fig.savefig(f)
        plt.close(fig)
        files.append(f)
    fig, ax = plt.subplots(figsize=(6, 3.4), dpi=80)
    keys = [("basic_ms", "basic, 1 thread"), ("optimized_ms", "optimized, 1 thread"),
            ("optimized_2t_ms", "optimized, 2 threads"), ("vtk_ms", "VTK sphere mapper, 1 thread"),
            ("embree_trace_ms", "Embree trace, 1 thread (auto camera)")]
    keys = [k for k in keys if any(isnum(s.get(k[0])) for s in summary)]
    wbar = 0.8 / max(len(keys), 1)
    for i, (k, label) in enumerate(keys):
        ys = [s.get(k) if s.get(k) is not None else float("nan") for s in summary]
        ax.bar([j + i * wbar for j in range(len(summary))], ys, wbar, label=label)
    ax.set_xticks([j + 0.4 - wbar / 2 for j in range(len(summary))])
    ax.set_xticklabels([f"{s['set'].upper()}\n{s['spheres']:,}" for s in summary], fontsize=8)
    ax.set_yscale("log")
    ax.set_ylabel("mean ms per frame over the orbit")
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    f = os.path.join(outdir, f"{prefix}mean.png")
    fig.savefig(f)
    plt.close(fig)
    files.append(f)
    return files


# ---------------------------------------------------------------- main

def parser():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sets", default=None, help="default c1,c2,c3,c4 (--ao: and 1hpv, the protein of --pdb)")
    ap.add_argument("--size", type=int, default=None, help="image width and height (default 1024; --quick 256)")
    ap.add_argument("--frames", type=int, default=None,
                    help="orbit frames (default 4; --quick 3; --translucent 1, the automatic camera)")
    ap.add_argument("--counts", default=None,
                    help="spheres per set, comma-separated in --sets order (default: full sizes; --quick: ~20 K)")
    ap.add_argument("--repeat", type=int, default=None,
                    help="whole frames per measurement, best counts (default 1; --ao 3, --quick 1)")
    ap.add_argument("--threads", default=None,
                    help="thread counts for ours (default 1,2; --quick 1); 1 is always run (basic and optimized), "
                         "the others optimized only")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench-out", "spheres"))
    ap.add_argument("--vtk", action="store_true", help="time VTK's vtkOpenGLSphereMapper (needs an X display)")
    ap.add_argument("--vtk-timeout", type=float, default=600, help="s for VTK's load + first frame per set")
    ap.add_argument("--vtk-frame-timeout", type=float, default=300, help="s per later VTK frame")
    ap.add_argument("--vtk-budget", type=float, default=420,
                    help="s of VTK frames per set (load and warm-up included); later frames are skipped")
    ap.add_argument("--embree", action="store_true", help="time the Embree reference (one view per set)")
    ap.add_argument("--memory-budget", type=float, default=None,
                    help="MiB, given to every zsweep render (default 4096; --ao 12288: 258 maps of 2048² take 4 GiB)")
    ap.add_argument("--quick", action="store_true", help="small counts, 256², 3 frames, 1 repeat")
    ap.add_argument("--doc", action="store_true",
                    help="write the tables into docs/spheres-bench.md and the plots to docs/bench/spheres-*.png")
    ap.add_argument("--replot", metavar="DIR", help="redraw the plots from DIR's CSVs (with --doc: into docs/bench)")
    ap.add_argument("--translucent", action="store_true",
                    help="the translucency benchmark instead (bench_spheres_translucent.py): modes, layers, "
                         "errors against sorted exact, VTK's depth peeling, the Embree reference")
    ap.add_argument("--translucent-sweep", choices=("small", "full"), default=None,
                    help="--translucent's error sweep over tolerance and layer cap (default full; --quick small)")
    ap.add_argument("--render-timeout", type=float, default=None,
                    help="--translucent: s per zsweep render or reference (default 900); --ao: s per zsweep render "
                         "(default 7200) (recorded as a timeout)")
    ap.add_argument("--exact-timeout", type=float, default=None,
                    help="--translucent: s for the exact renders (sorted t 0, the Embree reference), which "
                         "every error row needs (default --render-timeout)")
    ap.add_argument("--ao", action="store_true",
                    help="the ambient occlusion benchmark instead (bench_spheres_ao.py): Phong vs AO frames, map "
                         "times, AO error vs exact directions and Monte Carlo over directions x map size, VTK's "
                         "vtkSSAOPass (--vtk) and Tachyon (--tachyon) side by side")
    ap.add_argument("--error-size", type=int, default=None,
                    help="--ao: image size of the error grid and the side-by-side runs (default 512; --quick 128)")
    ap.add_argument("--directions", default=None, help="--ao: direction counts (default 6,18,66,258; --quick 6,18)")
    ap.add_argument("--map-sizes", default=None,
                    help="--ao: map sizes (default 256,512,1024,2048; --quick 64,128)")
    ap.add_argument("--table-directions", type=int, default=None,
                    help="--ao: directions of the Table 6 AO frame and the side-by-side run (default 66)")
    ap.add_argument("--table-map-size", type=int, default=None,
                    help="--ao: map size of Tables 6 and 7 (default 1024; --quick 128)")
    ap.add_argument("--grid", choices=("full", "cross"), default="full",
                    help="--ao: every directions x map size (full), or every count at --table-map-size and every "
                         "size at --table-directions (cross)")
    ap.add_argument("--ao-samples", type=int, default=None,
                    help="--ao: N; the Monte Carlo reference traces 4N rays per pixel, and a second one N rays for "
                         "its noise (default 256; --quick 64)")
    ap.add_argument("--ref-threads", type=int, default=2, help="--ao: threads of the references (not timed against us)")
    ap.add_argument("--ref-timeout", type=float, default=14400, help="--ao: s per reference")
    ap.add_argument("--reuse-references", action="store_true",
                    help="--ao: reuse the references already in --out traced from identical scenes (e.g. after a "
                         "change to the renderer only)")
    ap.add_argument("--amortise", type=float, default=100,
                    help="--ao: frames over which the maps (VTK's warm-up, Tachyon's grid) are amortised")
    ap.add_argument("--pdb", default="/usr/share/pymol/data/tut/1hpv.pdb", help="--ao: the protein set 1hpv")
    ap.add_argument("--tachyon", action="store_true", help="--ao: Tachyon's AO side by side (tachyon-bin-nox)")
    ap.add_argument("--tachyon-bin", default="tachyon", help=argparse.SUPPRESS)
    ap.add_argument("--tachyon-samples", default=None, help="--ao: Tachyon's AO sample counts (default 4,16,64,256)")
    ap.add_argument("--tachyon-timeout", type=float, default=7200, help="--ao: s per Tachyon run")
    ap.add_argument("--keep-tachyon-scene", action="store_true", help="--ao: keep the sets' Tachyon scene files")
    ap.add_argument("--ssao-radius", default="4,16,64",
                    help="--ao --vtk: vtkSSAOPass radii, in mean sphere radii (one row each; the ratios take the "
                         "most accurate)")
    ap.add_argument("--ssao-bias", type=float, default=0.05, help="--ao --vtk: vtkSSAOPass bias, in mean radii")
    ap.add_argument("--ssao-kernel", type=int, default=128, help="--ao --vtk: vtkSSAOPass kernel size")
    ap.add_argument("--vtk-worker", help=argparse.SUPPRESS)
    ap.add_argument("--vtk-translucent", action="store_true", help=argparse.SUPPRESS)
    return ap


def isnum(x):
    return isinstance(x, (int, float)) and x == x


def fmt(x, d=1):
    if x is None or x != x:
        return "–"
    return f"{x:,.{d}f}"


def main():
    ap = parser()
    a = ap.parse_args()
    if a.vtk_worker:
        return vtk_worker(a.vtk_worker, a.size, a.repeat, a.vtk_translucent)
    if a.render_timeout is None:  # AO maps of C4 take long
        a.render_timeout = 7200 if a.ao else 900
    if a.memory_budget is None:
        a.memory_budget = 12288 if a.ao else 4096
    if a.ao:
        import bench_spheres_ao
        return bench_spheres_ao.main(a, ap)
    a.sets = a.sets or "c1,c2,c3,c4"
    if a.translucent:
        import bench_spheres_translucent
        return bench_spheres_translucent.main(a, ap)
    if a.replot:
        return replot(a.replot, a.doc)
    size = a.size or (256 if a.quick else 1024)
    nframes = a.frames or (3 if a.quick else 4)
    repeat = a.repeat or 1
    sets = a.sets.split(",")
    for s in sets:
        if s not in FULL:
            ap.error(f"unknown set {s} (c1, c2, c3, c4)")
    if a.counts:
        counts = [int(float(c)) for c in a.counts.split(",")]
        if len(counts) != len(sets):
            ap.error("--counts needs one count per set")
    else:
        counts = [(QUICK if a.quick else FULL)[s] for s in sets]
    threads = sorted({1} | {int(t) for t in (a.threads or ("1" if a.quick else "1,2")).split(",")})
    os.makedirs(a.out, exist_ok=True)
    img = os.path.join(a.out, "images")
    os.makedirs(img, exist_ok=True)
    started = time.perf_counter()
    rows, summary = [], []
    for name, count in zip(sets, counts):
        path = os.path.join(a.out, f"{name}-{count}.sphb")
        if not os.path.exists(path):
            t = time.perf_counter()
            subprocess.run([ZSWEEP, "spheres", "generate", name, "--count", str(count), "-o", path],
                           check=True, capture_output=True)
            print(f"{name}: generated {count:,} spheres in {time.perf_counter() - t:.1f} s", flush=True)
        lo, hi = bounds(path)
        cams = orbit(lo, hi, nframes)
        vtkp = VtkProcess(path, size, repeat, a.vtk_timeout, a.vtk_frame_timeout,
                                                 a.vtk_budget) if a.vtk else None
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
        cols = []
        for r in rows:
            for k in r:
                if k not in cols:
                    cols.append(k)
        write_csv(os.path.join(a.out, "spheres-frames.csv"), [{k: r.get(k, "") for k in cols} for r in rows])
        scols = []
        for r in summary:
            for k in r:
                if k not in scols:
                    scols.append(k)
        write_csv(os.path.join(a.out, "spheres-summary.csv"), [{k: r.get(k, "") for k in scols} for r in summary])
    files = plots(rows, summary, a.out, "spheres-")
    wall = time.perf_counter() - started
    lines = doc_lines(summary, a, size, nframes, repeat, threads, wall)
    with open(os.path.join(a.out, "results.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    print(f"wrote {a.out}/spheres-frames.csv, spheres-summary.csv, results.md, " +
          ", ".join(os.path.basename(f) for f in files))
    if a.doc:
        os.makedirs(os.path.join(ROOT, "docs", "bench"), exist_ok=True)
        for f in files:
            shutil.copy(f, os.path.join(ROOT, "docs", "bench", os.path.basename(f)))
        shutil.copy(os.path.join(a.out, "spheres-summary.csv"), os.path.join(ROOT, "docs", "bench"))
        shutil.copy(os.path.join(a.out, "spheres-frames.csv"), os.path.join(ROOT, "docs", "bench"))
        replace_block(os.path.join(ROOT, "docs", "spheres-bench.md"), "bench-spheres", lines,
                      "## Results")
    bad = [r for r in rows if r.get("same_as_basic") == "NO"]
    return 1 if bad else 0


def replot(d, doc):
    import csv

    def num(v):
        try:
            x = float(v)
        except ValueError:
            return v
        return int(x) if x.is_integer() and "." not in v and "e" not in v else x

    def load(f):
        return [{k: num(v) for k, v in r.items()} for r in csv.DictReader(open(os.path.join(d, f)))]
    rows = load("spheres-frames.csv")
    for r in rows:  # ms is a float in the rows the run builds
        if isinstance(r.get("ms"), int):
            r["ms"] = float(r["ms"])
        if isinstance(r.get("frame"), float):
            r["frame"] = int(r["frame"])
    files = plots(rows, load("spheres-summary.csv"), d, "spheres-")
    if doc:
        for f in files:
            shutil.copy(f, os.path.join(ROOT, "docs", "bench", os.path.basename(f)))
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
    cmd = "scripts/bench-spheres " + " ".join(sys.argv[1:])
    lines = [
        f"Measured {datetime.date.today().isoformat()} on {cpu_name()} ({os.cpu_count()} cores, {cpu_vector_isa()}), "
        f"`{cmd.strip()}` ({wall / 60:.1f} min): {size}², perspective, {nframes} orbit frames, each the best of "
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


if __name__ == "__main__":
    sys.exit(main())
