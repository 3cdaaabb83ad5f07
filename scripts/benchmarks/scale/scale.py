"""zsweep against mesh size on one machine, up to 100 M tets and the largest
grid that fits (issue 41).

Run through scripts/bench scale (alias scripts/bench-scale; it provides
python3-vtk9 and a virtual X display for the VTK part). Meshes are grids from
`zsweep mesh generate grid --cells N --jitter 0.15 --field gaussians` (5 tets
per cube; N is the smallest with ≥ --tets million tets), written in --format
into a scratch directory (deleted afterwards unless --keep), one at a time:
generate (timed), `mesh info --json` (its render_memory estimate), then per
thread count one `zsweep render MESH --size² --threads T --frames F --stats`
process, so peak RSS is that render's. Bytes per tet = (peak RSS − the same
command's on a 2³ grid) / tets. A size whose estimated memory (render ~110
bytes/tet; generation ~40 plus the file) exceeds 80 % of MemAvailable is
skipped and said so; a run that fails or passes --timeout is recorded with its
exit status and last stderr line. Then VTK side by side on --vtk-tets
(scale_vtk.py). Writes the CSV, two plots, and the section between the
bench-scale markers of docs/scaling.md (scale_report.py).
"""
import argparse
import datetime
import os
import shlex
import shutil
import subprocess
import sys
import tempfile

from ..lib.common import ROOT, ZSWEEP, cpu_name, cpu_vector_isa, fail
from .scale_report import report
from .scale_runs import (MEM_SHARE, budget_mib, cells_for, generate, label, largest_cells, mesh_info, meminfo,
                         render, tets_of, too_big)
from .scale_vtk import vtk_side


def parser():
    ap = argparse.ArgumentParser(
        prog="bench scale",
        description="zsweep against mesh size (issue 41): generated grids of 1 to 100 M tets (and the largest "
                    "that fits, --largest), per phase time (load, topology, per-view set-up, sweep, first and "
                    "later frame) and peak RSS per tet, and VTK's ray-cast and ZSweep mappers on the 10 M grid. "
                    "Writes docs/bench/scale.csv, docs/bench/scale-time.png, docs/bench/scale-memory.png and the "
                    "section of docs/scaling.md between the bench-scale markers.",
        epilog="Needs python3-vtk9 and xvfb for the VTK part (scripts/bench installs them if missing) and "
               "matplotlib for the plots. The full run needs most of the machine's memory and can take an hour "
               "or more.")
    ap.add_argument("--tets", default="1,4,16,41,64,100", help="mesh sizes, millions of tets (decimals work)")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--size", type=int, default=512, help="image width and height")
    ap.add_argument("--frames", type=int, default=3, help="frames per render process (first, then later ones)")
    ap.add_argument("--format", choices=("vtu", "zsm"), default="vtu", help="mesh file format")
    ap.add_argument("--work", default=tempfile.gettempdir(), help="where the scratch directory is made")
    ap.add_argument("--keep", action="store_true", help="keep the scratch directory (meshes, images, stats)")
    ap.add_argument("--timeout", type=float, default=1800, help="seconds per process (generate, info, render, VTK)")
    ap.add_argument("--largest", action="store_true",
                    help=f"add the largest grid whose render estimate fits {MEM_SHARE * 100:.0f} %% of MemAvailable "
                         "(at most 300 M tets), at the largest thread count only")
    ap.add_argument("--memory-budget", type=float, default=0,
                    help="zsweep's --memory-budget, MiB (default: the larger of its own default, half of RAM, "
                         f"and {MEM_SHARE * 100:.0f} %% of MemAvailable before each render)")
    ap.add_argument("--vtk", action=argparse.BooleanOptionalAction, default=True,
                    help="VTK side by side on --vtk-tets")
    ap.add_argument("--vtk-tets", type=float, default=10, help="millions of tets of the VTK comparison's grid")
    ap.add_argument("--vtk-threads", type=int, default=2, help="threads of zsweep and VTK's ray caster there")
    ap.add_argument("--vtk-zsweep-timeout", type=float, default=600,
                    help="seconds VTK's ZSweep mapper gets (load + one frame); 0: not run")
    ap.add_argument("--csv", default=os.path.join(ROOT, "docs", "bench", "scale.csv"))
    ap.add_argument("--plots", help="directory of the plots (default docs/bench; with --no-doc, the CSV's)")
    ap.add_argument("--no-doc", action="store_true", help="do not update docs/scaling.md")
    return ap


def baseline(a, work, threads):
    """Peak RSS of the same render on a 2³ grid, per thread count (what a
    process holds whatever the mesh); exits when the format cannot be written."""
    path = os.path.join(work, f"grid-2.{a.format}")
    g = generate(2, path, a.timeout)
    if g["gen_status"] != 0:
        fail("bench scale", f"`zsweep mesh generate grid -o x.{a.format}` failed ({g['gen_status']}): "
                            f"{g.get('gen_error', '')}")
    out = {}
    for t in threads:
        r = render(path, t, a, work, f"baseline-{t}t", budget_mib(a))
        if r["status"] != 0:
            fail("bench scale", f"render of the 2³ grid failed: {r['error']}")
        out[t] = r["peak_rss_bytes"]
        print(f"baseline (2³ grid, {t} thread(s)): peak RSS {out[t] / 1e6:.0f} MB", flush=True)
    return out


def run_size(a, work, n, threads, base_rss, largest=False):
    """One grid: generate, mesh info, a render per thread count; the rows."""
    tets = tets_of(n)
    base = {"renderer": "zsweep", "mesh": label(tets), "cells": n, "tets": tets, "largest": int(largest)}
    why = too_big(n, work)
    if why:
        print(f"{base['mesh']:>9s} ({n}³ cells): skipped, {why}", flush=True)
        return [dict(base, status=f"skipped: {why}")]
    path = os.path.join(work, f"grid-{n}.{a.format}")
    gen = generate(n, path, a.timeout)
    if gen["gen_status"] != 0:
        print(f"{base['mesh']:>9s}: generation failed ({gen['gen_status']}): {gen.get('gen_error', '')}", flush=True)
        return [dict(base, status=f"generation failed ({gen['gen_status']})", error=gen.get("gen_error", ""), **gen)]
    print(f"{base['mesh']:>9s} ({n}³ cells): generated in {gen['gen_s']:.1f} s, "
          f"{gen['file_bytes'] / 1e9:.2f} GB", flush=True)
    info = mesh_info(path, a.timeout)
    est = {}
    if info and "render_memory" in info:
        est = {"est_bytes_per_tet": info["render_memory"]["bytes_per_tet"],
               "est_peak_bytes": info["render_memory"]["peak"]}
    rows = []
    for t in threads:
        r = render(path, t, a, work, f"grid-{n}-{t}t", budget_mib(a))
        r.pop("image")
        row = {**base, **gen, **est, **r}
        if r["status"] == 0 and row.get("peak_rss_bytes") and base_rss.get(t):
            row["baseline_rss_bytes"] = base_rss[t]
            row["bytes_per_tet"] = (row["peak_rss_bytes"] - base_rss[t]) / tets
        rows.append(row)
        if r["status"] != 0:
            print(f"{base['mesh']:>9s} {t} thread(s): failed ({r['status']}): {r['error']}", flush=True)
        else:
            print(f"{base['mesh']:>9s} {t} thread(s): load {r['load_s']:.2f} s, topology {r['topology_s']:.2f} s, "
                  f"set-up {r['setup_s']:.2f} s, sweep {r['sweep_s']:.2f} s, first frame {r['first_frame_s']:.2f} s, "
                  f"later {r['later_frame_s']:.2f} s, peak RSS {r['peak_rss_bytes'] / 1e9:.2f} GB "
                  f"({row.get('bytes_per_tet', float('nan')):.0f} B/tet, estimate "
                  f"{est.get('est_bytes_per_tet', float('nan')):.0f})", flush=True)
    # The VTK comparison reuses its grid when it is one of these (as .vtu).
    if not a.keep and not (a.vtk and a.format == "vtu" and n == cells_for(a.vtk_tets)):
        os.remove(path)
    return rows


def main(argv):
    a = parser().parse_args(argv)
    a.vtk_zsweep = a.vtk_zsweep_timeout > 0
    if not os.access(ZSWEEP, os.X_OK):
        fail("bench scale", f"no zsweep at {ZSWEEP} (build it: scripts/build)")
    threads = [int(x) for x in a.threads.split(",")]
    sizes = sorted({cells_for(float(x)) for x in a.tets.split(",") if x.strip()})
    os.makedirs(a.work, exist_ok=True)
    work = tempfile.mkdtemp(prefix="zsweep-scale-", dir=a.work)
    meta = {"date": datetime.date.today().isoformat(), "cpu": cpu_name(), "cores": os.cpu_count(),
            "isa": cpu_vector_isa(), "ram": meminfo("MemTotal"), "available": meminfo("MemAvailable"),
            "command": "scripts/bench-scale" + "".join(" " + shlex.quote(x) for x in argv),
            "commit": subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                                     text=True).stdout.strip()}
    rows, vtk_rows = [], []
    try:
        base_rss = baseline(a, work, threads)
        for n in sizes:
            rows += run_size(a, work, n, threads, base_rss)
        if a.largest:
            n = largest_cells()
            done = [r["cells"] for r in rows if r.get("status") == 0]
            if done and n <= max(done):
                print(f"--largest: {label(tets_of(n))} fits, not above the sizes rendered", flush=True)
            else:
                rows += run_size(a, work, n, [max(threads)], base_rss, largest=True)
        if a.vtk:
            keep = os.path.join(work, f"grid-{cells_for(a.vtk_tets)}.vtu")
            vtk_rows = vtk_side(a, work, keep if os.path.exists(keep) else None)
    finally:
        if a.keep:
            print(f"kept {work}", flush=True)
        else:
            shutil.rmtree(work, ignore_errors=True)
    skipped = [r["mesh"] for r in rows if str(r.get("status", "")).startswith("skipped")]
    if skipped:
        print("skipped (memory or disk estimate): " + ", ".join(skipped), flush=True)
    report(a, rows, vtk_rows, meta)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
