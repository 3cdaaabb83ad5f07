"""The VTK worker of `scripts/bench spheres --ao --vtk` (ao_others.run_vtk starts
it): vtkSSAOPass (delegate vtkRenderStepsPass) over vtkOpenGLSphereMapper on
Mesa llvmpipe, white spheres lit by the ambient term alone, so a pixel's value
is SSAO's visibility; per radius an untimed frame, then the best of R frames.

  python3 -m benchmarks.spheres_ao.ao_ssao_worker JOB_JSON   (scripts/ on PYTHONPATH, an X display)
"""
import json
import sys
import time

import numpy as np

from ..lib.common import peak_rss_mb
from ..lib.sphere_sets import read_sphb
from ..lib.sphere_vtk import set_camera, sphere_polydata, sphere_renderer


def ssao_worker(arg):
    """In the worker process: renders, writes the AO (+inf off the spheres) as
    .npy, prints one JSON line."""
    import vtk
    from vtk.util import numpy_support as ns
    p = json.loads(arg)
    vtk.vtkObject.GlobalWarningDisplayOff()
    t0 = time.perf_counter()
    xyz, r, _ = read_sphb(p["path"])
    ok = np.isfinite(r) & (r > 0) & np.isfinite(xyz).all(axis=1)
    xyz, r = np.ascontiguousarray(xyz[ok], np.float32), np.ascontiguousarray(r[ok], np.float32)
    n = len(r)
    pd = sphere_polydata(xyz, r)
    del xyz, r
    actor, ren = sphere_renderer(pd, colours=False)
    prop = actor.GetProperty()
    prop.SetColor(1, 1, 1)
    prop.SetAmbient(1)
    prop.SetDiffuse(0)
    prop.SetSpecular(0)
    ssao = vtk.vtkSSAOPass()
    ssao.SetDelegatePass(vtk.vtkRenderStepsPass())
    ssao.SetBias(p["bias"])
    ssao.SetKernelSize(p["kernel"])
    ssao.BlurOn()
    ren.SetPass(ssao)
    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetMultiSamples(0)
    win.AddRenderer(ren)
    W = H = p["size"]
    win.SetSize(W, H)
    set_camera(ren, p["camera"])
    load_s = time.perf_counter() - t0
    out = []
    for k, radius in enumerate(p["radii"]):
        # The first radius's first frame compiles the shaders and uploads the
        # points (VTK's preprocessing); later radii only change a uniform.
        ssao.SetRadius(radius)
        t = time.perf_counter()
        win.Render()
        win.WaitForCompletion()
        warm = time.perf_counter() - t
        times = []
        for _ in range(p["repeat"]):
            t = time.perf_counter()
            win.Render()
            win.WaitForCompletion()
            times.append(time.perf_counter() - t)
            if times[-1] > 2.0:  # slow frames (C4): one is enough
                break
        rgba = vtk.vtkUnsignedCharArray()
        win.GetRGBACharPixelData(0, 0, W - 1, H - 1, 0, rgba)
        img = ns.vtk_to_numpy(rgba).reshape(H, W, 4)[::-1]
        z = vtk.vtkFloatArray()
        win.GetZbufferData(0, 0, W - 1, H - 1, z)
        z = ns.vtk_to_numpy(z).reshape(H, W)[::-1]
        ao = np.where(z < 1, img[..., 0].astype(np.float32) / 255, np.float32(np.inf))
        np.save(f"{p['out']}-r{k}.npy", ao)
        out.append({"ms": min(times) * 1000, "frame_ms": " ".join(f"{x * 1000:.1f}" for x in times),
                    "preprocess_ms": warm * 1000 if k == 0 else out[0]["preprocess_ms"], "load_s": load_s,
                    "peak_rss_mb": peak_rss_mb(), "spheres": n})
    print(json.dumps(out), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(ssao_worker(sys.argv[1]))
