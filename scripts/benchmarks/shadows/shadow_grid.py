"""The measurements of `scripts/bench shadows` on our renderer: the grid (per
scene one exact render, then every map configuration, each compared with the
exact lit0; acne and peter-panning on `tilted`), the accuracy checks at the
largest map, and the Eq. 5.6/5.7 crossover. A failed check is recorded in
FAILS (the run goes on, and exits 1 at the end)."""
import os
import sys
import time

from .shadow_metrics import Reference, compare, metrics
from .shadow_runs import config_name, log, render, render_best, shadows_block, stats_row
from .shadow_scenes import ground_camera, scene_json

FAILS = []


def check_failed(msg):
    print("bench-shadows: CHECK FAILED: " + msg, file=sys.stderr, flush=True)
    FAILS.append(msg)


# ---------------------------------------------------------------- the grid

def grid(a, scenes):
    rows = []
    for name, s in scenes.items():
        w = h = a.size
        t0 = time.time()
        st, exr = render_best(a, f"{name}-exact", scene_json(s, w, h, shadows_block("exact")), a.frames, a.rounds)
        ref = Reference(exr, s["camera"]["fov_y"])
        base = {"scene": name, "width": w, "height": h, "frames": a.frames, "rounds": a.rounds}
        ex = dict(base, kind="exact", mode="exact", config="exact", depths="", select="", pcf="", map_size="",
                  bias="", slope_bias="", **stats_row(st), **metrics(ref, ref.lit, 1.0, a.band, 1, 1))
        rows.append(ex)
        log(f"{name}: exact {ex['time_ms']:.1f} ms, {ref.pixels} surface pixels, {ref.edges} edge pixels")
        for map_size in a.maps:
            for depths, select in a.depths:
                for pcf in a.pcf:
                    rows.append(one_map(a, s, ref, base, "map", map_size, depths, select, pcf))
        if name == "tilted":
            d, sel, k, m = 1, None, 4, max(a.maps)
            rows.append(one_map(a, s, ref, base, "acne_check", m, d, sel, k, slope_bias=0.0))
            rows.append(one_map(a, s, ref, base, "peter_check", m, d, sel, k, bias=round(0.05 * s["extent"], 6)))
            check_tilted(rows, m, d, sel, k)
        log(f"{name}: {sum(r['scene'] == name for r in rows)} renders in {time.time() - t0:.0f} s")
    return rows


def one_map(a, s, ref, base, kind, map_size, depths, select, pcf, bias=0.0, slope_bias=1.5):
    name = s["name"]
    cfg = config_name(depths, select, pcf)
    tag = f"{name}-{kind}-m{map_size}-d{depths}{select or ''}-k{pcf}"
    sh = shadows_block("map", map_size, depths, select, pcf, bias, slope_bias)
    st, exr = render_best(a, tag, scene_json(s, base["width"], base["height"], sh), a.frames, a.rounds)
    sr = stats_row(st)
    m = compare(ref, exr, float(sr["texel"]), a.band, depths, pcf)
    if not a.keep_images:
        os.remove(exr)
    if m["levels"] > m["max_levels"]:
        check_failed(f"{tag}: {m['levels']} lit levels > n·k+1 = {m['max_levels']}")
    row = dict(base, kind=kind, mode="map", config=cfg, depths=depths, select=select or "", pcf=pcf,
               map_size=map_size, bias=bias, slope_bias=slope_bias, **sr, **m)
    log(f"  {tag}: {sr['time_ms']:.1f} ms, levels {m['levels']}/{m['max_levels']}, band RMSE {m['band_rmse']:.3f} "
        f"max {m['band_max']:.2f}, far lit/shadowed {m['far_wrong_lit']}/{m['far_wrong_shadowed']}")
    return row


def check_tilted(rows, m, d, sel, k):
    pick = {r["kind"]: r for r in rows if r["scene"] == "tilted" and r["map_size"] == m and r["depths"] == d
            and r["pcf"] == k and r["select"] == (sel or "")}
    base = pick.get("map", {"far_wrong_shadowed": 0, "wrong_lit_all": 0})  # absent with a custom --pcf/--depths
    if pick["acne_check"]["far_wrong_shadowed"] <= 2 * base["far_wrong_shadowed"]:
        check_failed(f"tilted: slope_bias 0 shows no acne ({pick['acne_check']['far_wrong_shadowed']} wrongly shadowed "
             f"far from edges; default bias {base['far_wrong_shadowed']})")
    if pick["peter_check"]["wrong_lit_all"] <= 2 * base["wrong_lit_all"]:
        check_failed(f"tilted: bias {pick['peter_check']['bias']} shows no peter-panning ({pick['peter_check']['wrong_lit_all']} "
             f"wrongly lit; default bias {base['wrong_lit_all']})")


def check_accuracy(a, rows):
    """At the largest map every configuration is close to exact."""
    m = max(a.maps)
    for r in rows:
        if r["kind"] != "map" or r["map_size"] != m:
            continue
        far = r["far_wrong_lit"] + r["far_wrong_shadowed"]
        if not r["band_rmse"] < 0.5:
            check_failed(f"{r['scene']} {r['config']} map {m}: band RMSE {r['band_rmse']:.3f} >= 0.5")
        if far > a.far_tolerance * r["surface_pixels"]:
            check_failed(f"{r['scene']} {r['config']} map {m}: {far} wrong pixels far from edges "
                 f"(> {a.far_tolerance:.1%} of {r['surface_pixels']})")


# ---------------------------------------------------------------- Eq. 5.6/5.7

CROSS = [("2-SM(max)+PCF4", 2, "max", 4), ("1-SM+PCF9", 1, None, 9)]


def crossover(a, scenes):
    """--cross-rounds rounds over every image size (shadows off, then each
    config), each render the best of --cross-repeat frames; the best round
    is kept (another process on the machine spoils whole runs, not frames)."""
    if "bars" not in scenes:
        return [], "no bars scene"
    s = scenes["bars"]
    cam = ground_camera(s)
    best = {}
    for rnd in range(a.cross_rounds):
        for size in a.cross_sizes:
            for label, d, sel, k in [("off", 0, None, 0)] + CROSS:
                sh = False if d == 0 else shadows_block("map", a.cross_map, d, sel, k)
                tag = f"cross-{size}-" + ("off" if d == 0 else f"d{d}{sel or ''}-k{k}")
                st, exr = render(a, tag, scene_json(s, size, size, sh, cam), a.cross_repeat)
                os.remove(exr)
                sr = stats_row(st)
                if (size, label) not in best or sr["time_ms"] < best[(size, label)]["time_ms"]:
                    best[(size, label)] = sr
        log(f"  crossover round {rnd + 1}/{a.cross_rounds} done")
    rows = []
    for size in a.cross_sizes:
        off = best[(size, "off")]["time_ms"]
        for label, d, sel, k in CROSS:
            sr = best[(size, label)]
            rows.append({"width": size, "height": size, "config": label, "depths": d, "pcf": k, "map_size": a.cross_map,
                         "frames": a.cross_repeat, "rounds": a.cross_rounds, "f": sr["shadow_tests"],
                         "rendered_pixels": sr["rendered_pixels"], "depth_reads": sr["depth_reads"],
                         "total_ms": sr["time_ms"], "off_ms": round(off, 3),
                         "shadow_part_ms": round(sr["time_ms"] - off, 3), "shadows_ms": sr["shadows_ms"],
                         "raster_ms": sr["raster_ms"], "multi_depth_ms": sr["multi_depth_ms"],
                         "tiles_ms": sr["tiles_ms"]})
            log(f"  crossover {size}² {label}: f {sr['shadow_tests']}, total {sr['time_ms']:.1f} ms, "
                f"off {off:.1f} ms, shadow part {sr['time_ms'] - off:.1f} ms")
    cov = [r for r in rows if r["rendered_pixels"] != r["width"] * r["height"]]
    note = "" if not cov else f"{len(cov)} crossover renders do not cover every pixel"
    return rows, note
