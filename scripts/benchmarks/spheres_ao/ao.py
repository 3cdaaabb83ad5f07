"""`scripts/bench spheres --ao` (alias `scripts/bench spheres-ao`): ambient occlusion on the sphere sets C1-C4
and the protein 1hpv, one thread (the seed's Tables 6 and 7 analogues), its
error against two references as a function of the direction count and the map
size, and, side by side in the same run, VTK's screen-space AO (vtkSSAOPass on
llvmpipe) and Tachyon's ray-traced AO (ao_others.py).

Per set, one camera: zsweep reference's automatic perspective camera
(lib/sphere_sets.auto_camera), written into every scene (and given to VTK and
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
- --vtk and --tachyon (ao_others.py), at --error-size, against the
  same references; the ratios take our fastest configuration of the grid at
  an error (vs MC) no larger than theirs, per frame and with the maps
  amortised over --amortise frames.
References run with --ref-threads threads (they are not timed against us).
"""
import concurrent.futures
import json
import os
import shutil
import sys
import time

import numpy as np

from ..lib.common import ROOT, all_cols, copy_to_docs, fmt, isnum, replace_block, write_csv
from ..lib.sphere_sets import auto_camera
from ..lib.spheres_cli import parse
from .ao_others import run_tachyon, run_vtk, tachyon_body, tachyon_check, versus_row
from .ao_plots import compare_png, plots
from .ao_report import doc_lines, ratios, table7
from .ao_runs import SQ2PI, config, error, mc_variance, prepare, read_ao, reference, render, same_scene, write_scene

DOC_NAME, DOC_HEADING = "bench-spheres-ao", "## Ambient occlusion (`--ao`)"


# ---------------------------------------------------------------- one set

def run_set(a, c, name, log):
    count = c["counts"][name]
    path, n, rmean, lo, hi = prepare(a, name, count)
    img = os.path.join(a.out, "ao-images")
    cam = auto_camera(lo, hi, c["esize"], c["esize"])
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
    if isnum(t6["phong_ms"]) and isnum(t6["ao_ms"]):
        t6["ao_over_phong"] = t6["ao_ms"] / t6["phong_ms"]
    res["t6"].append(t6)
    log(f"{name}: {sz}² Phong {fmt(ph.get('ms'))} ms, AO ({c['tdirs']} directions, map {c['tmap']}) "
        f"{fmt(ao.get('ms'))} ms + maps {fmt(ao.get('maps_ms'))} ms")

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
        if isnum(row["ms"]) and isnum(row["maps_ms"]):
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
        log(f"{name}: {d} directions, map {m}: frame {fmt(r.get('ms'))} ms, maps {fmt(r.get('maps_ms'))} ms; "
            f"mean |dAO| vs exact {fmt(row.get('vs_exact_mean'), 4)}, vs MC {fmt(row.get('vs_mc_mean'), 4)}"
            + ("" if r["exit_status"] == 0 else f" [{r['exit_status']}: {r.get('error', '')}]"))

    # VTK's SSAO and Tachyon, same spheres, camera and size, one thread.
    images = {}
    if a.vtk:
        for v in run_vtk(a, path, cam, es, R, rmean, f"{base}-vtk-{es}"):
            res["versus"].append(versus_row(common, es, v, refs.get(c["tdirs"]), mc, a.amortise, var))
            x = res["versus"][-1]
            images[id(x)] = v.get("ao")
            log(f"{name}: VTK {v['params']}: " +
                (f"{v['ms']:.1f} ms, mean |dAO| vs MC {fmt(x.get('vs_mc_mean'), 4)}, coverage differs on "
                 f"{fmt(100 * x.get('coverage_diff', float('nan')), 2)} %" if "ms" in v else v.get("error", "failed")))
    if a.tachyon:
        body = tachyon_body(path, f"{base}-tachyon-body.dat")
        best = min((g["vs_mc_mean"] for g in res["grid"] if isnum(g.get("vs_mc_mean"))), default=0.0)
        done = None  # the last count that ran
        for s in sorted(c["tach"]):
            # Ascending counts: stop once Tachyon is at or below our best error (every
            # configuration of ours then has its match); skip a count whose predicted
            # time (linear in the count) is over --tachyon-timeout.
            if done and isnum(done.get("vs_mc_mean")) and done["vs_mc_mean"] <= best:
                break
            if done and done["ms"] * s / done["samples"] > a.tachyon_timeout * 1000:
                t = {"renderer": "tachyon", "samples": s, "error": "skipped: predicted over --tachyon-timeout"}
            else:
                t = run_tachyon(a, body, cam, es, s, f"{base}-tachyon-s{s}-{es}")
            res["versus"].append(versus_row(common, es, t, refs.get(c["tdirs"]), mc, a.amortise, var))
            images[id(res["versus"][-1])] = t.get("ao")
            if "ms" in t:
                done = res["versus"][-1]
            log(f"{name}: Tachyon {s} samples: " +
                (f"trace {t['ms']:.0f} ms (parse {t['parse_ms']:.0f}, preprocessing {t['preprocess_ms']:.0f}), "
                 f"mean |dAO| vs MC {fmt(res['versus'][-1].get('vs_mc_mean'), 4)}, coverage differs on "
                 f"{fmt(100 * res['versus'][-1].get('coverage_diff', float('nan')), 2)} %"
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
                if v["renderer"] == who and isnum(v.get("vs_mc_mean"))]
        if rows:
            v = res["versus"][min(rows)[1]]
            panels.append((f"VTK SSAO, radius {v['params'].split()[2]} r̄" if who == "vtk-ssao"
                           else f"Tachyon, {int(v['samples'])} samples", images.get(id(v))))
    res["pngs"] = [compare_png(os.path.join(a.out, f"ao-compare-{name}.png"), panels, name)]
    return res


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

def main(argv):
    a, ap = parse(argv)
    if a.replot:
        return replot(a)
    c = config(a, ap)
    os.makedirs(os.path.join(a.out, "ao-images"), exist_ok=True)
    if a.tachyon and not shutil.which(a.tachyon_bin):
        ap.error(f"--tachyon needs {a.tachyon_bin} (apt-get install tachyon-bin-nox)")
    started = time.perf_counter()
    results, check = [], []
    if a.tachyon:
        check = tachyon_check(a, os.path.join(a.out, "ao-images", "tachyon-check"))
        for r in check:
            print(f"Tachyon check, {r['scene']}, {r.get('samples')} samples: mean AO {fmt(r.get('tachyon_mean_ao'), 4)} "
                  f"(MC {fmt(r.get('mc_mean_ao'), 4)}), mean |dAO| {fmt(r.get('vs_mc_mean'), 4)}, coverage "
                  f"differs on {fmt(100 * r.get('coverage_diff', float('nan')), 2)} %" +
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
    files = plots(results, tables, c, a, a.out) + [f for r in results for f in r.get("pngs", []) if f]
    lines = doc_lines(a, c, tables, results, time.perf_counter() - started)
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
    copy_to_docs(files)
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
        mc = [r for r in tables["ao-references.csv"] if r["set"] == s and isnum(r.get("noise_floor_mean"))]
        if mc:
            res["noise_floor"] = mc[0]["noise_floor_mean"]
        results.append(res)
    for r in results:
        for g in r["grid"]:
            g["directions"], g["map_size"] = int(g["directions"]), int(g["map_size"])
    c = {"tmap": int(tables["ao-table7.csv"][0]["map_size"]) if tables["ao-table7.csv"] else 1024}
    files = plots(results, tables, c, a, a.replot)
    if a.doc:
        copy_to_docs(files)
    print("wrote", ", ".join(files))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
