"""VTK's sphere impostor mapper (vtkOpenGLSphereMapper on Mesa llvmpipe,
LP_NUM_THREADS=1) on a sphere set, for the orbit and the translucency
benchmarks: the worker process, kept alive over a set's frames and fed one
camera at a time (one JSON line each on stdin, one JSON answer each on
stdout), and VtkProcess, which runs it under time limits. Translucent: the
RGBA scalars' alpha makes the actor translucent, drawn with depth peeling (32
peels, occlusion ratio 0), and each frame with a PNG is checked against the
same frame drawn opaque.

The worker: python3 -m benchmarks.lib.sphere_vtk SET.sphb --size N --repeat R [--translucent]
(with scripts/ on PYTHONPATH and an X display)."""
import argparse
import json
import select
import subprocess
import sys
import time

import numpy as np

from .common import peak_rss_mb, worker_env
from .sphere_sets import read_sphb


def sphere_polydata(xyz, r):
    """The spheres as VTK polydata for vtkOpenGLSphereMapper: points, one
    vertex cell per sphere (the mapper draws cells; points alone draw
    nothing) and the radii as the array "radius" (its scale array)."""
    import vtk
    from vtk.util import numpy_support as ns
    pts = vtk.vtkPoints()
    pts.SetData(ns.numpy_to_vtk(np.ascontiguousarray(xyz, dtype=np.float32), deep=True))
    pd = vtk.vtkPolyData()
    pd.SetPoints(pts)
    n = len(r)
    verts = vtk.vtkCellArray()
    verts.SetData(ns.numpy_to_vtkIdTypeArray(np.arange(n + 1, dtype=np.int64), deep=True),
                  ns.numpy_to_vtkIdTypeArray(np.arange(n, dtype=np.int64), deep=True))
    pd.SetVerts(verts)
    rad = ns.numpy_to_vtk(np.ascontiguousarray(r, dtype=np.float32), deep=True)
    rad.SetName("radius")
    pd.GetPointData().AddArray(rad)
    return pd


def sphere_renderer(pd, colours):
    """A renderer (black background) with the spheres of `pd` drawn by
    vtkOpenGLSphereMapper; colours: the point scalars are the colours (else
    the actor's own colour). (actor, renderer)."""
    import vtk
    mapper = vtk.vtkOpenGLSphereMapper()
    mapper.SetInputData(pd)
    mapper.SetScaleArray("radius")
    if colours:
        mapper.SetColorModeToDirectScalars()
    else:
        mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    ren = vtk.vtkRenderer()
    ren.AddActor(actor)
    ren.SetBackground(0, 0, 0)
    return actor, ren


def set_camera(ren, c):
    """Our perspective camera `c` (eye, target, up, fov_y) on `ren`."""
    cam = ren.GetActiveCamera()
    cam.SetPosition(*c["eye"])
    cam.SetFocalPoint(*c["target"])
    cam.SetViewUp(*c["up"])
    cam.SetViewAngle(c["fov_y"])
    ren.ResetCameraClippingRange()


def vtk_worker(path, size, repeat, translucent=False):
    """Reads cameras (one JSON line each) on stdin, renders the set with
    vtkOpenGLSphereMapper, answers one JSON line per camera."""
    import vtk
    from vtk.util import numpy_support as ns
    vtk.vtkObject.GlobalWarningDisplayOff()
    t0 = time.perf_counter()
    xyz, r, rgba = read_sphb(path)
    pd = sphere_polydata(xyz, r)
    if rgba is not None:
        col = ns.numpy_to_vtk(np.ascontiguousarray(rgba), deep=True, array_type=vtk.VTK_UNSIGNED_CHAR)
        col.SetName("rgba")
        pd.GetPointData().SetScalars(col)
    del xyz, r, rgba
    actor, ren = sphere_renderer(pd, colours=True)
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

    first = True
    for line in sys.stdin:
        c = json.loads(line)
        set_camera(ren, c)
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
                out.update(vtk_opaque_check(vtk, ns, win, ren, actor, pd, px, c["_png"]))
        out.setdefault("peak_rss_mb", peak_rss_mb())
        sys.stdout.write(json.dumps(out) + "\n")
        sys.stdout.flush()


def vtk_opaque_check(vtk, ns, win, ren, actor, pd, px, png):
    """The worker's translucent frame against the same frame with every alpha
    set to 255 (no peeling then): they must differ. Untimed; the alphas are
    restored and uploaded again before the next frame."""
    col = pd.GetPointData().GetScalars()
    a = ns.vtk_to_numpy(col)
    keep = a[:, 3].copy()
    a[:, 3] = 255
    col.Modified()
    pd.Modified()
    win.Render()
    win.WaitForCompletion()
    out = {"opaque_depth_peeling": ren.GetLastRenderingUsedDepthPeeling(),
           "opaque_translucent_actor": actor.HasTranslucentPolygonalGeometry()}
    g = vtk.vtkWindowToImageFilter()
    g.SetInput(win)
    g.ReadFrontBufferOff()
    g.Update()
    q = ns.vtk_to_numpy(g.GetOutput().GetPointData().GetScalars())
    d = (px[:, :3].astype(np.float64) - q[:, :3]) / 255
    out["rmse_vs_opaque"] = float(np.sqrt((d * d).mean()))
    out["max_abs_vs_opaque"] = float(np.abs(d).max())
    w = vtk.vtkPNGWriter()
    w.SetFileName(png[:-4] + "-opaque.png")
    w.SetInputConnection(g.GetOutputPort())
    w.Write()
    a[:, 3] = keep
    col.Modified()
    pd.Modified()
    win.Render()
    win.WaitForCompletion()
    return out


class VtkProcess:
    """The VTK worker of one set; `frame(cam)` returns its answer, or a dict
    with 'error' once it died or timed out (then it is not asked again)."""

    def __init__(self, path, size, repeat, first_timeout, frame_timeout, budget, translucent=False):
        self.spent, self.budget = 0.0, budget
        env = worker_env(LP_NUM_THREADS="1", OMP_NUM_THREADS="1")
        self.p = subprocess.Popen([sys.executable, "-m", "benchmarks.lib.sphere_vtk", path, "--size", str(size),
                                   "--repeat", str(repeat)] + (["--translucent"] if translucent else []),
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


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description="the VTK sphere worker (started by VtkProcess)")
    ap.add_argument("path")
    ap.add_argument("--size", type=int, required=True)
    ap.add_argument("--repeat", type=int, required=True)
    ap.add_argument("--translucent", action="store_true")
    a = ap.parse_args()
    sys.exit(vtk_worker(a.path, a.size, a.repeat, a.translucent))
