"""`scripts/bench-spheres --translucent`: zsweep's translucent sphere modes on
the test sets C1-C4, one thread each (the seed's Table 5 analogue), their
error against `sorted` exact as a function of the tolerance t and the layer
cap, VTK's depth peeling and the Embree reference.

Per set, on zsweep reference's automatic perspective camera (and, with
--frames N > 1, N - 1 more frames of bench_spheres.py's orbit; the Table 5
rows are then means over the frames):
- Table 5 rows: sorted (t 8, cap 32: the defaults), sorted exact (t 0, no
  cap), peel (t 8, 32 layers), dual_peel (32 layers), weighted, and sorted
  with `surfaces: front` (t 8 and exact), each one `zsweep render` process,
  time_ms.total (loading the set and the grid are not in it), the stats'
  `translucency` counts and peak RSS;
- the error sweep (automatic camera only): peel over t x cap, sorted over t,
  dual_peel over the cap, weighted, each compared with sorted exact (max abs
  and RMSE over R, G, B, A: `zsweep compare`'s formula, in process, on the
  renders' uncompressed TIFFs; checked once per set against `zsweep
  compare`); the t/2-levels bound is
  checked on every row, and whether it is guaranteed: the tolerance stop
  alone keeps a pixel within t/510 (t/2 8-bit levels); a cap of n layers
  keeps that only when every translucent sphere has alpha >= 1 - (t/510)^(1/n);
- VTK (--vtk): vtkOpenGLSphereMapper with the RGBA scalars' alpha, depth
  peeling (32 peels, occlusion ratio 0) on llvmpipe, one thread; one worker
  per set (bench_spheres.vtk_worker), a warm-up frame first;
- Embree (--embree): `zsweep reference` on the sorted-exact scene (it
  composites every crossing; it takes the scene's camera), one thread.
Renders are bounded by --render-timeout (the exact ones, which every error
row needs, by --exact-timeout); a peel (dual_peel) row whose
smaller-or-equal cap and larger-or-equal t timed out is skipped, not run.
"""
import concurrent.futures
import json
import os
import shutil
import struct
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_spheres as bs  # noqa: E402
from bench_common import write_csv  # noqa: E402

ROOT = bs.ROOT
EPS = 2e-6        # float rounding between two exact composites (dual_peel to completion: <= 1e-6)
FLOOR = 1e-9      # RMSE 0 is plotted here (log scale)
# --quick: C2's maximal balls are deeply nested (a 256² pixel crosses hundreds
# of surfaces even with a few hundred spheres; exhaustive peeling of 20,000 of
# them takes minutes), so its quick set is small.
QUICK = dict(bs.QUICK, c2=100)

# Table 5 rows: (label, mode, t, cap, surfaces)
TABLE5 = [("sorted", "sorted", 8, 32, "both"), ("sorted exact", "sorted", 0, 0, "both"),
          ("peel", "peel", 8, 32, "both"), ("dual_peel", "dual_peel", 0, 32, "both"),
          ("weighted", "weighted", 0, 0, "both"), ("sorted front", "sorted", 8, 32, "front"),
          ("sorted front exact", "sorted", 0, 0, "front")]
SWEEPS = {"full": {"peel_t": [16, 8, 4, 2, 0], "caps": [8, 16, 32, 64, 0], "sorted_t": [16, 8, 4, 2]},
          "small": {"peel_t": [8, 0], "caps": [8, 32, 0], "sorted_t": [8]}}


def alpha_n(t, n):
    """The smallest alpha for which n layers reach 1 - A <= t/510."""
    return 1.0 - (t / 510.0) ** (1.0 / n) if n else 0.0


def alpha_stats(path):
    """(smallest alpha in (0, 1), translucent, opaque, clear) over the set's
    float alphas, as the renderer reads them (alpha >= 1 opaque, <= 0 clear)."""
    with open(path, "rb") as f:
        head = f.read(24)
    fields = int(np.frombuffer(head[8:12], "<u4")[0])
    count = int(np.frombuffer(head[16:24], "<u8")[0])
    if fields != 8:
        return float("nan"), 0, count, 0
    a = np.memmap(path, dtype="<f4", mode="r", offset=24, shape=(count, fields))
    amin, tr, op, cl = float("inf"), 0, 0, 0
    for i in range(0, count, 4_000_000):
        al = np.asarray(a[i:i + 4_000_000, 7], dtype=np.float64)
        m = (al > 0) & (al < 1)
        tr += int(m.sum())
        op += int((al >= 1).sum())
        cl += int((~(al > 0)).sum())
        if m.any():
            amin = min(amin, float(al[m].min()))
    return (amin if tr else float("nan")), tr, op, cl


def read_tiff(path):
    """R, G, B, A (h x w x 4 float32) of an uncompressed float TIFF as zsweep
    writes it with `--compression none` (tiles or strips, samples contiguous)."""
    b = open(path, "rb").read()
    bo = {b"II": "<", b"MM": ">"}[b[:2]]
    (off,) = struct.unpack(bo + "I", b[4:8])
    (n,) = struct.unpack(bo + "H", b[off:off + 2])
    tags = {}
    for i in range(n):
        tag, typ, cnt, val = struct.unpack(bo + "HHI4s", b[off + 2 + 12 * i:off + 14 + 12 * i])
        if typ in (3, 4):  # SHORT, LONG
            size = (2 if typ == 3 else 4) * cnt
            raw = val if size <= 4 else b[struct.unpack(bo + "I", val)[0]:][:size]
            tags[tag] = struct.unpack(bo + ("H" if typ == 3 else "I") * cnt, raw[:size])
    w, h, spp = tags[256][0], tags[257][0], tags[277][0]
    if tags.get(259, (1,))[0] != 1 or set(tags[258]) != {32} or set(tags.get(339, (1,))) != {3} \
            or tags.get(284, (1,))[0] != 1 or spp < 4:
        raise ValueError(f"{path}: not an uncompressed float RGBA TIFF")
    img = np.empty((h, w, spp), np.float32)
    dt = np.dtype(bo + "f4")
    if 322 in tags:  # tiles
        tw, th = tags[322][0], tags[323][0]
        across = (w + tw - 1) // tw
        for k, o in enumerate(tags[324]):
            y, x = (k // across) * th, (k % across) * tw
            t = np.frombuffer(b, dt, tw * th * spp, o).reshape(th, tw, spp)
            img[y:y + th, x:x + tw] = t[:min(th, h - y), :min(tw, w - x)]
    else:
        rps = tags.get(278, (h,))[0]
        for k, o in enumerate(tags[273]):
            rows = min(rps, h - k * rps)
            img[k * rps:k * rps + rows] = np.frombuffer(b, dt, rows * w * spp, o).reshape(rows, w, spp)
    return img[:, :, :4]


def compare_images(a, b):
    """`zsweep compare A B`'s max abs and RMSE over R, G, B, A
    (src/image/image_compare.cpp), in process: one zsweep process costs
    ~0.5 s of start-up, and a set has ~40 images to compare."""
    try:
        e = np.abs(read_tiff(a).astype(np.float64) - read_tiff(b).astype(np.float64))
    except (OSError, ValueError, KeyError) as x:
        print(f"compare {a} {b}: {x}", file=sys.stderr)
        return float("nan"), float("nan")
    return float(np.nan_to_num(e, nan=np.inf).max()), float(np.sqrt((e * e).mean()))


def key(v):
    """What a variant's image depends on (sorted ignores the cap; dual_peel
    and weighted the tolerance; weighted both)."""
    m = v["mode"]
    return (m, v["t"] if m in ("sorted", "peel") else None, v["cap"] if m in ("peel", "dual_peel") else None,
            v["surfaces"])


def tag(v):
    k = key(v)
    return k[0] + (f"-t{k[1]}" if k[1] is not None else "") + (f"-n{k[2]}" if k[2] is not None else "") + \
        ("-front" if v["surfaces"] == "front" else "")


def variant(mode, t, cap, surfaces="both"):
    return {"mode": mode, "t": t, "cap": cap, "surfaces": surfaces}


def render(scene_path, out, budget, repeat, timeout):
    stats = out + ".stats.json"
    if os.path.exists(stats):
        os.remove(stats)
    cmd = [bs.ZSWEEP, "render", scene_path, "-o", out, "--threads", "1", "--frames", str(repeat),
           "--stats", stats, "--memory-budget", str(budget), "--compression", "none"]
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"exit_status": f"timeout after {timeout:g} s", "timeout": True}
    row = {"exit_status": p.returncode, "process_s": round(time.perf_counter() - t0, 3)}
    if p.returncode != 0:
        err = p.stderr.strip().splitlines()
        row["error"] = err[-1][:200] if err else ""
        sys.stderr.write(f"zsweep failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}\n")
        return row
    with open(stats) as f:
        j = json.load(f)
    tr = j.get("translucency", {})
    row.update({"ms": j["time_ms"]["total"], "setup_ms": j["time_ms"].get("setup"),
                "peak_rss_mb": round(j.get("peak_rss_bytes", 0) / 2**20, 1),
                "rendered_pixels": j.get("rendered_pixels"), "fragments": j.get("fragments")})
    for k in ("passes", "layers_max", "layers_mean", "fragments_composited", "pixels_stopped", "spheres_clear",
              "flushes", "pending_peak"):
        row[k] = tr.get(k)
    return row


def run_reference(scene_path, out, timeout):
    stats = out + ".stats.json"
    cmd = ["/usr/bin/time", "-f", "MAXRSS %M", bs.ZSWEEP, "reference", scene_path, "-o", out, "--threads", "1",
           "--stats", stats]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"error": f"timeout after {timeout:g} s"}
    if p.returncode != 0:
        return {"error": f"exit {p.returncode}: {p.stderr.strip()[-200:]}"}
    with open(stats) as f:
        t = json.load(f)["time_ms"]
    rss = [ln for ln in p.stderr.splitlines() if ln.startswith("MAXRSS ")]
    return {"build_ms": t["build"], "trace_ms": t["trace"],
            "peak_rss_mb": round(int(rss[-1].split()[1]) / 1024, 1) if rss else float("nan")}


def sweep_variants(kind):
    s = SWEEPS[kind]
    vs = [variant("peel", t, cap) for t in s["peel_t"] for cap in s["caps"]]
    vs += [variant("sorted", t, 32) for t in s["sorted_t"]]
    vs += [variant("dual_peel", 0, cap) for cap in s["caps"]]
    return vs + [variant("weighted", 0, 0)]


def exact_timeout(a):
    return a.exact_timeout or a.render_timeout


def skipped_by(v, timeouts):
    """A timed-out run that does less work than v (peel: t >= v's, cap
    <= v's, 0 meaning none; dual_peel: cap <= v's), or None."""
    def covers(cap, c2):
        return cap == 0 or (c2 != 0 and cap >= c2)
    for w in timeouts:
        if w["mode"] == v["mode"] == "peel" and v["t"] <= w["t"] and covers(v["cap"], w["cap"]):
            return w
        if w["mode"] == v["mode"] == "dual_peel" and covers(v["cap"], w["cap"]):
            return w
    return None


def bound_row(v, r, amin):
    """The t/2-levels check of one error row."""
    m, t, cap = v["mode"], v["t"], v["cap"]
    out = {"alpha_min": amin}
    if m in ("peel", "sorted"):
        b = t / 2
        capped = m == "peel" and cap != 0
        out["alpha_n"] = alpha_n(t, cap) if capped else ""
        out["guaranteed"] = "yes" if not capped or amin >= alpha_n(t, cap) else "no"
    elif m == "dual_peel" and cap == 0:  # to completion: exact up to rounding
        b = 0.0
        out["alpha_n"] = ""
        out["guaranteed"] = "yes"
    else:
        b = None
        out["alpha_n"] = ""
        out["guaranteed"] = "no"
    out["bound_levels"] = b if b is not None else ""
    mx = r.get("max_abs")
    if isinstance(mx, float) and mx == mx:
        out["max_abs_levels"] = mx * 255
        out["within"] = "" if b is None else ("yes" if mx <= b / 255 + EPS else "no")
    else:
        out["max_abs_levels"] = ""
        out["within"] = ""
    out["violation"] = "BUG" if out["guaranteed"] == "yes" and out["within"] == "no" else ""
    return out


# ---------------------------------------------------------------- VTK check (runs in the worker)

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


# ---------------------------------------------------------------- one set

class SetRun:
    """One set's renders, each run once per (frame, what its image depends on)."""

    def __init__(self, a, name, size, path, img, scenes):
        self.a, self.name, self.size, self.path, self.img, self.scenes = a, name, size, path, img, scenes
        self.repeat = a.repeat or 1
        self.done = {}      # (frame, key) -> result dict
        self.timeouts = []  # variants that timed out (automatic camera)

    def run(self, fname, cam, v):
        k = (fname, key(v))
        if k in self.done:
            return self.done[k]
        sc = bs.scene(self.path, cam, self.size, self.a.memory_budget)
        sc["render"].update({"mode": v["mode"], "tolerance": v["t"], "max_layers": v["cap"],
                             "surfaces": v["surfaces"]})
        base = f"{self.name}-{fname}-{tag(v)}"
        sp = os.path.join(self.scenes, base + ".json")
        with open(sp, "w") as f:
            json.dump(sc, f, indent=1)
        w = skipped_by(v, self.timeouts) if fname == "auto" else None
        image = os.path.join(self.img, base + ".tif")
        if w:
            r = {"exit_status": f"skipped: {w['mode']} t={w['t']} cap={w['cap']} timed out"}
        else:
            exact = v["mode"] == "sorted" and v["t"] == 0
            r = render(sp, image, self.a.memory_budget, self.repeat,
                       exact_timeout(self.a) if exact else self.a.render_timeout)
            if r.get("timeout") and fname == "auto":
                self.timeouts.append(v)
        r.update(scene=sp, image=image)
        self.done[k] = r
        status = r["exit_status"]
        print(f"{self.name} {fname} {tag(v)}: " + (f"{r['ms']:.1f} ms, layers max {r.get('layers_max')}, "
                                                    f"peak RSS {r['peak_rss_mb']:.0f} MiB"
                                                    if status == 0 else str(status)), flush=True)
        return r

    def error_vs_exact(self, fname, v):
        r = self.done[(fname, key(v))]
        ref = self.done.get((fname, key(variant("sorted", 0, 0, v["surfaces"]))))
        if r is ref and r.get("exit_status") == 0:
            r["max_abs"], r["rmse"] = 0.0, 0.0
        elif r.get("exit_status") == 0 and ref and ref.get("exit_status") == 0 and "max_abs" not in r:
            r["max_abs"], r["rmse"] = compare_images(r["image"], ref["image"])


def run_set(a, name, count, size, cams, img, scenes, vtk_rows, emb_rows):
    path = os.path.join(a.out, f"{name}-{count}.sphb")
    amin, ntr, nop, ncl = alpha_stats(path)
    print(f"{name}: {count:,} spheres, {ntr:,} translucent (alpha min {amin:.6f}), {nop:,} opaque, {ncl:,} clear",
          flush=True)
    S = SetRun(a, name, size, path, img, scenes)
    vtkp = bs.VtkProcess(path, size, S.repeat, a.vtk_timeout, a.vtk_frame_timeout, a.vtk_budget,
                         extra=("--vtk-translucent",)) if a.vtk else None
    warm = {}
    if vtkp:
        warm = vtkp.frame(dict(cams[0][1], _warmup=True))
        print(f"{name}: VTK " + (f"loaded in {warm['load_s']:.1f} s, warm-up frame {warm['warmup_s']:.1f} s"
                                 if "error" not in warm else warm["error"]), flush=True)
        if "warmup_s" in warm:  # a timed frame peels as long as the warm-up did (and the check renders twice)
            vtkp.frame_timeout = max(vtkp.frame_timeout, 2.5 * warm["warmup_s"] + 60)
    for fname, cam in cams:
        for label, mode, t, cap, surf in TABLE5:
            S.run(fname, cam, variant(mode, t, cap, surf))
        if vtkp:
            c = dict(cam)
            if fname == "auto":
                c["_png"] = os.path.join(img, f"{name}-auto-vtk.png")
            v = vtkp.frame(c)
            row = {"set": name, "spheres": count, "size": size, "frame": fname, "renderer": "vtk",
                   "label": "VTK depth peeling (32 peels)", "surfaces": "front"}
            if "error" in v:
                row["exit_status"] = v["error"]
            else:
                row.update({k: v.get(k) for k in ("ms", "peak_rss_mb", "depth_peeling", "translucent_actor",
                                                  "rmse_vs_opaque", "max_abs_vs_opaque", "opaque_depth_peeling")},
                           exit_status=0, rendered_pixels=v.get("pixels_hit"))
                if "warmup_s" in warm:
                    row.update(warmup_s=warm["warmup_s"], load_s=warm["load_s"])
                if c.get("_png"):
                    row["png"] = c["_png"]
            vtk_rows.append(row)
            print(f"{name} {fname} VTK: " + (f"{row['ms']:.0f} ms, depth peeling used {row['depth_peeling']}"
                                             if row["exit_status"] == 0 else str(row["exit_status"])), flush=True)
    if vtkp:
        vtkp.close()
    sweep = sweep_variants(a.translucent_sweep or ("small" if a.quick else "full"))
    auto = cams[0][1]
    for v in sweep:
        S.run("auto", auto, v)
    emb = {}
    if a.embree:
        ref = S.done[("auto", key(variant("sorted", 0, 0)))]
        out = os.path.join(img, f"{name}-auto-embree.exr")
        emb = run_reference(ref["scene"], out, exact_timeout(a))
        emb.update(set=name, spheres=count, size=size, frame="auto", renderer="embree",
                   label="Embree reference (every crossing)", surfaces="both",
                   exit_status=emb.get("error", 0), ms=emb.get("trace_ms"), setup_ms=emb.get("build_ms"))
        if "error" not in emb and ref.get("exit_status") == 0:
            emb["vs_exact_max_abs"], emb["vs_exact_rmse"] = bs.compare(out, ref["image"])
        emb_rows.append(emb)
        print(f"{name} Embree: " + (f"build {emb['build_ms']:.0f} ms, trace {emb['trace_ms']:.0f} ms"
                                    if "error" not in emb else emb["error"]), flush=True)
    # Errors: every rendered variant against sorted exact of its frame and surfaces.
    for fname, _ in cams:
        for label, mode, t, cap, surf in TABLE5:
            S.error_vs_exact(fname, variant(mode, t, cap, surf))
    for v in sweep:
        S.error_vs_exact("auto", v)
    fe = S.done.get(("auto", key(variant("sorted", 0, 0, "front"))))
    for row in vtk_rows:
        if row["set"] == name and row.get("png") and fe and fe.get("exit_status") == 0:
            row["rgb_vs_front_exact_max_abs"], row["rgb_vs_front_exact_rmse"] = \
                bs.compare(row["png"], fe["image"], "--rgb")
    # The in-process compare against zsweep compare, once per set.
    r, ref = S.done[("auto", key(variant("sorted", 8, 32)))], S.done[("auto", key(variant("sorted", 0, 0)))]
    check = ""
    if r.get("exit_status") == 0 and ref.get("exit_status") == 0:
        m, e = bs.compare(r["image"], ref["image"])
        check = "yes" if abs(m - r["max_abs"]) <= 1e-9 and abs(e - r["rmse"]) <= 1e-9 else "NO"
        if check != "yes":
            print(f"*** {name}: in-process compare ({r['max_abs']}, {r['rmse']}) != zsweep compare ({m}, {e})",
                  flush=True)
    mode_rows = []
    for fname, _ in cams:
        for label, mode, t, cap, surf in TABLE5:
            v = variant(mode, t, cap, surf)
            r = S.done[(fname, key(v))]
            row = {"set": name, "spheres": count, "size": size, "frame": fname, "renderer": "zsweep", "label": label,
                   "mode": mode, "t": t if mode in ("sorted", "peel") else "",
                   "cap": cap if mode in ("peel", "dual_peel") else "", "surfaces": surf}
            row.update({k: x for k, x in r.items() if k not in ("scene", "image", "timeout")})
            if mode in ("peel", "dual_peel") and isinstance(r.get("ms"), float) and r.get("layers_max"):
                row["ms_per_layer"] = r["ms"] / r["layers_max"]
            mode_rows.append(row)
    err_rows = []
    for v in [variant("sorted", 0, 0)] + sweep:
        r = S.done[("auto", key(v))]
        row = {"set": name, "spheres": count, "size": size, "frame": "auto", "mode": v["mode"],
               "t": v["t"] if v["mode"] in ("sorted", "peel") else "",
               "cap": v["cap"] if v["mode"] in ("peel", "dual_peel") else "",
               "reference": "yes" if v == variant("sorted", 0, 0) else ""}
        for k in ("ms", "passes", "layers_max", "layers_mean", "pixels_stopped", "peak_rss_mb", "exit_status",
                  "max_abs", "rmse"):
            row[k] = r.get(k, "")
        row.update(bound_row(v, r, amin))
        if row["violation"]:
            print(f"\n*** {name}: {v['mode']} t={v['t']} cap={v['cap']}: max abs {row['max_abs_levels']:.3f} "
                  f"levels exceeds the GUARANTEED t/2 = {row['bound_levels']} levels: a bug ***\n", flush=True)
        err_rows.append(row)
    stats = {"alpha_min": amin, "translucent": ntr, "opaque": nop, "clear": ncl, "compare_matches_zsweep": check}
    return mode_rows, err_rows, stats, emb


# ---------------------------------------------------------------- main

def replot(d, doc):
    """The plots again from DIR's CSVs (with --doc: into docs/bench)."""
    import csv
    from bench_spheres_translucent_tables import plots

    def num(v):
        try:
            x = float(v)
        except ValueError:
            return v
        return int(x) if x.is_integer() and "." not in v and "e" not in v else x

    def load(f):
        return [{k: num(v) for k, v in r.items()} for r in csv.DictReader(open(os.path.join(d, f)))]
    summary, errors = load("translucent-summary.csv"), load("translucent-errors.csv")
    for r in errors:
        if isinstance(r.get("ms"), int):
            r["ms"] = float(r["ms"])
    files = plots(summary, [], errors, [], [], d)
    if doc:
        for f in files:
            shutil.copy(f, os.path.join(ROOT, "docs", "bench", os.path.basename(f)))
    print("wrote", ", ".join(files))
    return 0


def main(a, ap):
    from bench_spheres_translucent_tables import all_cols, doc_lines, plots, summarize, write_doc_block
    if a.replot:
        return replot(a.replot, a.doc)
    size = a.size or (256 if a.quick else 1024)
    nframes = a.frames or 1
    sets = a.sets.split(",")
    for s in sets:
        if s not in bs.FULL:
            ap.error(f"unknown set {s} (c1, c2, c3, c4)")
    if a.counts:
        counts = [int(float(c)) for c in a.counts.split(",")]
        if len(counts) != len(sets):
            ap.error("--counts needs one count per set")
    else:
        counts = [(QUICK if a.quick else bs.FULL)[s] for s in sets]
    if a.threads and a.threads != "1":
        print("bench-spheres --translucent: one thread only (--threads ignored)", file=sys.stderr)
    os.makedirs(a.out, exist_ok=True)
    img, scenes = os.path.join(a.out, "images"), os.path.join(a.out, "translucent-scenes")
    os.makedirs(img, exist_ok=True)
    os.makedirs(scenes, exist_ok=True)
    started = time.perf_counter()
    mode_rows, err_rows, vtk_rows, emb_rows, summary, all_cams = [], [], [], [], [], []

    def one_set(name, count):
        path = os.path.join(a.out, f"{name}-{count}.sphb")
        if not os.path.exists(path):
            t = time.perf_counter()
            subprocess.run([bs.ZSWEEP, "spheres", "generate", name, "--count", str(count), "-o", path],
                           check=True, capture_output=True)
            print(f"{name}: generated {count:,} spheres in {time.perf_counter() - t:.1f} s", flush=True)
        lo, hi = bs.bounds(path)
        cams = [("auto", bs.auto_camera(lo, hi, size, size))]
        if nframes > 1:
            cams += [(f"f{k:03d}", c) for k, c in enumerate(bs.orbit(lo, hi, nframes)) if k > 0]
        return cams, run_set(a, name, count, size, cams, img, scenes, vtk_rows, emb_rows)

    # --quick (a smoke test: its times mean nothing) runs two sets at a time.
    par = 2 if a.quick and not a.vtk and not a.embree else 1
    with concurrent.futures.ThreadPoolExecutor(par) as setpool:
        futs = [setpool.submit(one_set, name, count) for name, count in zip(sets, counts)]
        for (name, count), fut in zip(zip(sets, counts), futs):
            all_cams, (mr, er, astats, emb) = fut.result()
            mode_rows += mr
            err_rows += er
            summary.append(summarize(name, count, size, mr, er, astats, vtk_rows, emb, a.memory_budget))
            # After every set: a run cut short keeps the sets it finished.
            write_csv(os.path.join(a.out, "translucent-modes.csv"),
                      all_cols(mode_rows + vtk_rows + [{k: v for k, v in e.items() if k != "error"}
                                                       for e in emb_rows]))
            write_csv(os.path.join(a.out, "translucent-errors.csv"), all_cols(err_rows))
            write_csv(os.path.join(a.out, "translucent-summary.csv"), all_cols(summary))
    files = plots(summary, mode_rows, err_rows, vtk_rows, emb_rows, a.out)
    wall = time.perf_counter() - started
    lines = doc_lines(a, summary, mode_rows, err_rows, vtk_rows, emb_rows, size, all_cams, wall, files)
    with open(os.path.join(a.out, "translucent-results.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    print(f"wrote {a.out}/translucent-modes.csv, translucent-errors.csv, translucent-summary.csv, "
          "translucent-results.md, " + ", ".join(os.path.basename(f) for f in files))
    if a.doc:
        os.makedirs(os.path.join(ROOT, "docs", "bench"), exist_ok=True)
        for f in files:
            shutil.copy(f, os.path.join(ROOT, "docs", "bench", os.path.basename(f)))
        write_doc_block(lines)
    bad = sum(s["bound_violations"] for s in summary)
    if bad:
        print(f"\n*** {bad} row(s) break a GUARANTEED t/2-levels bound (see 'BOUND VIOLATED') ***", flush=True)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(bs.main())
