"""The ambient occlusion benchmark's settings and zsweep runs: the run's
configuration (--quick's defaults filled in), the sets' files, the scenes,
`zsweep render` and `zsweep reference` (exact directions or Monte Carlo), the
AO channel of an EXR, and the error of one AO image against another."""
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

from ..lib.common import ZSWEEP, run_stats
from ..lib.sphere_sets import FULL, bounds, read_sphb, scene

QUICK = {"c1": 3000, "c2": 3000, "c3": 3000, "c4": 3375}
SQ2PI = math.sqrt(2 / math.pi)  # E|X| / std(X) for a normal X


def ints(s):
    return [int(x) for x in str(s).split(",") if x]


def config(a, ap):
    """The run's settings, --quick's defaults filled in."""
    q = a.quick
    c = {"sets": (a.sets or ("c1,c2,c3,c4,1hpv")).split(","),
         "size": a.size or (128 if q else 1024), "esize": a.error_size or (128 if q else 512),
         "R": a.repeat or a.frames or (1 if q else 3),
         "dirs": ints(a.directions or ("6,18" if q else "6,18,66,258")),
         "maps": ints(a.map_sizes or ("64,128" if q else "256,512,1024,2048")),
         "N": a.ao_samples or (64 if q else 256),
         "tach": ints(a.tachyon_samples or ("4,16" if q else "4,16,64,256"))}
    c["tdirs"] = a.table_directions or (66 if 66 in c["dirs"] else max(c["dirs"]))
    c["tmap"] = a.table_map_size or (1024 if 1024 in c["maps"] else max(c["maps"]))
    if c["tdirs"] not in c["dirs"] or c["tmap"] not in c["maps"]:
        ap.error("--table-directions must be in --directions and --table-map-size in --map-sizes")
    for s in c["sets"]:
        if s not in FULL and s != "1hpv":
            ap.error(f"unknown set {s} (c1, c2, c3, c4, 1hpv)")
    if "1hpv" in c["sets"] and not os.path.exists(a.pdb):
        print(f"bench-spheres --ao: {a.pdb} missing (pymol-data): 1hpv left out", file=sys.stderr)
        c["sets"].remove("1hpv")
    if a.counts:
        counts = ints(a.counts)
        if len(counts) != len(c["sets"]):
            ap.error("--counts needs one count per set (1hpv's is ignored)")
    else:
        counts = [(QUICK if q else FULL).get(s, 0) for s in c["sets"]]
    c["counts"] = dict(zip(c["sets"], counts))
    if a.grid == "cross":
        c["grid"] = sorted({(d, c["tmap"]) for d in c["dirs"]} | {(c["tdirs"], m) for m in c["maps"]})
    else:
        c["grid"] = [(d, m) for d in c["dirs"] for m in c["maps"]]
    return c


def prepare(a, name, count):
    """(path, spheres, mean radius, lo, hi) of the set's .sphb in --out."""
    if name == "1hpv":
        path = os.path.join(a.out, "1hpv.sphb")
        cmd = [ZSWEEP, "spheres", "convert", a.pdb, path]
    else:
        path = os.path.join(a.out, f"{name}-{count}.sphb")
        cmd = [ZSWEEP, "spheres", "generate", name, "--count", str(count), "-o", path]
    if not os.path.exists(path):
        t = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        print(f"{name}: wrote {os.path.basename(path)} in {time.perf_counter() - t:.1f} s", flush=True)
    _, r, _ = read_sphb(path)
    ok = np.isfinite(r) & (r > 0)
    lo, hi = bounds(path)
    return path, int(len(r)), float(np.asarray(r[ok], np.float64).mean()), lo, hi


def write_scene(a, path, cam, size, dirs, mapsize, fname):
    sc = scene(path, cam, size, a.memory_budget)
    if dirs:
        sc["ao"] = {"directions": dirs, "map_size": mapsize}
    with open(fname, "w") as f:
        json.dump(sc, f, indent=1)
    return fname


def same_scene(p, q):
    """Two scene files equal but for the memory budget (references ignore it)."""
    def load(f):
        j = json.load(open(f))
        j.get("render", {}).pop("memory_budget_mb", None)
        return j
    return load(p) == load(q)


def render(scene_path, out, R, budget, timeout):
    """One `zsweep render --threads 1 --frames R` process: best frame, maps."""
    stats = out + ".stats.json"
    for f in (stats, out):
        if os.path.exists(f):
            os.remove(f)
    cmd = [ZSWEEP, "render", scene_path, "-o", out, "--threads", "1", "--frames", str(R), "--stats", stats,
           "--memory-budget", str(budget), "--compression", "none"]
    row, j = run_stats(cmd, stats, timeout, err_chars=300)
    if j is None:
        return row
    t, ao = j["time_ms"], j.get("ao", {})
    row.update({"ms": t["total"], "setup_ms": t.get("setup"), "maps_ms": t.get("ao_maps"),
                "map_mb": round(ao.get("map_bytes", 0) / 2**20, 2) if ao.get("directions") else "",
                # Maps over the budget are built in batches by every frame (in its time).
                "ao_batches": ao.get("batches", ""),
                "frame_ms": " ".join(f"{x:.1f}" for x in j.get("frame_ms", [t["total"]])),
                "rendered_pixels": j.get("rendered_pixels"),
                "peak_rss_mb": round(j.get("peak_rss_bytes", 0) / 2**20, 1)})
    return row


def reference(scene_path, out, samples, threads, timeout):
    stats = out + ".stats.json"
    cmd = [ZSWEEP, "reference", scene_path, "-o", out, "--threads", str(threads), "--stats", stats]
    if samples:
        cmd += ["--ao-samples", str(samples)]
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"exit_status": f"timeout after {timeout:g} s"}
    if p.returncode != 0:
        sys.stderr.write(f"zsweep reference failed: {' '.join(cmd)}\n{p.stderr}\n")
        return {"exit_status": p.returncode, "error": p.stderr.strip()[-300:]}
    with open(stats) as f:
        t = json.load(f)["time_ms"]
    return {"exit_status": 0, "build_ms": t["build"], "trace_ms": t["trace"], "threads": threads,
            "process_s": round(time.perf_counter() - t0, 3)}


def read_ao(path):
    """The AO channel (h x w float32, +inf off the spheres) of an EXR."""
    import OpenImageIO as oiio
    i = oiio.ImageInput.open(path)
    if not i:
        raise OSError(f"cannot open {path}")
    names = list(i.spec().channelnames)
    img = i.read_image("float")
    i.close()
    return np.asarray(img[..., names.index("AO")], np.float32)


def error(a, b, var=None):
    """|a - b| over the pixels covered in both (finite AO), and how many
    covered pixels only one of them covers (a fraction of the union). With
    `var`, b's per-pixel noise variance (a Monte Carlo b): the RMS against the
    noise-free b, E[(a - b)²] - var, as rms_corrected."""
    ca, cb = np.isfinite(a), np.isfinite(b)
    m = ca & cb
    d = np.abs(a[m].astype(np.float64) - b[m])
    union = int((ca | cb).sum())
    e = {"mean": float(d.mean()) if d.size else float("nan"), "max": float(d.max()) if d.size else float("nan"),
         "rms": float(np.sqrt((d * d).mean())) if d.size else float("nan"), "covered": int(m.sum()),
         "coverage_diff": float((ca ^ cb).sum() / union) if union else float("nan")}
    if var is not None and d.size:
        e["rms_corrected"] = float(np.sqrt(max(0.0, (d * d).mean() - var[m].mean())))
    return e


def mc_variance(p, n):
    """The variance of an n-ray Monte Carlo AO (hits/n, binomial), estimated
    without bias from its value p: p(1 - p)/(n - 1)."""
    p = np.where(np.isfinite(p), p, 0).astype(np.float64)
    return p * (1 - p) / (n - 1)
