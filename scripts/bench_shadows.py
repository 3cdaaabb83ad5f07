"""zsweep's surface renderer: shadow maps (classic and multiple-depth n-SM,
PCF(k,n); ../shared/seeds/shadowmaps-digest.md) against exact Embree shadow
rays (`shadows.mode: exact`) and VTK 9.1's vtkShadowMapPass, one thread.

Run through scripts/bench-shadows. Everything runs in one go:
- the grid: per scene (bars, elephant, tilted) one exact render, then every
  map configuration (depths × pcf × map size), each compared with the exact
  lit0 (scripts/bench_shadows_metrics.py): levels (asserted ≤ n·k + 1), RMSE
  and max error in the band within --band texels of an exact shadow edge,
  wrongly lit / shadowed pixels outside it; on `tilted` also slope_bias 0
  (acne must show) and a bias of 5 % of the scene (peter-panning must show);
- the seed's pairings (3-SM+PCF4 vs 1-SM+PCF9, 2-SM+PCF9 and 3-SM+PCF9 vs
  1-SM+PCF16) at each map size;
- Eq. 5.6/5.7: on `bars` seen so that ground fills the image (deferred
  shading: f = shadow tests = h·w), map 512, growing images, 2-SM+PCF4 vs
  1-SM+PCF9; time of the shadow part = total − a shadows-off render of the same
  image (each the best of --cross-repeat frames in one process, best of
  --cross-rounds processes);
- side by side at map 2048, image 1024²: VTK (scripts/bench_shadows_vtk.py
  under xvfb-run, LP_NUM_THREADS=1), ours 1-SM+PCF1/4/9 and 2-SM+PCF4, and the
  Embree exact mode.
Outputs in --out: results.csv, crossover.csv, vs_vtk.csv, PNGs, summary.md.
Exit 1 (after writing them) when a check fails.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_common import write_csv  # noqa: E402
import bench_shadows_metrics as M  # noqa: E402
import bench_shadows_report as R  # noqa: E402
import bench_shadows_scenes as S  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ZSWEEP = os.environ.get("ZSWEEP", os.path.join(ROOT, "build", "src", "zsweep"))
FAILS = []


def fail(msg):
    print("bench-shadows: CHECK FAILED: " + msg, file=sys.stderr, flush=True)
    FAILS.append(msg)


def log(msg):
    print(msg, flush=True)


def parse_depths(text):
    """'1,2max,2min,3,4' -> [(1, None), (2, 'max'), (2, 'min'), (3, None), (4, None)]."""
    out = []
    for t in text.split(","):
        t = t.strip()
        sel = "max" if t.endswith("max") else "min" if t.endswith("min") else None
        n = int(t[:-3] if sel else t)
        if n == 2 and sel is None:
            sel = "max"
        out.append((n, sel))
    return out


def ints(text):
    return [int(x) for x in text.split(",") if x.strip()]


def args_parse(argv):
    p = argparse.ArgumentParser(prog="bench-shadows", description=__doc__.split("\n")[0])
    p.add_argument("--out", default="/tmp/bench-shadows")
    p.add_argument("--quick", action="store_true", help="small sweep, no VTK (< 3 min)")
    p.add_argument("--scenes", default="bars,elephant,tilted")
    p.add_argument("--size", type=int, help="grid image side (512; quick 256)")
    p.add_argument("--maps", help="map sizes (512,1024,2048,4096; quick 512,1024)")
    p.add_argument("--pcf", help="PCF kernels (1,4,9,16; quick 1,4,9)")
    p.add_argument("--depths", help="depths per cell (1,2max,2min,3,4; quick 1,2max,3)")
    p.add_argument("--frames", type=int, help="frames per grid render, best kept (3; quick 2)")
    p.add_argument("--rounds", type=int, help="processes per grid render, fastest kept (2; quick 1)")
    p.add_argument("--band", type=float, default=3.0, help="edge band half-width in map texels (3)")
    p.add_argument("--far-tolerance", type=float, default=0.01,
                   help="largest map: far errors allowed, fraction of surface pixels (0.01)")
    p.add_argument("--cross-sizes", help="crossover image sides (256,384,512,640,768,1024,1536,2048; quick 256,512,768)")
    p.add_argument("--cross-map", type=int, default=512)
    p.add_argument("--cross-repeat", type=int, help="frames per crossover render, best kept (5; quick 3)")
    p.add_argument("--cross-rounds", type=int, help="rounds of crossover processes, best kept (3; quick 2)")
    p.add_argument("--no-crossover", action="store_true")
    p.add_argument("--no-vtk", action="store_true", help="no VTK side by side (also skips ours at 1024²)")
    p.add_argument("--vtk-size", default="1024", help="image sides for the side by side, comma-separated")
    p.add_argument("--vtk-map", type=int, default=2048)
    p.add_argument("--vtk-repeat", type=int, default=5)
    p.add_argument("--ours-repeat", type=int, default=5,
                   help="frames of ours/Embree next to VTK (5: as many as VTK's Render() calls)")
    p.add_argument("--timeout", type=float, default=900, help="seconds per zsweep or VTK process (900)")
    p.add_argument("--keep-images", action="store_true", help="keep every map-mode EXR")
    a = p.parse_args(argv)
    q = a.quick
    a.size = a.size or (256 if q else 512)
    a.maps = ints(a.maps or ("512,1024" if q else "512,1024,2048,4096"))
    a.pcf = ints(a.pcf or ("1,4,9" if q else "1,4,9,16"))
    a.depths = parse_depths(a.depths or ("1,2max,3" if q else "1,2max,2min,3,4"))
    a.frames = a.frames or (2 if q else 3)
    a.rounds = a.rounds or (1 if q else 2)
    a.cross_sizes = ints(a.cross_sizes or ("256,512,768" if q else "256,384,512,640,768,1024,1536,2048"))
    a.cross_repeat = a.cross_repeat or (3 if q else 5)
    a.cross_rounds = a.cross_rounds or (2 if q else 3)
    a.scenes = [s.strip() for s in a.scenes.split(",") if s.strip()]
    if q:
        a.no_vtk = True
    for s in a.scenes:
        if s not in ("bars", "elephant", "tilted"):
            p.error(f"unknown scene {s}")
    return a


# ---------------------------------------------------------------- running zsweep

def render(a, tag, scene, frames=1, keep=True, ext="exr"):
    """Run `zsweep render` on `scene` (dict), one thread; (stats, image path).
    EXR keeps Z and lit0.. (the error measures read them); PNG is RGBA only,
    which zsweep then leaves out of its frames (as VTK's frames hold RGBA)."""
    for sub in ("scenes", "stats", "images"):
        os.makedirs(os.path.join(a.out, sub), exist_ok=True)
    sj = os.path.join(a.out, "scenes", tag + ".json")
    st = os.path.join(a.out, "stats", tag + ".json")
    exr = os.path.join(a.out, "images", tag + "." + ext)
    with open(sj, "w") as f:
        json.dump(scene, f, indent=1)
    cmd = [ZSWEEP, "render", sj, "-o", exr, "--threads", "1", "--stats", st]
    if frames > 1:
        cmd += ["--frames", str(frames)]
    try:
        # Through a forking sh: Linux keeps a process's ru_maxrss (zsweep's
        # peak_rss_bytes) across exec, so a zsweep exec'd straight from this
        # (large) python would report python's RSS as its peak.
        r = subprocess.run(["/bin/sh", "-c", '"$@"; exit $?', "sh"] + cmd, capture_output=True, text=True,
                           timeout=a.timeout)
    except subprocess.TimeoutExpired:
        raise RuntimeError(f"{tag}: zsweep took more than {a.timeout:.0f} s")
    if r.returncode != 0:
        raise RuntimeError(f"{tag}: zsweep exit {r.returncode}: {r.stderr.strip()}\n  {' '.join(cmd)}")
    with open(st) as f:
        stats = json.load(f)
    return stats, exr


def render_best(a, tag, scene, frames, rounds, ext="exr"):
    """`rounds` processes of render(); the stats of the fastest (the images
    are identical: zsweep is deterministic), the image of the last."""
    best = None
    for _ in range(max(1, rounds)):
        st, exr = render(a, tag, scene, frames, ext=ext)
        if best is None or st["time_ms"]["total"] < best["time_ms"]["total"]:
            best = st
    return best, exr


def shadows_block(mode, map_size=2048, depths=1, select=None, pcf=1, bias=0.0, slope_bias=1.5):
    if mode == "exact":
        return {"mode": "exact"}
    b = {"mode": "map", "map_size": map_size, "depths": depths, "pcf": pcf, "bias": bias, "slope_bias": slope_bias}
    if select:
        b["select"] = select
    return b


def config_name(depths, select, pcf):
    sm = f"{depths}-SM" + (f"({select})" if depths == 2 and select else "")
    return f"{sm}+PCF{pcf}"


def stats_row(stats):
    t, sh = stats["time_ms"], stats["shadows"]
    maps = sh.get("maps") or [{}]
    m = maps[0]
    return {"time_ms": round(t["total"], 3), "setup_ms": round(t["setup"], 3),
            "shadows_ms": round(t["shadows"], 3), "light_fit_ms": round(t["light_fit"], 3),
            "raster_ms": round(m.get("raster_ms", 0.0), 3), "multi_depth_ms": round(m.get("multi_depth_ms", 0.0), 3),
            "rays_build_ms": round(t["rays_build"], 3), "tiles_ms": round(t["tiles_all_threads"], 3),
            "texel": m.get("texel", ""), "map_bytes": m.get("bytes", 0),
            "peak_rss_mb": round(stats["peak_rss_bytes"] / 2**20, 1),
            "shadow_tests": sh["tests"], "depth_reads": sh["depth_reads"], "rays": sh["rays"],
            "rendered_pixels": stats["rendered_pixels"]}


# ---------------------------------------------------------------- the grid

def grid(a, scenes):
    rows = []
    for name, s in scenes.items():
        w = h = a.size
        t0 = time.time()
        st, exr = render_best(a, f"{name}-exact", S.scene_json(s, w, h, shadows_block("exact")), a.frames, a.rounds)
        ref = M.Reference(exr, s["camera"]["fov_y"])
        base = {"scene": name, "width": w, "height": h, "frames": a.frames, "rounds": a.rounds}
        ex = dict(base, kind="exact", mode="exact", config="exact", depths="", select="", pcf="", map_size="",
                  bias="", slope_bias="", **stats_row(st), **M.metrics(ref, ref.lit, 1.0, a.band, 1, 1))
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
    st, exr = render_best(a, tag, S.scene_json(s, base["width"], base["height"], sh), a.frames, a.rounds)
    sr = stats_row(st)
    m = M.compare(ref, exr, float(sr["texel"]), a.band, depths, pcf)
    if not a.keep_images:
        os.remove(exr)
    if m["levels"] > m["max_levels"]:
        fail(f"{tag}: {m['levels']} lit levels > n·k+1 = {m['max_levels']}")
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
        fail(f"tilted: slope_bias 0 shows no acne ({pick['acne_check']['far_wrong_shadowed']} wrongly shadowed "
             f"far from edges; default bias {base['far_wrong_shadowed']})")
    if pick["peter_check"]["wrong_lit_all"] <= 2 * base["wrong_lit_all"]:
        fail(f"tilted: bias {pick['peter_check']['bias']} shows no peter-panning ({pick['peter_check']['wrong_lit_all']} "
             f"wrongly lit; default bias {base['wrong_lit_all']})")


def check_accuracy(a, rows):
    """At the largest map every configuration is close to exact."""
    m = max(a.maps)
    for r in rows:
        if r["kind"] != "map" or r["map_size"] != m:
            continue
        far = r["far_wrong_lit"] + r["far_wrong_shadowed"]
        if not r["band_rmse"] < 0.5:
            fail(f"{r['scene']} {r['config']} map {m}: band RMSE {r['band_rmse']:.3f} >= 0.5")
        if far > a.far_tolerance * r["surface_pixels"]:
            fail(f"{r['scene']} {r['config']} map {m}: {far} wrong pixels far from edges "
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
    cam = S.ground_camera(s)
    best = {}
    for rnd in range(a.cross_rounds):
        for size in a.cross_sizes:
            for label, d, sel, k in [("off", 0, None, 0)] + CROSS:
                sh = False if d == 0 else shadows_block("map", a.cross_map, d, sel, k)
                tag = f"cross-{size}-" + ("off" if d == 0 else f"d{d}{sel or ''}-k{k}")
                st, exr = render(a, tag, S.scene_json(s, size, size, sh, cam), a.cross_repeat)
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


# ---------------------------------------------------------------- VTK side by side

def vtk_available():
    if not shutil.which("xvfb-run"):
        return "xvfb-run is missing (apt-get install xvfb)"
    r = subprocess.run(["/usr/bin/python3", "-c", "import vtk"], capture_output=True)
    if r.returncode != 0:
        return "/usr/bin/python3 has no vtk (python3-vtk9)"
    return ""


def vs_vtk(a, scenes):
    why = "--no-vtk" + (" (implied by --quick)" if a.quick else "") if a.no_vtk else vtk_available()
    rows = []
    if why:
        log(f"VTK side by side skipped: {why}")
        return rows, why
    for name, s, w in [(n, sc, int(z)) for z in str(a.vtk_size).split(",") for n, sc in scenes.items()]:
        h = w
        base = {"scene": name, "width": w, "height": h, "map_size": a.vtk_map}
        job = S.vtk_job(s, w, h, a.vtk_map, a.vtk_repeat, os.path.join(a.out, f"vtk-{name}-{w}.png"))
        jp = os.path.join(a.out, "scenes", f"vtk-{name}-{w}.json")
        with open(jp, "w") as f:
            json.dump(job, f, indent=1)
        env = dict(os.environ, LP_NUM_THREADS="1")
        cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "/usr/bin/python3",
               os.path.join(ROOT, "scripts", "bench_shadows_vtk.py"), jp]
        vt = None
        try:
            r = subprocess.run(cmd, capture_output=True, text=True, timeout=a.timeout, env=env)
            if r.returncode == 0:
                vt = json.loads(r.stdout.strip().splitlines()[-1])
            else:
                log(f"  VTK on {name} failed (exit {r.returncode}): {r.stderr.strip()[-300:]}")
        except subprocess.TimeoutExpired:
            log(f"  VTK on {name}: more than {a.timeout:.0f} s")
        # Timed with PNG output: RGBA frames, as VTK's; an EXR frame (Z and
        # lit channels too) gives the darkened pixels and its own time.
        plain, ppng = render_best(a, f"vtk-{name}-{w}-noshadow", S.scene_json(s, w, h, False), a.ours_repeat,
                                  a.rounds, ext="png")
        os.remove(ppng)
        plain_ms = stats_row(plain)["time_ms"]
        _, pexr = render(a, f"vtk-{name}-{w}-noshadow", S.scene_json(s, w, h, False))
        ours = []
        for label, d, sel, k in [("1-SM+PCF1", 1, None, 1), ("1-SM+PCF4", 1, None, 4), ("1-SM+PCF9", 1, None, 9),
                                 ("2-SM(max)+PCF4", 2, "max", 4), ("exact", 0, None, 0)]:
            sh = shadows_block("exact") if d == 0 else shadows_block("map", a.vtk_map, d, sel, k)
            st, png = render_best(a, f"vtk-{name}-{w}-{label}", S.scene_json(s, w, h, sh), a.ours_repeat, a.rounds,
                                  ext="png")
            os.remove(png)
            sx, exr = render(a, f"vtk-{name}-{w}-{label}", S.scene_json(s, w, h, sh), a.ours_repeat)
            sr = stats_row(st)
            ours.append(dict(base, renderer="zsweep" if d else "zsweep (Embree exact)", config=label,
                             frame_ms=sr["time_ms"], frame_cached_ms="", frame_plain_ms=plain_ms,
                             frame_exr_ms=stats_row(sx)["time_ms"],
                             shadow_part_ms=round(sr["time_ms"] - plain_ms, 3), runs=a.ours_repeat * a.rounds,
                             peak_rss_mb=sr["peak_rss_mb"], darker_pixels=M.darker_pixels(exr, pexr),
                             pixels=w * h, triangles=st["triangles"]["total"]))
            os.remove(exr)
            log(f"  {name} {label} {w}²: {sr['time_ms']:.1f} ms")
        os.remove(pexr)
        exact_dark = ours[-1]["darker_pixels"]
        if vt:
            rows.append(dict(base, renderer="VTK vtkShadowMapPass", config="1 map, VTK's PCF",
                             frame_ms=vt["frame_ms"], frame_cached_ms=vt["frame_cached_ms"], frame_exr_ms="",
                             frame_plain_ms=vt["frame_plain_ms"],
                             shadow_part_ms=round(vt["frame_ms"] - vt["frame_plain_ms"], 3), runs=len(vt["frames_ms"]),
                             peak_rss_mb=round(vt["peak_rss_mb"] or 0, 1),
                             darker_pixels=vt["shadow_check"]["darker_pixels"], pixels=w * h,
                             triangles=vt["triangles"]))
            log(f"  {name} VTK {w}²: {vt['frame_ms']:.1f} ms (cached map {vt['frame_cached_ms']:.1f} ms)")
        rows += ours
        for r in rows:
            if r["scene"] == name and r["width"] == w:
                r["darker_vs_exact"] = round(r["darker_pixels"] / exact_dark, 3) if exact_dark else ""
    return rows, ""


# ---------------------------------------------------------------- main

def main(argv):
    a = args_parse(argv)
    if not os.access(ZSWEEP, os.X_OK):
        sys.exit(f"bench-shadows: no zsweep binary at {ZSWEEP} (set ZSWEEP)")
    os.makedirs(a.out, exist_ok=True)
    t0 = time.time()
    scenes, notes = S.make_scenes(a.scenes, os.path.join(a.out, "meshes"))
    for n in notes:
        log("bench-shadows: " + n)
    if not scenes:
        sys.exit("bench-shadows: no scene to render")
    rows = grid(a, scenes)
    check_accuracy(a, rows)
    write_csv(os.path.join(a.out, "results.csv"), rows)
    cross, cross_note = ([], "--no-crossover") if a.no_crossover else crossover(a, scenes)
    if cross:
        write_csv(os.path.join(a.out, "crossover.csv"), cross)
    vtk_rows, vtk_note = vs_vtk(a, scenes)
    if vtk_rows:
        write_csv(os.path.join(a.out, "vs_vtk.csv"), vtk_rows)
    R.plots(a.out, rows, cross)
    R.summary(a, argv, scenes, rows, cross, cross_note, vtk_rows, vtk_note, notes, FAILS, time.time() - t0, ZSWEEP)
    log(f"bench-shadows: wrote {a.out}/summary.md in {time.time() - t0:.0f} s")
    if FAILS:
        print(f"bench-shadows: {len(FAILS)} check(s) failed:", file=sys.stderr)
        for f in FAILS:
            print("  " + f, file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    try:
        main(sys.argv[1:])
    except RuntimeError as e:
        sys.exit(f"bench-shadows: {e}")
