"""`scripts/bench spheres --translucent` (alias `scripts/bench spheres-translucent`): zsweep's translucent sphere modes on
the test sets C1-C4, one thread each (the seed's Table 5 analogue), their
error against `sorted` exact as a function of the tolerance t and the layer
cap, VTK's depth peeling and the Embree reference.

Per set, on zsweep reference's automatic perspective camera (and, with
--frames N > 1, N - 1 more frames of the orbit benchmark's orbit; the Table 5
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
  per set (lib/sphere_vtk.py), a warm-up frame first;
- Embree (--embree): `zsweep reference` on the sorted-exact scene (it
  composites every crossing; it takes the scene's camera), one thread.
Renders are bounded by --render-timeout (the exact ones, which every error
row needs, by --exact-timeout); a peel (dual_peel) row whose
smaller-or-equal cap and larger-or-equal t timed out is skipped, not run.
"""
import concurrent.futures
import json
import os
import sys
import time

from ..lib.common import all_cols, copy_to_docs, read_csv, write_csv
from ..lib.sphere_sets import auto_camera, bounds, compare, ensure_set, orbit, scene
from ..lib.sphere_vtk import VtkProcess
from ..lib.spheres_cli import parse, sets_and_counts
from .translucent_runs import (QUICK, TABLE5, alpha_stats, bound_row, compare_images, exact_timeout, key, render,
                               run_reference, skipped_by, sweep_variants, tag, variant)
from .translucent_tables import doc_lines, plots, summarize, write_doc_block


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
        sc = scene(self.path, cam, self.size, self.a.memory_budget)
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
    vtkp = VtkProcess(path, size, S.repeat, a.vtk_timeout, a.vtk_frame_timeout, a.vtk_budget,
                      translucent=True) if a.vtk else None
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
            emb["vs_exact_max_abs"], emb["vs_exact_rmse"] = compare(out, ref["image"])
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
                compare(row["png"], fe["image"], "--rgb")
    # The in-process compare against zsweep compare, once per set.
    r, ref = S.done[("auto", key(variant("sorted", 8, 32)))], S.done[("auto", key(variant("sorted", 0, 0)))]
    check = ""
    if r.get("exit_status") == 0 and ref.get("exit_status") == 0:
        m, e = compare(r["image"], ref["image"])
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
    summary, errors = read_csv(d, "translucent-summary.csv"), read_csv(d, "translucent-errors.csv")
    for r in errors:
        if isinstance(r.get("ms"), int):
            r["ms"] = float(r["ms"])
    files = plots(summary, [], errors, [], [], d)
    if doc:
        copy_to_docs(files)
    print("wrote", ", ".join(files))
    return 0


def main(argv):
    a, ap = parse(argv)
    if a.replot:
        return replot(a.replot, a.doc)
    size = a.size or (256 if a.quick else 1024)
    nframes = a.frames or 1
    sets, counts = sets_and_counts(a, ap, QUICK)
    if a.threads and a.threads != "1":
        print("bench-spheres --translucent: one thread only (--threads ignored)", file=sys.stderr)
    os.makedirs(a.out, exist_ok=True)
    img, scenes = os.path.join(a.out, "images"), os.path.join(a.out, "translucent-scenes")
    os.makedirs(img, exist_ok=True)
    os.makedirs(scenes, exist_ok=True)
    started = time.perf_counter()
    mode_rows, err_rows, vtk_rows, emb_rows, summary, all_cams = [], [], [], [], [], []

    def one_set(name, count):
        path = ensure_set(a.out, name, count)
        lo, hi = bounds(path)
        cams = [("auto", auto_camera(lo, hi, size, size))]
        if nframes > 1:
            cams += [(f"f{k:03d}", c) for k, c in enumerate(orbit(lo, hi, nframes)) if k > 0]
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
        copy_to_docs(files)
        write_doc_block(lines)
    bad = sum(s["bound_violations"] for s in summary)
    if bad:
        print(f"\n*** {bad} row(s) break a GUARANTEED t/2-levels bound (see 'BOUND VIOLATED') ***", flush=True)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
