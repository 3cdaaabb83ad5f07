"""Running zsweep for `scripts/bench shadows`: one `zsweep render` process on
a scene, one thread (and the fastest of a few), the scene's `shadows` block,
a configuration's name, and the --stats fields the tables take."""
import json
import os
import subprocess

from ..lib.common import ZSWEEP


def log(msg):
    print(msg, flush=True)


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
