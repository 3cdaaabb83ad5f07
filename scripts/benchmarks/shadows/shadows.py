"""zsweep's surface renderer: shadow maps (classic and multiple-depth n-SM,
PCF(k,n); ../shared/seeds/shadowmaps-digest.md) against exact Embree shadow
rays (`shadows.mode: exact`) and VTK 9.1's vtkShadowMapPass, one thread.

Run through scripts/bench shadows (alias scripts/bench-shadows). Everything
runs in one go:
- the grid: per scene (bars, elephant, tilted) one exact render, then every
  map configuration (depths × pcf × map size), each compared with the exact
  lit0 (shadow_metrics.py): levels (asserted ≤ n·k + 1), RMSE
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
- side by side at map 2048, image 1024²: VTK (shadow_vtk.py
  under xvfb-run, LP_NUM_THREADS=1), ours 1-SM+PCF1/4/9 and 2-SM+PCF4, and the
  Embree exact mode.
Outputs in --out: results.csv, crossover.csv, vs_vtk.csv, PNGs, summary.md.
Exit 1 (after writing them) when a check fails.
"""
import argparse
import os
import sys
import time

from ..lib.common import ZSWEEP, write_csv
from .shadow_grid import FAILS, check_accuracy, crossover, grid
from .shadow_report import plots, summary
from .shadow_runs import log
from .shadow_scenes import make_scenes
from .shadow_vs_vtk import vs_vtk


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
    p = argparse.ArgumentParser(
        prog="bench shadows",
        description="zsweep's surface renderer: shadow maps (1-SM and multiple-depth n-SM, PCF(k,n)) against "
                    "exact Embree shadow rays and VTK 9.1's vtkShadowMapPass, one thread: per scene error in the "
                    "shadow-edge band, wrong pixels away from it, lit levels (<= n*k+1 asserted), acne and "
                    "peter-panning; the seed's pairings; the Eq. 5.6/5.7 crossover; VTK and Embree side by side. "
                    "results.csv, crossover.csv, vs_vtk.csv, PNGs and summary.md in --out; exit 1 when a check "
                    "fails.",
        epilog="--quick: 256² images, maps 512,1024, PCF 1,4,9, depths 1,2max,3, three crossover sizes, fewer "
               "repeats, no VTK (about 35 s; under 3 minutes on two cores); the full run takes 5-8 minutes on two "
               "cores. Needs numpy, scipy, matplotlib and OpenImageIO (python3-numpy python3-scipy "
               "python3-matplotlib python3-openimageio); the VTK part also python3-vtk9 and xvfb (skipped with a "
               "message without them). ZSWEEP=path/to/zsweep skips the build. Docs: docs/shadows.md.")
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


def run(argv):
    a = args_parse(argv)
    if not os.access(ZSWEEP, os.X_OK):
        sys.exit(f"bench-shadows: no zsweep binary at {ZSWEEP} (set ZSWEEP)")
    os.makedirs(a.out, exist_ok=True)
    t0 = time.time()
    scenes, notes = make_scenes(a.scenes, os.path.join(a.out, "meshes"))
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
    plots(a.out, rows, cross)
    summary(a, argv, scenes, rows, cross, cross_note, vtk_rows, vtk_note, notes, FAILS, time.time() - t0, ZSWEEP)
    log(f"bench-shadows: wrote {a.out}/summary.md in {time.time() - t0:.0f} s")
    if FAILS:
        print(f"bench-shadows: {len(FAILS)} check(s) failed:", file=sys.stderr)
        for f in FAILS:
            print("  " + f, file=sys.stderr)
        sys.exit(1)


def main(argv):
    try:
        run(argv)
    except RuntimeError as e:
        sys.exit(f"bench-shadows: {e}")


if __name__ == "__main__":
    main(sys.argv[1:])
