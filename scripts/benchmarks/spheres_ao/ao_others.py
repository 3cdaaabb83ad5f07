"""`scripts/bench spheres --ao`'s other renderers (ao.py runs them):

- VTK: vtkSSAOPass (delegate vtkRenderStepsPass) over vtkOpenGLSphereMapper on
  Mesa llvmpipe, LP_NUM_THREADS=1, one worker process per set (ao_ssao_worker.py,
  under the virtual display scripts/bench starts for --vtk); white spheres lit by the
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
import json
import math
import os
import re
import subprocess
import sys

import numpy as np

from ..lib.common import ZSWEEP, worker_env
from ..lib.sphere_sets import read_sphb
from .ao_runs import error, read_ao, reference


# ---------------------------------------------------------------- VTK

def run_vtk(a, path, cam, size, repeat, rmean, base):
    """One row per SSAO radius (--ssao-radius, in mean radii), one worker."""
    radii = [float(x) for x in str(a.ssao_radius).split(",")]
    p = {"path": path, "size": size, "repeat": repeat, "out": base, "kernel": a.ssao_kernel,
         "radii": [x * rmean for x in radii], "bias": a.ssao_bias * rmean,
         "camera": {k: v for k, v in cam.items() if not k.startswith("_")}}
    env = worker_env(LP_NUM_THREADS="1", OMP_NUM_THREADS="1")
    timeout = a.vtk_timeout + len(radii) * (repeat + 1) * a.vtk_frame_timeout
    params = [f"SSAO radius {x:g} r̄ = {x * rmean:.4g}, bias {a.ssao_bias:g} r̄, kernel {a.ssao_kernel}, blur on"
              for x in radii]
    try:
        q = subprocess.run([sys.executable, "-m", "benchmarks.spheres_ao.ao_ssao_worker", json.dumps(p)],
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
    xyz, r, _ = read_sphb(path)
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


def tachyon_check(a, d):
    """Tachyon's normalisation: an isolated sphere (AO 1 everywhere) and a
    sphere crowded by seven neighbours (cli.sphere_ao's scene), 96², against
    our Monte Carlo reference (4,096 rays)."""
    os.makedirs(d, exist_ok=True)
    cam = {"projection": "perspective", "eye": [0.4, 3, 6], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 40}
    crowd = ["0 0 0 1"] + [f"{1.95 * math.cos(math.radians(t)):.9f} 0 {1.95 * math.sin(math.radians(t)):.9f} 0.9"
                           for t in range(0, 360, 60)] + ["0 1.95 0 0.9"]
    rows = []
    for name, lines in (("isolated sphere", ["0 0 0 1"]), ("crowded sphere", crowd)):
        base = os.path.join(d, name.split()[0])
        with open(base + ".sph", "w") as f:
            f.write("\n".join(lines) + "\n")
        subprocess.run([ZSWEEP, "spheres", "convert", base + ".sph", base + ".sphb"], check=True,
                       capture_output=True)
        with open(base + ".json", "w") as f:
            json.dump({"spheres": base + ".sphb", "image": {"width": 96, "height": 96}, "camera": cam,
                       "ao": {"directions": 66, "map_size": 1024}}, f)
        r = reference(base + ".json", base + "-mc.exr", 4096, a.ref_threads, a.ref_timeout)
        if r["exit_status"] != 0:
            rows.append({"scene": name, "error": str(r.get("error", r["exit_status"]))})
            continue
        mc = read_ao(base + "-mc.exr")
        body = tachyon_body(base + ".sphb", base + "-body.dat")
        for samples in (64, 1024):
            t = run_tachyon(a, body, cam, 96, samples, f"{base}-s{samples}")
            row = {"scene": name, "samples": samples, "mc_mean_ao": float(mc[np.isfinite(mc)].mean())}
            if "ao" not in t:
                rows.append(dict(row, error=t.get("error")))
                continue
            e = error(t["ao"], mc)
            m = np.isfinite(t["ao"]) & np.isfinite(mc)
            rows.append(dict(row, tachyon_mean_ao=float(t["ao"][m].mean()),
                             clamp_expected_isolated=1 - 1 / math.sqrt(2 * math.pi * 3 * samples),
                             mean_bias=float((t["ao"][m] - mc[m]).mean()), vs_mc_mean=e["mean"], vs_mc_max=e["max"],
                             coverage_diff=e["coverage_diff"]))
    return rows


def versus_row(common, size, v, exact, mc, amortise, var=None):
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
