"""The translucency benchmark's renders and measures: the Table 5 rows and
the error sweep's variants (mode, tolerance t, layer cap, surfaces), one
`zsweep render` or `zsweep reference` (Embree) process each, the renders'
uncompressed TIFFs compared in process, the set's alphas, and the t/2-levels
bound of an error row."""
import json
import os
import struct
import subprocess
import sys

import numpy as np

from ..lib.common import ZSWEEP, run_stats
from ..lib.sphere_sets import QUICK as SETS_QUICK

EPS = 2e-6        # float rounding between two exact composites (dual_peel to completion: <= 1e-6)
FLOOR = 1e-9      # RMSE 0 is plotted here (log scale)
# --quick: C2's maximal balls are deeply nested (a 256² pixel crosses hundreds
# of surfaces even with a few hundred spheres; exhaustive peeling of 20,000 of
# them takes minutes), so its quick set is small.
QUICK = dict(SETS_QUICK, c2=100)

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
    cmd = [ZSWEEP, "render", scene_path, "-o", out, "--threads", "1", "--frames", str(repeat),
           "--stats", stats, "--memory-budget", str(budget), "--compression", "none"]
    row, j = run_stats(cmd, stats, timeout)
    if "process_s" not in row:  # timed out
        return dict(row, timeout=True)
    if j is None:
        return row
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
    cmd = ["/usr/bin/time", "-f", "MAXRSS %M", ZSWEEP, "reference", scene_path, "-o", out, "--threads", "1",
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
