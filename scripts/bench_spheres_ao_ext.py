"""`scripts/bench-spheres --ao`'s other renderers and plots
(bench_spheres_ao.py runs them):

- VTK: vtkSSAOPass (delegate vtkRenderStepsPass) over vtkOpenGLSphereMapper on
  Mesa llvmpipe, LP_NUM_THREADS=1, one worker process per set (run under the
  virtual display bench-spheres starts for --vtk); white spheres lit by the
  ambient term alone (ambient 1, diffuse 0, specular 0), so a pixel's value is
  SSAO's visibility; radius --ssao-radius (a list: one row each, the ratios
  take the most accurate) and bias --ssao-bias mean sphere radii,
  --ssao-kernel samples, blur on; per radius an untimed frame (the first one
  compiles the shaders and uploads the points: VTK's preprocessing), then the
  best of R Render() + WaitForCompletion(); coverage from the depth buffer;
  8-bit read-back (a 1/255 quantisation floor).
- Tachyon (`tachyon`, tachyon-bin-nox), -numthreads 1: the set as SPHERE
  CENTER RAD with one white texture (ambient 0, diffuse 1, specular 0), no
  lights, `SHADER_MODE FULL AMBIENT_OCCLUSION AMBIENT_COLOR 1 1 1
  RESCALE_DIRECT 0 SAMPLES S`, so a pixel is 2/S · sum of N·w over the
  unoccluded ones of S directions drawn uniformly on the hemisphere: an
  unbiased estimate of the cosine-weighted AO (ours), whose occluders are at
  any distance (FHUGE), clamped to [0, 1); its camera is ours through an
  explicit FRUSTUM (Tachyon's right vector is up x view, the mirror of ours,
  and its pixel indices start at 1: both undone by the frustum's signs and a
  half-pixel shift; checked by the coverage masks); 48-bit PPM output (16 bits
  per channel, no 8-bit floor);
  times from its own report (parse, preprocessing = its grid, ray tracing).
"""
import datetime
import json
import os
import re
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_spheres as bs  # noqa: E402
from bench_common import cpu_name, cpu_vector_isa  # noqa: E402


# ---------------------------------------------------------------- VTK

def ssao_worker(arg):
    """In the worker process: renders, writes the AO (+inf off the spheres) as
    .npy, prints one JSON line."""
    import vtk
    from vtk.util import numpy_support as ns
    p = json.loads(arg)
    vtk.vtkObject.GlobalWarningDisplayOff()
    t0 = time.perf_counter()
    xyz, r, _ = bs.read_sphb(p["path"])
    ok = np.isfinite(r) & (r > 0) & np.isfinite(xyz).all(axis=1)
    xyz, r = np.ascontiguousarray(xyz[ok], np.float32), np.ascontiguousarray(r[ok], np.float32)
    n = len(r)
    pts = vtk.vtkPoints()
    pts.SetData(ns.numpy_to_vtk(xyz, deep=True))
    pd = vtk.vtkPolyData()
    pd.SetPoints(pts)
    verts = vtk.vtkCellArray()
    verts.SetData(ns.numpy_to_vtkIdTypeArray(np.arange(n + 1, dtype=np.int64), deep=True),
                  ns.numpy_to_vtkIdTypeArray(np.arange(n, dtype=np.int64), deep=True))
    pd.SetVerts(verts)
    rad = ns.numpy_to_vtk(r, deep=True)
    rad.SetName("radius")
    pd.GetPointData().AddArray(rad)
    del xyz, r
    mapper = vtk.vtkOpenGLSphereMapper()
    mapper.SetInputData(pd)
    mapper.SetScaleArray("radius")
    mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetColor(1, 1, 1)
    prop.SetAmbient(1)
    prop.SetDiffuse(0)
    prop.SetSpecular(0)
    ren = vtk.vtkRenderer()
    ren.AddActor(actor)
    ren.SetBackground(0, 0, 0)
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
    c, cam = p["camera"], ren.GetActiveCamera()
    cam.SetPosition(*c["eye"])
    cam.SetFocalPoint(*c["target"])
    cam.SetViewUp(*c["up"])
    cam.SetViewAngle(c["fov_y"])
    ren.ResetCameraClippingRange()
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
                    "peak_rss_mb": bs.peak_rss_mb(), "spheres": n})
    print(json.dumps(out), flush=True)
    return 0


def run_vtk(a, path, cam, size, repeat, rmean, base):
    """One row per SSAO radius (--ssao-radius, in mean radii), one worker."""
    radii = [float(x) for x in str(a.ssao_radius).split(",")]
    p = {"path": path, "size": size, "repeat": repeat, "out": base, "kernel": a.ssao_kernel,
         "radii": [x * rmean for x in radii], "bias": a.ssao_bias * rmean,
         "camera": {k: v for k, v in cam.items() if not k.startswith("_")}}
    env = dict(os.environ, LP_NUM_THREADS="1", OMP_NUM_THREADS="1")
    timeout = a.vtk_timeout + len(radii) * (repeat + 1) * a.vtk_frame_timeout
    params = [f"SSAO radius {x:g} r̄ = {x * rmean:.4g}, bias {a.ssao_bias:g} r̄, kernel {a.ssao_kernel}, blur on"
              for x in radii]
    try:
        q = subprocess.run([sys.executable, os.path.abspath(__file__), "--ssao-worker", json.dumps(p)],
                           capture_output=True, text=True, env=env, timeout=timeout)
    except subprocess.TimeoutExpired:
        return [{"renderer": "vtk-ssao", "error": f"timeout after {timeout:g} s", "params": params[0]}]
    line = q.stdout.strip().splitlines()[-1:] if q.returncode == 0 else []
    if not line:
        err = q.stderr.strip().splitlines()
        return [{"renderer": "vtk-ssao", "error": f"exit {q.returncode}" + (f": {err[-1][:200]}" if err else ""),
                 "params": params[0]}]
    rows = json.loads(line[0])
    for k, v in enumerate(rows):
        v.update(renderer="vtk-ssao", params=params[k], radius=radii[k], ao=np.load(f"{base}-r{k}.npy"))
    return rows


# ---------------------------------------------------------------- Tachyon

def tachyon_body(path, out):
    """The spheres as a Tachyon include file (written once per set)."""
    if os.path.exists(out):
        return out
    xyz, r, _ = bs.read_sphb(path)
    with open(out + ".tmp", "w") as f:
        f.write("TEXDEF W AMBIENT 0 DIFFUSE 1 SPECULAR 0 OPACITY 1 COLOR 1 1 1 TEXFUNC 0\n")
        for i in range(0, len(r), 1_000_000):
            c, rr = np.asarray(xyz[i:i + 1_000_000], np.float64), np.asarray(r[i:i + 1_000_000], np.float64)
            ok = np.isfinite(rr) & (rr > 0) & np.isfinite(c).all(axis=1)
            np.savetxt(f, np.column_stack([c[ok], rr[ok]]), fmt="SPHERE CENTER %.9g %.9g %.9g RAD %.9g W")
    os.replace(out + ".tmp", out)
    return out


def tachyon_scene(body, cam, size, samples):
    eye, tgt, up = (np.array(cam[k], np.float64) for k in ("eye", "target", "up"))
    view = (tgt - eye) / np.linalg.norm(tgt - eye)
    ty = np.tan(np.radians(cam["fov_y"]) / 2)
    tx = ty  # square images
    # Tachyon's right = up x view (the mirror of ours): left and right swapped;
    # its ray through pixel (x, y), 1-based from the lower left, meets the
    # image plane at (left + x psx, bottom + y psy): shifted by half a pixel,
    # the rays go through our pixel centres.
    left, right = tx + tx / size, -tx + tx / size
    bottom, top = -ty - ty / size, ty - ty / size
    v = lambda x: " ".join(f"{c:.17g}" for c in x)  # noqa: E731
    return "\n".join([
        "BEGIN_SCENE", f"RESOLUTION {size} {size}",
        "CAMERA", "  PROJECTION PERSPECTIVE", "  ZOOM 1.0", "  ASPECTRATIO 1.0", "  ANTIALIASING 0", "  RAYDEPTH 1",
        f"  CENTER {v(eye)}", f"  VIEWDIR {v(view)}", f"  UPDIR {v(up)}",
        f"  FRUSTUM {left:.17g} {right:.17g} {bottom:.17g} {top:.17g}", "END_CAMERA",
        "BACKGROUND 0 0 1",
        "SHADER_MODE FULL",
        f"  AMBIENT_OCCLUSION AMBIENT_COLOR 1 1 1 RESCALE_DIRECT 0 SAMPLES {samples}",
        "END_SHADER_MODE",
        f"INCLUDE {body}", "END_SCENE", ""])


def read_ppm(path):
    b = open(path, "rb").read()
    parts, i = [], 0
    while len(parts) < 4:
        while b[i:i + 1].isspace():
            i += 1
        if b[i:i + 1] == b"#":
            while b[i:i + 1] != b"\n":
                i += 1
            continue
        j = i
        while not b[j:j + 1].isspace():
            j += 1
        parts.append(b[i:j])
        i = j
    w, h, mx = int(parts[1]), int(parts[2]), int(parts[3])
    return np.frombuffer(b, ">u2" if mx > 255 else "u1", w * h * 3, i + 1).reshape(h, w, 3).astype(np.float32) / mx


def run_tachyon(a, body, cam, size, samples, base):
    sc = base + ".dat"
    with open(sc, "w") as f:
        f.write(tachyon_scene(body, cam, size, samples))
    out = base + ".ppm"
    if os.path.exists(out):
        os.remove(out)
    cmd = ["/usr/bin/time", "-f", "MAXRSS %M", a.tachyon_bin, sc, "-numthreads", "1", "-format", "PPM48", "-o", out]
    row = {"renderer": "tachyon", "samples": samples,
           "params": f"{samples} AO samples, FULL shading, no lights, 1 thread"}
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=a.tachyon_timeout)
    except subprocess.TimeoutExpired:
        return dict(row, error=f"timeout after {a.tachyon_timeout:g} s")
    times = {k: float(m) for k, m in re.findall(r"(Scene Parsing|Preprocessing|Ray Tracing) Time:\s+([0-9.]+)",
                                                 p.stdout)}
    if p.returncode != 0 or "Ray Tracing" not in times or not os.path.exists(out):
        return dict(row, error=f"exit {p.returncode}: {(p.stdout + p.stderr).strip()[-200:]}")
    img = read_ppm(out)
    bg = (img[..., 0] < 1e-6) & (img[..., 1] < 1e-6) & (img[..., 2] > 0.5)
    rss = re.findall(r"MAXRSS (\d+)", p.stderr)
    return dict(row, ms=times["Ray Tracing"] * 1000, preprocess_ms=times.get("Preprocessing", 0) * 1000,
                parse_ms=times.get("Scene Parsing", 0) * 1000, ao=np.where(bg, np.inf, img[..., 0]),
                peak_rss_mb=round(int(rss[-1]) / 1024, 1) if rss else "")


def tachyon_check(a, d, zs):
    """Tachyon's normalisation: an isolated sphere (AO 1 everywhere) and a
    sphere crowded by seven neighbours (cli.sphere_ao's scene), 96², against
    our Monte Carlo reference (4,096 rays); zs is bench_spheres_ao."""
    import math
    os.makedirs(d, exist_ok=True)
    cam = {"projection": "perspective", "eye": [0.4, 3, 6], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 40}
    crowd = ["0 0 0 1"] + [f"{1.95 * math.cos(math.radians(t)):.9f} 0 {1.95 * math.sin(math.radians(t)):.9f} 0.9"
                           for t in range(0, 360, 60)] + ["0 1.95 0 0.9"]
    rows = []
    for name, lines in (("isolated sphere", ["0 0 0 1"]), ("crowded sphere", crowd)):
        base = os.path.join(d, name.split()[0])
        with open(base + ".sph", "w") as f:
            f.write("\n".join(lines) + "\n")
        subprocess.run([bs.ZSWEEP, "spheres", "convert", base + ".sph", base + ".sphb"], check=True,
                       capture_output=True)
        with open(base + ".json", "w") as f:
            json.dump({"spheres": base + ".sphb", "image": {"width": 96, "height": 96}, "camera": cam,
                       "ao": {"directions": 66, "map_size": 1024}}, f)
        r = zs.reference(base + ".json", base + "-mc.exr", 4096, a.ref_threads, a.ref_timeout)
        if r["exit_status"] != 0:
            rows.append({"scene": name, "error": str(r.get("error", r["exit_status"]))})
            continue
        mc = zs.read_ao(base + "-mc.exr")
        body = tachyon_body(base + ".sphb", base + "-body.dat")
        for samples in (64, 1024):
            t = run_tachyon(a, body, cam, 96, samples, f"{base}-s{samples}")
            row = {"scene": name, "samples": samples, "mc_mean_ao": float(mc[np.isfinite(mc)].mean())}
            if "ao" not in t:
                rows.append(dict(row, error=t.get("error")))
                continue
            e = zs.error(t["ao"], mc)
            m = np.isfinite(t["ao"]) & np.isfinite(mc)
            rows.append(dict(row, tachyon_mean_ao=float(t["ao"][m].mean()),
                             clamp_expected_isolated=1 - 1 / math.sqrt(2 * math.pi * 3 * samples),
                             mean_bias=float((t["ao"][m] - mc[m]).mean()), vs_mc_mean=e["mean"], vs_mc_max=e["max"],
                             coverage_diff=e["coverage_diff"]))
    return rows


def versus_row(common, size, v, exact, mc, error, amortise, var=None):
    row = dict(common, size=size, renderer=v["renderer"], samples=v.get("samples", ""), radius=v.get("radius", ""),
               params=v.get("params", ""))
    if "error" in v:
        return dict(row, exit_status=v["error"])
    row.update({k: v.get(k, "") for k in ("ms", "frame_ms", "preprocess_ms", "parse_ms", "load_s", "peak_rss_mb")},
               exit_status=0)
    row["amortised_ms"] = v["ms"] + v["preprocess_ms"] / amortise
    for key, ref, vr in (("exact", exact, None), ("mc", mc, var)):
        if ref is not None:
            e = error(v["ao"], ref, vr)
            row.update({f"vs_{key}_mean": e["mean"], f"vs_{key}_max": e["max"], f"vs_{key}_rms": e["rms"]})
            if key == "mc":
                row["coverage_diff"] = e["coverage_diff"]
                row["vs_mc_rms_corrected"] = e.get("rms_corrected", "")
    return row


def doc_lines(a, c, tables, results, wall):
    f = bs.fmt
    cmd = "scripts/bench-spheres " + " ".join(sys.argv[1:])
    sets = ", ".join(f"{r['set'].upper()} ({r['spheres']:,})" for r in results)
    L = [f"Measured {datetime.date.today().isoformat()} on {cpu_name()} ({os.cpu_count()} cores, {cpu_vector_isa()}), "
         f"`{cmd.strip()}` ({wall / 60:.1f} min). Sets: {sets}. One thread for every timed renderer; each zsweep time "
         f"is the best of {c['R']} whole frames of one `render --frames {c['R']}` process; the AO maps are built "
         f"once per process, before the frames, and reported apart; memory budget {a.memory_budget:g} MiB. Camera: "
         f"zsweep reference's automatic perspective camera (fov 30°), the same for every renderer.", "",
         f"**Table 6 analogue** ({c['size']}², one thread): Phong against AO with {c['tdirs']} directions and maps "
         f"of {c['tmap']}² (the frame includes the visibility structures, not the maps).", "",
         "| set | spheres | Phong ms | AO ms | AO / Phong | maps ms (once per set) | maps MiB |",
         "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for r in tables["ao-table6.csv"]:
        L.append(f"| {r['set'].upper()} | {r['spheres']:,} | {f(r.get('phong_ms'))} | {f(r.get('ao_ms'))} | "
                 f"{f(r.get('ao_over_phong'), 2)}× | {f(r.get('maps_ms'), 0)} | {f(r.get('map_mb'), 0)} |" +
                 (f" {r['error']}" if r.get("error") else ""))
    t7 = tables["ao-table7.csv"]
    L += ["", f"**Table 7 analogue**: building the maps ({c['tmap']}², one thread), ms (MiB), per direction count:",
          "", "| set | spheres | " + " | ".join(f"{d} directions" for d in c["dirs"]) + " |",
          "| --- | ---: | " + " ---: |" * len(c["dirs"])]
    for r in results:
        cells = []
        for d in c["dirs"]:
            x = next((t for t in t7 if t["set"] == r["set"] and t["directions"] == d), None)
            cells.append("–" if x is None else (f"{f(x['maps_ms'], 0)} ({f(x['map_mb'], 1)})" if x["exit_status"] == 0
                                                 else str(x.get("error") or x["exit_status"])[:60]))
        L.append(f"| {r['set'].upper()} | {r['spheres']:,} | " + " | ".join(cells) + " |")
    refs = tables["ao-references.csv"]
    L += ["", f"**Error** ({c['esize']}², mean and max |ΔAO| over the pixels covered in both images): against the "
          f"same directions traced exactly (`zsweep reference`: the maps' error alone) and against a cosine-weighted "
          f"Monte Carlo AO with {4 * c['N']:,} rays per pixel (`reference --ao-samples {4 * c['N']}`: the converged "
          f"reference; its own noise floor below). References ran with {a.ref_threads} threads. Frame ms: one "
          f"thread; amortised: + maps / {a.amortise}.", "",
          "| set | directions | map | frame ms | maps ms | amortised ms | vs exact: mean | max | vs MC: mean | max | "
          "RMS, MC noise removed | exact directions vs MC: mean | RMS, noise removed |",
          "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for g in tables["ao-error.csv"]:
        L.append(f"| {g['set'].upper()} | {g['directions']} | {g['map_size']} | {f(g.get('ms'))} | "
                 f"{f(g.get('maps_ms'), 0)} | {f(g.get('amortised_ms'))} | {f(g.get('vs_exact_mean'), 4)} | "
                 f"{f(g.get('vs_exact_max'), 3)} | {f(g.get('vs_mc_mean'), 4)} | {f(g.get('vs_mc_max'), 3)} | "
                 f"{f(g.get('vs_mc_rms_corrected'), 4)} | {f(g.get('exact_dirs_vs_mc_mean'), 4)} | "
                 f"{f(g.get('exact_dirs_vs_mc_rms_corrected'), 4)} |" +
                 (f" maps built in {g['ao_batches']} batches per frame (in the frame time)" if g.get("ao_batches") else "")
                 + ("" if g["exit_status"] == 0 else
                                                               f" {g.get('error') or g['exit_status']}"))
    L += ["", f"The Monte Carlo reference's noise: hits / {4 * c['N']} is binomial, so its expected mean |error| is "
          f"√(2/π)·mean √(AO(1−AO)/{4 * c['N']}) (\"floor\"); measured against a second reference with {c['N']} rays "
          f"(nested streams: expected mean |Δ| √(2/π)·mean √(0.75·AO(1−AO)/{c['N']}); the floor estimated from it: "
          "rms Δ / √3 · √(2/π)). \"RMS, MC noise removed\": √(mean Δ² − mean p(1−p)/(4N−1)), p the reference's "
          "value: the RMS against the noise-free Monte Carlo AO, unbiased.", "",
          "| set | MC build + trace ms (4N) | floor (analytic) | N vs 4N: measured | expected | floor from N vs 4N | "
          "exact-direction references: trace ms |", "| --- | ---: | ---: | ---: | ---: | ---: | --- |"]
    for r in results:
        mc = next((x for x in refs if x["set"] == r["set"] and x.get("samples") == 4 * c["N"]), {})
        ex = ", ".join(f"{x['directions']}: {f(x.get('trace_ms'), 0)}" for x in refs
                       if x["set"] == r["set"] and x.get("kind") == "exact directions")
        L.append(f"| {r['set'].upper()} | {f((mc.get('build_ms') or 0) + (mc.get('trace_ms') or float('nan')), 0)} | "
                 f"{f(mc.get('noise_floor_mean'), 4)} | {f(mc.get('n_vs_4n_mean'), 4)} | "
                 f"{f(mc.get('n_vs_4n_expected'), 4)} | {f(mc.get('noise_floor_from_n'), 4)} | {ex} |")
    if tables["ao-versus.csv"]:
        L += versus_doc(a, c, tables, f)
    return L


def versus_doc(a, c, tables, f):
    vs, ra = tables["ao-versus.csv"], tables["ao-ratios.csv"]
    L = ["", f"**Side by side** ({c['esize']}², one thread each, same spheres and camera; errors vs the Monte Carlo "
         f"reference and vs our {c['tdirs']} directions traced exactly; coverage: pixels covered by one image only, "
         "of the pixels either covers, against the MC reference). Preprocessing: our maps, VTK's warm-up frame "
         "(shaders, upload), Tachyon's grid (its parse is left out, as our load is).", "",
         "| set | renderer | settings | frame ms | preprocessing ms | vs MC: mean | max | RMS, noise removed | "
         "vs exact: mean | coverage differs |", "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for s in dict.fromkeys(r["set"] for r in tables["ao-error.csv"]):
        g = next((x for x in tables["ao-error.csv"] if x["set"] == s and x["directions"] == c["tdirs"]
                  and x["map_size"] == c["tmap"]), None)
        if g and any(v["set"] == s for v in vs):
            L.append(f"| {s.upper()} | zsweep | {c['tdirs']} directions, maps {c['tmap']}² | {f(g.get('ms'))} | "
                     f"{f(g.get('maps_ms'), 0)} | {f(g.get('vs_mc_mean'), 4)} | {f(g.get('vs_mc_max'), 3)} | "
                     f"{f(g.get('vs_mc_rms_corrected'), 4)} | {f(g.get('vs_exact_mean'), 4)} | "
                     f"{f(100 * g.get('vs_mc_coverage_diff', float('nan')), 2)} % |")
        for v in vs:
            if v["set"] != s:
                continue
            if v["exit_status"] != 0:
                L.append(f"| {s.upper()} | {v['renderer']} | {v['params']} | {v['exit_status']} | | | | | | |")
                continue
            L.append(f"| {s.upper()} | {v['renderer']} | {v['params']} | {f(v.get('ms'))} | "
                     f"{f(v.get('preprocess_ms'), 0)} | {f(v.get('vs_mc_mean'), 4)} | {f(v.get('vs_mc_max'), 3)} | "
                     f"{f(v.get('vs_mc_rms_corrected'), 4)} | {f(v.get('vs_exact_mean'), 4)} | {f(100 * v.get('coverage_diff', float('nan')), 2)} % |")
    for r in tables.get("ao-tachyon-check.csv") or []:
        if r is tables["ao-tachyon-check.csv"][0]:
            L += ["", "Tachyon's normalisation, checked (96², camera matched, against our Monte Carlo AO with 4,096 "
                  "rays). An isolated sphere must average 1 and the crowded one our AO; Tachyon's clamp to [0, 1) "
                  "lowers open surfaces (with independent uniform samples, to 1 − 1/√(2π·3S) on average):", "",
                  "| scene | samples S | Tachyon mean AO | MC mean AO | 1 − 1/√(2π·3S) | mean bias | "
                  "mean |Δ| | coverage differs |", "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
        L.append(f"| {r['scene']} | {r.get('samples', '')} | {f(r.get('tachyon_mean_ao'), 4)} | "
                 f"{f(r.get('mc_mean_ao'), 4)} | {f(r.get('clamp_expected_isolated'), 4)} | {f(r.get('mean_bias'), 4)} | "
                 f"{f(r.get('vs_mc_mean'), 4)} | {f(100 * r.get('coverage_diff', float('nan')), 2)} % |"
                 + (f" {r['error']}" if r.get("error") else ""))
    if ra:
        L += ["", "**Ratios** (same run; time: per frame, or with the preprocessing amortised): their time over ours "
              "at an error vs MC (mean) no larger than theirs. VTK: its most accurate radius, against our fastest "
              "configuration (directions/map size) at or below its error. Tachyon: for each configuration of ours, "
              "its time at our error, interpolated log-log between the two sample counts around it (count shown "
              "interpolated; \"≥\": even its largest count is less accurate, its time there is a lower bound; "
              "\"≤\": its smallest count is already more accurate, an upper bound), the best ratio shown. The goal "
              "(≥ 5× faster than both at equal or lower error) is read on one configuration of ours against both: "
              "at or below VTK's error, with Tachyon at that configuration's error.", "",
              "| set | time | VTK / ours (ours: config, error; VTK error) | Tachyon / ours (samples; ours: config, "
              "error) | one config for both: VTK / ours, Tachyon / ours | ≥ 5× both |",
              "| --- | --- | --- | --- | --- | :---: |"]
        for r in ra:
            vt = (f"{f(r['vtk_over_ours'], 1)}× ({r.get('ours_for_vtk')}, {f(r.get('ours_for_vtk_err'), 4)}; "
                  f"{f(r.get('vtk_err'), 4)})" if bs.isnum(r.get("vtk_over_ours")) else str(r.get("vtk_over_ours", "–")))
            ta = (f"{r.get('tachyon_bound', '')}{f(r['tachyon_over_ours'], 1)}× ({f(r.get('tachyon_samples'), 0)}; "
                  f"{r.get('ours_for_tachyon')}, {f(r.get('ours_for_tachyon_err'), 4)})"
                  if bs.isnum(r.get("tachyon_over_ours")) else "–")
            one = "–"
            if r.get("one_config"):
                one = (f"{r['one_config']} ({f(r.get('one_config_err'), 4)}): " +
                       (f"{f(r['one_config_vtk_over_ours'], 1)}×" if bs.isnum(r.get("one_config_vtk_over_ours"))
                        else "–") + ", " +
                       (f"{r.get('one_config_tachyon_bound', '')}{f(r['one_config_tachyon_over_ours'], 1)}× "
                        f"({f(r.get('one_config_tachyon_samples'), 0)} samples)"
                        if bs.isnum(r.get("one_config_tachyon_over_ours")) else "–"))
            L.append(f"| {r['set'].upper()} | {r['time']} | {vt} | {ta} | {one} | "
                     f"{'yes' if r['goal_5x'] == 'yes' else '**' + str(r['goal_5x']) + '**'} |")
    L += ["", "Notes: VTK's SSAO is a screen-space approximation within a radius (it sees only what the depth buffer "
          "holds), so it does not converge to the references; its value is read back in 8 bits (a 1/255 floor). "
          "Tachyon's AO samples S directions uniformly on the hemisphere and weights each by N·ω with a 2/S factor: "
          "the same cosine-weighted AO as ours (occluders at any distance), unbiased before its clamp to [0, 1), "
          "which biases bright pixels low at small S (see the check above); read from a 16-bit PPM."]
    return L


# ---------------------------------------------------------------- plots

def save_bars(fig, ax, ylabel, path):
    """A bar chart's log axis, grid and legend, saved to `path` (returned)."""
    import matplotlib.pyplot as plt
    ax.set_yscale("log")
    ax.set_ylabel(ylabel, fontsize=8)
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return path


def plots(results, tables, c, a, outdir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    files = []
    sets = [r for r in results if r["grid"]]
    if not sets:
        return files
    cols = min(3, len(sets))
    nrow = (len(sets) + cols - 1) // cols
    dirs = sorted({g["directions"] for r in sets for g in r["grid"]})
    maps = sorted({g["map_size"] for r in sets for g in r["grid"]})
    colours = {d: plt.cm.viridis(i / max(len(dirs) - 1, 1)) for i, d in enumerate(dirs)}
    marks = dict(zip(maps, "os^Dvp<>"))

    # Time against error vs MC.
    fig, axs = plt.subplots(nrow, cols, figsize=(4.2 * cols, 3.4 * nrow), dpi=80, squeeze=False)
    for ax, r in zip(axs.flat, sets):
        for g in r["grid"]:
            if not (bs.isnum(g.get("vs_mc_mean")) and bs.isnum(g.get("ms"))):
                continue
            ax.plot(g["ms"], g["vs_mc_mean"], marks[g["map_size"]], color=colours[g["directions"]], ms=5)
            if bs.isnum(g.get("amortised_ms")):
                ax.plot(g["amortised_ms"], g["vs_mc_mean"], marks[g["map_size"]], mfc="none",
                        color=colours[g["directions"]], ms=5)
        ta = sorted([v for v in r["versus"] if v["renderer"] == "tachyon" and bs.isnum(v.get("vs_mc_mean"))],
                    key=lambda v: v["samples"])
        if ta:
            ax.plot([v["ms"] for v in ta], [v["vs_mc_mean"] for v in ta], "k.--", lw=1, label="Tachyon (4…S samples)")
            for v in ta:
                ax.annotate(str(int(v["samples"])), (v["ms"], v["vs_mc_mean"]), fontsize=6)
        vt = [v for v in r["versus"] if v["renderer"] == "vtk-ssao" and bs.isnum(v.get("vs_mc_mean"))]
        if vt:
            ax.plot([v["ms"] for v in vt], [v["vs_mc_mean"] for v in vt], "rx", ms=7,
                    label="VTK vtkSSAOPass (radius in r̄)")
            for v in vt:
                if bs.isnum(v.get("radius")):
                    ax.annotate(f"{v['radius']:g}", (v["ms"], v["vs_mc_mean"]), fontsize=6, color="r")
        if bs.isnum(r.get("noise_floor")):
            ax.axhline(r["noise_floor"], color="grey", ls=":", lw=1, label="MC reference noise")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{r['set'].upper()} ({r['spheres']:,} spheres)", fontsize=9)
        ax.set_xlabel("ms per frame, 1 thread (hollow: + maps / %g)" % getattr(a, "amortise", 100), fontsize=7)
        ax.set_ylabel("mean |ΔAO| vs Monte Carlo", fontsize=7)
        ax.grid(True, which="both", alpha=0.3)
        ax.tick_params(labelsize=7)
    for ax in list(axs.flat)[len(sets):]:
        ax.axis("off")
    handles = [plt.Line2D([], [], color=colours[d], marker="o", ls="", label=f"{d} directions") for d in dirs]
    handles += [plt.Line2D([], [], color="k", marker=marks[m], ls="", mfc="none", label=f"map {m}²") for m in maps]
    seen = {}
    for ax in axs.flat:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            seen.setdefault(lab, h)
    fig.tight_layout()
    fig.legend(handles + list(seen.values()), [x.get_label() for x in handles] + list(seen), fontsize=7,
               loc="center left", bbox_to_anchor=(1.0, 0.5))
    files.append(os.path.join(outdir, "ao-time-error.png"))
    fig.savefig(files[-1], bbox_inches="tight")
    plt.close(fig)

    # Error vs the exact directions, against the map size.
    fig, axs = plt.subplots(nrow, cols, figsize=(4.2 * cols, 3.2 * nrow), dpi=80, squeeze=False)
    for ax, r in zip(axs.flat, sets):
        for d in dirs:
            pts = sorted((g["map_size"], g["vs_exact_mean"]) for g in r["grid"]
                         if g["directions"] == d and bs.isnum(g.get("vs_exact_mean")))
            if pts:
                ax.plot(*zip(*pts), "o-", color=colours[d], label=f"{d} directions", ms=4)
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_title(f"{r['set'].upper()}", fontsize=9)
        ax.set_xlabel("map size (texels per side)", fontsize=7)
        ax.set_ylabel("mean |ΔAO| vs exact directions", fontsize=7)
        ax.grid(True, which="both", alpha=0.3)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6)
    for ax in list(axs.flat)[len(sets):]:
        ax.axis("off")
    fig.tight_layout()
    files.append(os.path.join(outdir, "ao-error-map.png"))
    fig.savefig(files[-1])
    plt.close(fig)

    # Table 7: the maps' time per direction count; Table 6: Phong against AO.
    t7 = tables.get("ao-table7.csv") or []
    fig, ax = plt.subplots(figsize=(6, 3.4), dpi=80)
    wbar = 0.8 / max(len(dirs), 1)
    for i, d in enumerate(dirs):
        ys = [next((t["maps_ms"] for t in t7 if t["set"] == r["set"] and t["directions"] == d
                    and bs.isnum(t.get("maps_ms"))), float("nan")) for r in sets]
        ax.bar([j + i * wbar for j in range(len(sets))], ys, wbar, label=f"{d} directions", color=colours[d])
    ax.set_xticks([j + 0.4 - wbar / 2 for j in range(len(sets))])
    ax.set_xticklabels([f"{r['set'].upper()}\n{r['spheres']:,}" for r in sets], fontsize=8)
    files.append(save_bars(fig, ax, f"ms to build the maps ({c['tmap']}², 1 thread)", os.path.join(outdir, "ao-table7.png")))
    t6 = tables.get("ao-table6.csv") or []
    if t6:
        fig, ax = plt.subplots(figsize=(6, 3.4), dpi=80)
        xs = np.arange(len(t6))
        for i, (k, lab) in enumerate([("phong_ms", "Phong"), ("ao_ms", "AO frame"), ("maps_ms", "AO maps (once)")]):
            ax.bar(xs + i * 0.27, [t.get(k) if bs.isnum(t.get(k)) else float("nan") for t in t6], 0.27, label=lab)
        ax.set_xticks(xs + 0.27)
        ax.set_xticklabels([f"{t['set'].upper()}\n{int(t['spheres']):,}" for t in t6], fontsize=8)
        files.append(save_bars(fig, ax, f"ms, 1 thread, {int(t6[0]['size'])}²", os.path.join(outdir, "ao-table6.png")))
    return files


def compare_png(path, panels, name):
    """AO images side by side (grey: 0 black, 1 white; off the spheres blue)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    panels = [(t, im) for t, im in panels if im is not None]
    if not panels:
        return None
    fig, axs = plt.subplots(1, len(panels), figsize=(2.6 * len(panels), 2.9), dpi=90, squeeze=False)
    for ax, (t, im) in zip(axs[0], panels):
        rgb = np.repeat(np.clip(np.where(np.isfinite(im), im, 0), 0, 1)[..., None], 3, axis=2)
        rgb[~np.isfinite(im)] = (0.2, 0.3, 0.6)
        ax.imshow(rgb, interpolation="nearest")
        ax.set_title(t, fontsize=7)
        ax.axis("off")
    fig.suptitle(f"{name.upper()}: AO", fontsize=9)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return path


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--ssao-worker":
        sys.exit(ssao_worker(sys.argv[2]))
    sys.exit("bench_spheres_ao_ext.py: run through scripts/bench-spheres --ao")
