"""`scripts/bench-spheres --ao`: ambient occlusion on the sphere sets C1-C4
and the protein 1hpv, one thread (the seed's Tables 6 and 7 analogues), its
error against two references as a function of the direction count and the map
size, and, side by side in the same run, VTK's screen-space AO (vtkSSAOPass on
llvmpipe) and Tachyon's ray-traced AO (bench_spheres_ao_ext.py).

Per set, one camera: zsweep reference's automatic perspective camera
(bench_spheres.auto_camera), written into every scene (and given to VTK and
Tachyon), square images so --size and --error-size frame the same view.
- Table 6 (--size, default 1024²): a Phong frame (no `ao` block) and an AO frame
  (--table-directions, --table-map-size), each `render --threads 1 --frames R`,
  best of the R whole frames (time_ms.total: visibility structures included);
  the maps (time_ms.ao_maps) are built once per process before the frames and
  are not in the frame time: they are reported apart;
- Table 7: time_ms.ao_maps and ao.map_bytes of the error grid's renders at
  --table-map-size, per direction count (the maps do not depend on the view or
  the image size); one thread, so the maps are built one after the other;
- the error grid (--error-size, default 512², to keep the references
  affordable): every direction count x map size (--grid cross: every count at
  --table-map-size and every map size at --table-directions), each render's AO
  channel against (a) `zsweep reference` on the same scene, the same directions
  traced exactly (the maps' error alone) and (b) `zsweep reference
  --ao-samples 4N`, a cosine-weighted Monte Carlo AO (the converged reference);
  mean and max |dAO| over the pixels covered in both images; the MC noise
  floor from a second reference with N samples (the streams are nested: the
  4N reference's first N rays are the N reference's), and analytically:
  hits/4N is binomial, so its error has std sqrt(AO (1 - AO) / 4N);
- --vtk and --tachyon (bench_spheres_ao_ext.py), at --error-size, against the
  same references; the ratios take our fastest configuration of the grid at
  an error (vs MC) no larger than theirs, per frame and with the maps
  amortised over --amortise frames.
References run with --ref-threads threads (they are not timed against us).
"""
import concurrent.futures
import json
import math
import os
import shutil
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_spheres as bs  # noqa: E402
import bench_spheres_ao_ext as ext  # noqa: E402
from bench_common import replace_block, write_csv  # noqa: E402

ROOT = bs.ROOT
PDB = "/usr/share/pymol/data/tut/1hpv.pdb"
QUICK = {"c1": 3000, "c2": 3000, "c3": 3000, "c4": 3375}
DOC_NAME, DOC_HEADING = "bench-spheres-ao", "## Ambient occlusion (`--ao`)"
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
        if s not in bs.FULL and s != "1hpv":
            ap.error(f"unknown set {s} (c1, c2, c3, c4, 1hpv)")
    if "1hpv" in c["sets"] and not os.path.exists(a.pdb):
        print(f"bench-spheres --ao: {a.pdb} missing (pymol-data): 1hpv left out", file=sys.stderr)
        c["sets"].remove("1hpv")
    if a.counts:
        counts = ints(a.counts)
        if len(counts) != len(c["sets"]):
            ap.error("--counts needs one count per set (1hpv's is ignored)")
    else:
        counts = [(QUICK if q else bs.FULL).get(s, 0) for s in c["sets"]]
    c["counts"] = dict(zip(c["sets"], counts))
    if a.grid == "cross":
        c["grid"] = sorted({(d, c["tmap"]) for d in c["dirs"]} | {(c["tdirs"], m) for m in c["maps"]})
    else:
        c["grid"] = [(d, m) for d in c["dirs"] for m in c["maps"]]
    return c


# ---------------------------------------------------------------- runs

def prepare(a, name, count):
    """(path, spheres, mean radius, lo, hi) of the set's .sphb in --out."""
    if name == "1hpv":
        path = os.path.join(a.out, "1hpv.sphb")
        cmd = [bs.ZSWEEP, "spheres", "convert", a.pdb, path]
    else:
        path = os.path.join(a.out, f"{name}-{count}.sphb")
        cmd = [bs.ZSWEEP, "spheres", "generate", name, "--count", str(count), "-o", path]
    if not os.path.exists(path):
        t = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        print(f"{name}: wrote {os.path.basename(path)} in {time.perf_counter() - t:.1f} s", flush=True)
    _, r, _ = bs.read_sphb(path)
    ok = np.isfinite(r) & (r > 0)
    lo, hi = bs.bounds(path)
    return path, int(len(r)), float(np.asarray(r[ok], np.float64).mean()), lo, hi


def write_scene(a, path, cam, size, dirs, mapsize, fname):
    sc = bs.scene(path, cam, size, a.memory_budget)
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
    cmd = [bs.ZSWEEP, "render", scene_path, "-o", out, "--threads", "1", "--frames", str(R), "--stats", stats,
           "--memory-budget", str(budget), "--compression", "none"]
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"exit_status": f"timeout after {timeout:g} s"}
    row = {"exit_status": p.returncode, "process_s": round(time.perf_counter() - t0, 3)}
    if p.returncode != 0:
        err = p.stderr.strip().splitlines()
        row["error"] = err[-1][:300] if err else ""
        sys.stderr.write(f"zsweep failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}\n")
        return row
    with open(stats) as f:
        j = json.load(f)
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
    cmd = [bs.ZSWEEP, "reference", scene_path, "-o", out, "--threads", str(threads), "--stats", stats]
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


# ---------------------------------------------------------------- one set

def run_set(a, c, name, log):
    count = c["counts"][name]
    path, n, rmean, lo, hi = prepare(a, name, count)
    img = os.path.join(a.out, "ao-images")
    cam = bs.auto_camera(lo, hi, c["esize"], c["esize"])
    R, budget, base = c["R"], a.memory_budget, os.path.join(img, name)
    res = {"set": name, "spheres": n, "mean_radius": rmean, "t6": [], "grid": [], "refs": [], "versus": []}
    common = {"set": name, "spheres": n}

    # Table 6: Phong, then AO with the table's directions and map size.
    sz = c["size"]
    ph = render(write_scene(a, path, cam, sz, 0, 0, f"{base}-phong-{sz}.json"), f"{base}-phong-{sz}.exr", R, budget,
                a.render_timeout)
    ao = render(write_scene(a, path, cam, sz, c["tdirs"], c["tmap"], f"{base}-ao-{sz}.json"),
                f"{base}-ao-{sz}.exr", R, budget, a.render_timeout)
    t6 = dict(common, size=sz, frames=R, directions=c["tdirs"], map_size=c["tmap"], phong_ms=ph.get("ms", ""),
              ao_ms=ao.get("ms", ""), maps_ms=ao.get("maps_ms", ""), map_mb=ao.get("map_mb", ""),
              phong_frame_ms=ph.get("frame_ms", ""), ao_frame_ms=ao.get("frame_ms", ""),
              rendered_pixels=ao.get("rendered_pixels", ""), peak_rss_mb=ao.get("peak_rss_mb", ""),
              ao_batches=ao.get("ao_batches", ""),
              phong_exit=ph["exit_status"], ao_exit=ao["exit_status"], error=ao.get("error", ph.get("error", "")))
    if bs.isnum(t6["phong_ms"]) and bs.isnum(t6["ao_ms"]):
        t6["ao_over_phong"] = t6["ao_ms"] / t6["phong_ms"]
    res["t6"].append(t6)
    log(f"{name}: {sz}² Phong {bs.fmt(ph.get('ms'))} ms, AO ({c['tdirs']} directions, map {c['tmap']}) "
        f"{bs.fmt(ao.get('ms'))} ms + maps {bs.fmt(ao.get('maps_ms'))} ms")

    # References at the error size: exact directions per count, Monte Carlo N and 4N.
    es = c["esize"]
    refs = {}
    for d in c["dirs"] + ["mc", "mc4"]:
        dd = c["tdirs"] if isinstance(d, str) else d
        samples = {"mc": c["N"], "mc4": 4 * c["N"]}.get(d, 0)
        sp = write_scene(a, path, cam, es, dd, c["tmap"], f"{base}-ref-{d}-{es}.json")
        out = f"{base}-ref-{d}-{es}.exr"
        if a.reuse_references and os.path.exists(out) and os.path.exists(out + ".stats.json") \
                and os.path.exists(out + ".json") and same_scene(sp, out + ".json"):
            t = json.load(open(out + ".stats.json"))["time_ms"]
            r = {"exit_status": 0, "build_ms": t["build"], "trace_ms": t["trace"], "threads": "reused"}
        else:
            r = reference(sp, out, samples, a.ref_threads, a.ref_timeout)
            shutil.copy(sp, out + ".json")  # what it was traced from (--reuse-references)
        r.update(common, size=es, kind="exact directions" if not samples else "Monte Carlo", directions=dd
                 if not samples else "", samples=samples or "")
        if r["exit_status"] == 0:
            refs[d] = read_ao(out)
        res["refs"].append(r)
        log(f"{name}: reference {d if samples == 0 else f'MC {samples} rays'}: " +
            (f"trace {r['trace_ms']:.0f} ms ({r['threads']} threads)" if r["exit_status"] == 0 else
             str(r["exit_status"])))
    if "mc" in refs and "mc4" in refs:  # the MC reference's own noise
        m4 = refs["mc4"]
        cov = np.isfinite(m4) & np.isfinite(refs["mc"])
        p = m4[cov].astype(np.float64)
        dlt = refs["mc"][cov] - p
        floor = SQ2PI * float(np.sqrt(p * (1 - p) / (4 * c["N"])).mean())
        res["refs"][-1].update(noise_floor_mean=floor, n_vs_4n_mean=float(np.abs(dlt).mean()),
                               n_vs_4n_expected=SQ2PI * float(np.sqrt(0.75 * p * (1 - p) / c["N"]).mean()),
                               noise_floor_from_n=SQ2PI * float(np.sqrt((dlt * dlt).mean() / 3)))
        res["noise_floor"] = floor
    mc = refs.get("mc4")
    var = mc_variance(mc, 4 * c["N"]) if mc is not None else None
    dir_err = {d: error(refs[d], mc, var) if d in refs and mc is not None else None for d in c["dirs"]}

    # The error grid.
    for d, m in c["grid"]:
        sp = write_scene(a, path, cam, es, d, m, f"{base}-d{d}-m{m}-{es}.json")
        out = f"{base}-d{d}-m{m}-{es}.exr"
        r = render(sp, out, R, budget, a.render_timeout)
        row = dict(common, size=es, directions=d, map_size=m, frames=R)
        row.update({k: r.get(k, "") for k in ("exit_status", "ms", "maps_ms", "map_mb", "ao_batches", "frame_ms",
                                               "peak_rss_mb", "rendered_pixels", "error")})
        if bs.isnum(row["ms"]) and bs.isnum(row["maps_ms"]):
            row["amortised_ms"] = row["ms"] + row["maps_ms"] / a.amortise
        if r["exit_status"] == 0:
            mine = read_ao(out)
            for key, ref, v in (("exact", refs.get(d), None), ("mc", mc, var)):
                if ref is not None:
                    e = error(mine, ref, v)
                    row.update({f"vs_{key}_mean": e["mean"], f"vs_{key}_max": e["max"], f"vs_{key}_rms": e["rms"],
                                f"vs_{key}_coverage_diff": e["coverage_diff"]})
                    if "rms_corrected" in e:
                        row["vs_mc_rms_corrected"] = e["rms_corrected"]
            if dir_err.get(d):
                row["exact_dirs_vs_mc_mean"] = dir_err[d]["mean"]
                row["exact_dirs_vs_mc_max"] = dir_err[d]["max"]
                row["exact_dirs_vs_mc_rms_corrected"] = dir_err[d].get("rms_corrected", "")
        res["grid"].append(row)
        log(f"{name}: {d} directions, map {m}: frame {bs.fmt(r.get('ms'))} ms, maps {bs.fmt(r.get('maps_ms'))} ms; "
            f"mean |dAO| vs exact {bs.fmt(row.get('vs_exact_mean'), 4)}, vs MC {bs.fmt(row.get('vs_mc_mean'), 4)}"
            + ("" if r["exit_status"] == 0 else f" [{r['exit_status']}: {r.get('error', '')}]"))

    # VTK's SSAO and Tachyon, same spheres, camera and size, one thread.
    images = {}
    if a.vtk:
        for v in ext.run_vtk(a, path, cam, es, R, rmean, f"{base}-vtk-{es}"):
            res["versus"].append(ext.versus_row(common, es, v, refs.get(c["tdirs"]), mc, error, a.amortise, var))
            x = res["versus"][-1]
            images[id(x)] = v.get("ao")
            log(f"{name}: VTK {v['params']}: " +
                (f"{v['ms']:.1f} ms, mean |dAO| vs MC {bs.fmt(x.get('vs_mc_mean'), 4)}, coverage differs on "
                 f"{bs.fmt(100 * x.get('coverage_diff', float('nan')), 2)} %" if "ms" in v else v.get("error", "failed")))
    if a.tachyon:
        body = ext.tachyon_body(path, f"{base}-tachyon-body.dat")
        best = min((g["vs_mc_mean"] for g in res["grid"] if bs.isnum(g.get("vs_mc_mean"))), default=0.0)
        done = None  # the last count that ran
        for s in sorted(c["tach"]):
            # Ascending counts: stop once Tachyon is at or below our best error (every
            # configuration of ours then has its match); skip a count whose predicted
            # time (linear in the count) is over --tachyon-timeout.
            if done and bs.isnum(done.get("vs_mc_mean")) and done["vs_mc_mean"] <= best:
                break
            if done and done["ms"] * s / done["samples"] > a.tachyon_timeout * 1000:
                t = {"renderer": "tachyon", "samples": s, "error": "skipped: predicted over --tachyon-timeout"}
            else:
                t = ext.run_tachyon(a, body, cam, es, s, f"{base}-tachyon-s{s}-{es}")
            res["versus"].append(ext.versus_row(common, es, t, refs.get(c["tdirs"]), mc, error, a.amortise, var))
            images[id(res["versus"][-1])] = t.get("ao")
            if "ms" in t:
                done = res["versus"][-1]
            log(f"{name}: Tachyon {s} samples: " +
                (f"trace {t['ms']:.0f} ms (parse {t['parse_ms']:.0f}, preprocessing {t['preprocess_ms']:.0f}), "
                 f"mean |dAO| vs MC {bs.fmt(res['versus'][-1].get('vs_mc_mean'), 4)}, coverage differs on "
                 f"{bs.fmt(100 * res['versus'][-1].get('coverage_diff', float('nan')), 2)} %"
                 if "ms" in t else t.get("error", "failed")))
        if not a.keep_tachyon_scene and os.path.exists(body):
            os.remove(body)
    # The images side by side: MC, the exact directions, ours, VTK's and Tachyon's most accurate.
    panels = [(f"Monte Carlo, {4 * c['N']} rays", mc), (f"{c['tdirs']} directions, exact", refs.get(c["tdirs"]))]
    own = f"{base}-d{c['tdirs']}-m{c['tmap']}-{es}.exr"
    if os.path.exists(own):
        panels.append((f"ours, {c['tdirs']} directions, maps {c['tmap']}²", read_ao(own)))
    for who in ("vtk-ssao", "tachyon"):
        rows = [(v["vs_mc_mean"], i) for i, v in enumerate(res["versus"])
                if v["renderer"] == who and bs.isnum(v.get("vs_mc_mean"))]
        if rows:
            v = res["versus"][min(rows)[1]]
            panels.append((f"VTK SSAO, radius {v['params'].split()[2]} r̄" if who == "vtk-ssao"
                           else f"Tachyon, {int(v['samples'])} samples", images.get(id(v))))
    res["pngs"] = [ext.compare_png(os.path.join(a.out, f"ao-compare-{name}.png"), panels, name)]
    return res


# ---------------------------------------------------------------- tables

def table7(results, c):
    rows = []
    for r in results:
        for g in r["grid"]:
            if g["map_size"] == c["tmap"]:
                rows.append({"set": r["set"], "spheres": r["spheres"], "directions": g["directions"],
                             "map_size": g["map_size"], "maps_ms": g.get("maps_ms", ""), "map_mb": g.get("map_mb", ""),
                             "maps_ms_per_direction": g["maps_ms"] / g["directions"] if bs.isnum(g.get("maps_ms"))
                             else "", "exit_status": g["exit_status"], "error": g.get("error", "")})
    return rows


def tachyon_at(ta, err, key):
    """Tachyon's time (`key`) and sample count at a mean error vs MC of err:
    interpolated (log-log) between the two sample counts around err; "≥ " its
    largest count's when even that is less accurate (a lower bound), "≤ " its
    smallest count's when that is already more accurate (an upper bound).
    ta: ascending sample counts."""
    for lo, hi in zip(ta, ta[1:]):
        if hi["vs_mc_mean"] <= err < lo["vs_mc_mean"]:
            w = math.log(lo["vs_mc_mean"] / err) / math.log(lo["vs_mc_mean"] / hi["vs_mc_mean"])
            return {"ms": math.exp((1 - w) * math.log(lo[key]) + w * math.log(hi[key])),
                    "samples": math.exp((1 - w) * math.log(lo["samples"]) + w * math.log(hi["samples"])),
                    "first": hi["samples"], "bound": ""}
    if err >= ta[0]["vs_mc_mean"]:
        return {"ms": ta[0][key], "samples": ta[0]["samples"], "first": ta[0]["samples"], "bound": "≤ "}
    return {"ms": ta[-1][key], "samples": ta[-1]["samples"], "first": "", "bound": "≥ "}


def ratios(results, a):
    """Per set, per frame and with the preprocessing amortised: VTK (its most
    accurate radius) and Tachyon against ours at an error vs MC no larger
    than theirs: each against our best configuration for it, and one
    configuration of ours against both (at most VTK's error; Tachyon at its
    cheapest count no more accurate than needed) - the goal's reading."""
    out = []
    for r in results:
        ours = [g for g in r["grid"] if bs.isnum(g.get("vs_mc_mean")) and bs.isnum(g.get("ms"))]
        vt = sorted([v for v in r["versus"] if v["renderer"] == "vtk-ssao" and bs.isnum(v.get("vs_mc_mean"))],
                    key=lambda v: v["vs_mc_mean"])[:1]  # its most accurate radius
        ta = sorted([v for v in r["versus"] if v["renderer"] == "tachyon" and bs.isnum(v.get("vs_mc_mean"))],
                    key=lambda v: v["samples"])
        if not ours or (not vt and not ta):
            continue
        for key in ("ms", "amortised_ms"):
            row = {"set": r["set"], "time": "per frame" if key == "ms" else f"amortised over {a.amortise:g} frames"}
            mine = [g for g in ours if bs.isnum(g.get(key))]
            if vt:
                v = vt[0]
                fit = [g for g in mine if g["vs_mc_mean"] <= v["vs_mc_mean"]]
                row.update(vtk_ms=v[key], vtk_err=v["vs_mc_mean"], vtk_params=v.get("params", ""))
                if fit:
                    g = min(fit, key=lambda g: g[key])
                    row.update(ours_for_vtk=f"{g['directions']}/{g['map_size']}", ours_for_vtk_ms=g[key],
                               ours_for_vtk_err=g["vs_mc_mean"], vtk_over_ours=v[key] / g[key])
                else:
                    row["vtk_over_ours"] = "no configuration of ours reaches VTK's error"
            if ta:
                best = None
                for g in mine:
                    t = tachyon_at(ta, g["vs_mc_mean"], key)
                    if best is None or t["ms"] / g[key] > best[0]:
                        best = (t["ms"] / g[key], g, t)
                q, g, t = best
                row.update(tachyon_samples=t["samples"], tachyon_first_samples_below=t["first"], tachyon_ms=t["ms"],
                           ours_for_tachyon=f"{g['directions']}/{g['map_size']}", ours_for_tachyon_ms=g[key],
                           ours_for_tachyon_err=g["vs_mc_mean"], tachyon_over_ours=q, tachyon_bound=t["bound"])
            # One configuration of ours against both: the one whose smaller ratio is largest.
            both = None
            for g in mine:
                if vt and g["vs_mc_mean"] > vt[0]["vs_mc_mean"]:
                    continue
                rv = vt[0][key] / g[key] if vt else float("inf")
                t = tachyon_at(ta, g["vs_mc_mean"], key) if ta else None
                rt = t["ms"] / g[key] if t else float("inf")
                if both is None or min(rv, rt) > both[0]:
                    both = (min(rv, rt), g, rv, rt, t)
            if both:
                _, g, rv, rt, t = both
                row["one_config"] = f"{g['directions']}/{g['map_size']}"
                row["one_config_err"] = g["vs_mc_mean"]
                row["one_config_vtk_over_ours"] = rv if vt else ""
                row["one_config_tachyon_over_ours"] = rt if ta else ""
                row["one_config_tachyon_samples"] = t["samples"] if t else ""
                row["one_config_tachyon_bound"] = t["bound"] if t else ""
                # A "≤" Tachyon ratio is an upper bound: it cannot show the goal.
                row["goal_5x"] = "yes" if min(rv, rt) >= 5 and not (t and t["bound"] == "≤ ") else "no"
            else:
                row["goal_5x"] = "no (no configuration of ours reaches VTK's error)"
            out.append(row)
    return out


def all_cols(rows):
    cols = []
    for r in rows:
        for k in r:
            if k not in cols:
                cols.append(k)
    return [{k: r.get(k, "") for k in cols} for r in rows]


def save(a, results, c, check):
    t6 = [x for r in results for x in r["t6"]]
    grid = [x for r in results for x in r["grid"]]
    refs = [x for r in results for x in r["refs"]]
    vs = [x for r in results for x in r["versus"]]
    tables = {"ao-table6.csv": t6, "ao-table7.csv": table7(results, c), "ao-error.csv": grid,
              "ao-references.csv": refs, "ao-versus.csv": vs, "ao-ratios.csv": ratios(results, a),
              "ao-tachyon-check.csv": check}
    for f, rows in tables.items():
        if rows:
            write_csv(os.path.join(a.out, f), all_cols(rows))
    return tables


# ---------------------------------------------------------------- main

def main(a, ap):
    if a.replot:
        return replot(a)
    c = config(a, ap)
    os.makedirs(os.path.join(a.out, "ao-images"), exist_ok=True)
    if a.tachyon and not shutil.which(a.tachyon_bin):
        ap.error(f"--tachyon needs {a.tachyon_bin} (apt-get install tachyon-bin-nox)")
    started = time.perf_counter()
    results, check = [], []
    if a.tachyon:
        check = ext.tachyon_check(a, os.path.join(a.out, "ao-images", "tachyon-check"), sys.modules[__name__])
        for r in check:
            print(f"Tachyon check, {r['scene']}, {r.get('samples')} samples: mean AO {bs.fmt(r.get('tachyon_mean_ao'), 4)} "
                  f"(MC {bs.fmt(r.get('mc_mean_ao'), 4)}), mean |dAO| {bs.fmt(r.get('vs_mc_mean'), 4)}, coverage "
                  f"differs on {bs.fmt(100 * r.get('coverage_diff', float('nan')), 2)} %" +
                  (f" [{r['error']}]" if r.get("error") else ""), flush=True)

    def log(msg):
        print(msg, flush=True)

    # --quick (a smoke test: its times mean nothing) runs two sets at a time.
    par = 2 if a.quick and not a.vtk and not a.tachyon else 1
    with concurrent.futures.ThreadPoolExecutor(par) as pool:
        futs = [pool.submit(run_set, a, c, s, log) for s in c["sets"]]
        for f in futs:
            results.append(f.result())
            tables = save(a, results, c, check)  # after every set: a run cut short keeps the sets it finished
    files = ext.plots(results, tables, c, a, a.out) + [f for r in results for f in r.get("pngs", []) if f]
    lines = ext.doc_lines(a, c, tables, results, time.perf_counter() - started)
    with open(os.path.join(a.out, "ao-results.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    print(f"wrote {a.out}/" + ", ".join(sorted(k for k, v in tables.items() if v)) + ", ao-results.md, " +
          ", ".join(os.path.basename(f) for f in files))
    if a.doc:
        write_doc(files, lines)
    bad = [f"{r['set']} Table 6" for r in results for t in r["t6"] if (t["phong_exit"], t["ao_exit"]) != (0, 0)]
    bad += [f"{r['set']} {g['directions']} directions, map {g['map_size']}: {g.get('error') or g['exit_status']}"
            for r in results for g in r["grid"] if g["exit_status"] != 0]
    bad += [f"{r['set']} reference {x['kind']} {x['directions'] or x['samples']}: {x['exit_status']}"
            for r in results for x in r["refs"] if x["exit_status"] != 0]
    if bad:
        print("\n*** failed runs (recorded in the tables):\n" + "\n".join(bad), flush=True)
    return 1 if bad and a.quick else 0


def write_doc(files, lines):
    os.makedirs(os.path.join(ROOT, "docs", "bench"), exist_ok=True)
    for f in files:
        shutil.copy(f, os.path.join(ROOT, "docs", "bench", os.path.basename(f)))
    replace_block(os.path.join(ROOT, "docs", "spheres-bench.md"), DOC_NAME, lines, DOC_HEADING,
                  "scripts/bench-spheres --ao")


def replot(a):
    """The plots again from --replot DIR's CSVs (with --doc: into docs/bench)."""
    import csv

    def num(v):
        try:
            return float(v) if v not in ("", "nan") else (float("nan") if v == "nan" else v)
        except ValueError:
            return v

    def load(f):
        p = os.path.join(a.replot, f)
        return [{k: num(v) for k, v in r.items()} for r in csv.DictReader(open(p))] if os.path.exists(p) else []
    tables = {f: load(f) for f in ("ao-table6.csv", "ao-table7.csv", "ao-error.csv", "ao-references.csv",
                                   "ao-versus.csv", "ao-ratios.csv", "ao-tachyon-check.csv")}
    results = []
    for s in dict.fromkeys(r["set"] for r in tables["ao-error.csv"]):
        res = {"set": s, "spheres": int(next(r["spheres"] for r in tables["ao-error.csv"] if r["set"] == s)),
               "grid": [r for r in tables["ao-error.csv"] if r["set"] == s],
               "versus": [r for r in tables["ao-versus.csv"] if r["set"] == s],
               "t6": [r for r in tables["ao-table6.csv"] if r["set"] == s]}
        mc = [r for r in tables["ao-references.csv"] if r["set"] == s and bs.isnum(r.get("noise_floor_mean"))]
        if mc:
            res["noise_floor"] = mc[0]["noise_floor_mean"]
        results.append(res)
    for r in results:
        for g in r["grid"]:
            g["directions"], g["map_size"] = int(g["directions"]), int(g["map_size"])
    c = {"tmap": int(tables["ao-table7.csv"][0]["map_size"]) if tables["ao-table7.csv"] else 1024}
    files = ext.plots(results, tables, c, a, a.replot)
    if a.doc:
        for f in files:
            shutil.copy(f, os.path.join(ROOT, "docs", "bench", os.path.basename(f)))
    print("wrote", ", ".join(files))
    return 0
