"""`scripts/bench spheres --ao`'s tables: Table 7 (the maps' time per
direction count), the ratios against VTK and Tachyon at equal error, and the
Markdown of ao-results.md (with --doc the block between the bench-spheres-ao
markers of docs/spheres-bench.md)."""
import datetime
import math
import os

from ..lib.common import cpu_name, cpu_vector_isa, fmt, isnum


def table7(results, c):
    rows = []
    for r in results:
        for g in r["grid"]:
            if g["map_size"] == c["tmap"]:
                rows.append({"set": r["set"], "spheres": r["spheres"], "directions": g["directions"],
                             "map_size": g["map_size"], "maps_ms": g.get("maps_ms", ""), "map_mb": g.get("map_mb", ""),
                             "maps_ms_per_direction": g["maps_ms"] / g["directions"] if isnum(g.get("maps_ms"))
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
        ours = [g for g in r["grid"] if isnum(g.get("vs_mc_mean")) and isnum(g.get("ms"))]
        vt = sorted([v for v in r["versus"] if v["renderer"] == "vtk-ssao" and isnum(v.get("vs_mc_mean"))],
                    key=lambda v: v["vs_mc_mean"])[:1]  # its most accurate radius
        ta = sorted([v for v in r["versus"] if v["renderer"] == "tachyon" and isnum(v.get("vs_mc_mean"))],
                    key=lambda v: v["samples"])
        if not ours or (not vt and not ta):
            continue
        for key in ("ms", "amortised_ms"):
            row = {"set": r["set"], "time": "per frame" if key == "ms" else f"amortised over {a.amortise:g} frames"}
            mine = [g for g in ours if isnum(g.get(key))]
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


def doc_lines(a, c, tables, results, wall):
    f = fmt
    sets = ", ".join(f"{r['set'].upper()} ({r['spheres']:,})" for r in results)
    L = [f"Measured {datetime.date.today().isoformat()} on {cpu_name()} ({os.cpu_count()} cores, {cpu_vector_isa()}), "
         f"`{a.command}` ({wall / 60:.1f} min). Sets: {sets}. One thread for every timed renderer; each zsweep time "
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
                  f"{f(r.get('vtk_err'), 4)})" if isnum(r.get("vtk_over_ours")) else str(r.get("vtk_over_ours", "–")))
            ta = (f"{r.get('tachyon_bound', '')}{f(r['tachyon_over_ours'], 1)}× ({f(r.get('tachyon_samples'), 0)}; "
                  f"{r.get('ours_for_tachyon')}, {f(r.get('ours_for_tachyon_err'), 4)})"
                  if isnum(r.get("tachyon_over_ours")) else "–")
            one = "–"
            if r.get("one_config"):
                one = (f"{r['one_config']} ({f(r.get('one_config_err'), 4)}): " +
                       (f"{f(r['one_config_vtk_over_ours'], 1)}×" if isnum(r.get("one_config_vtk_over_ours"))
                        else "–") + ", " +
                       (f"{r.get('one_config_tachyon_bound', '')}{f(r['one_config_tachyon_over_ours'], 1)}× "
                        f"({f(r.get('one_config_tachyon_samples'), 0)} samples)"
                        if isnum(r.get("one_config_tachyon_over_ours")) else "–"))
            L.append(f"| {r['set'].upper()} | {r['time']} | {vt} | {ta} | {one} | "
                     f"{'yes' if r['goal_5x'] == 'yes' else '**' + str(r['goal_5x']) + '**'} |")
    L += ["", "Notes: VTK's SSAO is a screen-space approximation within a radius (it sees only what the depth buffer "
          "holds), so it does not converge to the references; its value is read back in 8 bits (a 1/255 floor). "
          "Tachyon's AO samples S directions uniformly on the hemisphere and weights each by N·ω with a 2/S factor: "
          "the same cosine-weighted AO as ours (occluders at any distance), unbiased before its clamp to [0, 1), "
          "which biases bright pixels low at small S (see the check above); read from a 16-bit PPM."]
    return L
