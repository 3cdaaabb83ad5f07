"""The options of `scripts/bench spheres` (aliases: scripts/bench-spheres,
`scripts/bench spheres-translucent` = `spheres --translucent`, `scripts/bench
spheres-ao` = `spheres --ao`): one parser, one usage text, for the orbit, the
translucency and the ambient occlusion benchmarks."""
import argparse
import os

from .common import ROOT
from .sphere_sets import FULL


def parser():
    ap = argparse.ArgumentParser(
        prog="bench spheres",
        description="zsweep's sphere renderer on C1-C4: an orbit of frames, culling on (optimized) and off "
                    "(basic), with --vtk VTK's vtkOpenGLSphereMapper and with --embree the Embree reference side "
                    "by side. --translucent: the translucent modes instead (time, layers, error against sorted "
                    "exact, VTK's depth peeling, Embree). --ao: ambient occlusion instead (Phong vs AO, map "
                    "times, error against exact directions and Monte Carlo, VTK's SSAO, Tachyon).",
        epilog="Needs numpy and matplotlib; --ao also OpenImageIO, --vtk python3-vtk9 and xvfb, --tachyon "
               "tachyon-bin-nox. ZSWEEP=path/to/zsweep skips the build. Docs: docs/spheres-bench.md.")
    ap.add_argument("--sets", default=None, help="default c1,c2,c3,c4 (--ao: and 1hpv, the protein of --pdb)")
    ap.add_argument("--size", type=int, default=None, help="image width and height (default 1024; --quick 256)")
    ap.add_argument("--frames", type=int, default=None,
                    help="orbit frames (default 4; --quick 3; --translucent 1, the automatic camera)")
    ap.add_argument("--counts", default=None,
                    help="spheres per set, comma-separated in --sets order (default: full sizes; --quick: ~20 K)")
    ap.add_argument("--repeat", type=int, default=None,
                    help="whole frames per measurement, best counts (default 1; --ao 3, --quick 1)")
    ap.add_argument("--threads", default=None,
                    help="thread counts for ours (default 1,2; --quick 1); 1 is always run (basic and optimized), "
                         "the others optimized only")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench-out", "spheres"))
    ap.add_argument("--vtk", action="store_true", help="time VTK's vtkOpenGLSphereMapper (needs an X display)")
    ap.add_argument("--vtk-timeout", type=float, default=600, help="s for VTK's load + first frame per set")
    ap.add_argument("--vtk-frame-timeout", type=float, default=300, help="s per later VTK frame")
    ap.add_argument("--vtk-budget", type=float, default=420,
                    help="s of VTK frames per set (load and warm-up included); later frames are skipped")
    ap.add_argument("--embree", action="store_true", help="time the Embree reference (one view per set)")
    ap.add_argument("--memory-budget", type=float, default=None,
                    help="MiB, given to every zsweep render (default 4096; --ao 12288: 258 maps of 2048² take 4 GiB)")
    ap.add_argument("--quick", action="store_true", help="small counts, 256², 3 frames, 1 repeat")
    ap.add_argument("--doc", action="store_true",
                    help="write the tables into docs/spheres-bench.md and the plots to docs/bench/spheres-*.png")
    ap.add_argument("--replot", metavar="DIR", help="redraw the plots from DIR's CSVs (with --doc: into docs/bench)")
    ap.add_argument("--translucent", action="store_true",
                    help="the translucency benchmark instead (module spheres_translucent): modes, layers, "
                         "errors against sorted exact, VTK's depth peeling, the Embree reference")
    ap.add_argument("--translucent-sweep", choices=("small", "full"), default=None,
                    help="--translucent's error sweep over tolerance and layer cap (default full; --quick small)")
    ap.add_argument("--render-timeout", type=float, default=None,
                    help="--translucent: s per zsweep render or reference (default 900); --ao: s per zsweep render "
                         "(default 7200) (recorded as a timeout)")
    ap.add_argument("--exact-timeout", type=float, default=None,
                    help="--translucent: s for the exact renders (sorted t 0, the Embree reference), which "
                         "every error row needs (default --render-timeout)")
    ap.add_argument("--ao", action="store_true",
                    help="the ambient occlusion benchmark instead (module spheres_ao): Phong vs AO frames, map "
                         "times, AO error vs exact directions and Monte Carlo over directions x map size, VTK's "
                         "vtkSSAOPass (--vtk) and Tachyon (--tachyon) side by side")
    ap.add_argument("--error-size", type=int, default=None,
                    help="--ao: image size of the error grid and the side-by-side runs (default 512; --quick 128)")
    ap.add_argument("--directions", default=None, help="--ao: direction counts (default 6,18,66,258; --quick 6,18)")
    ap.add_argument("--map-sizes", default=None,
                    help="--ao: map sizes (default 256,512,1024,2048; --quick 64,128)")
    ap.add_argument("--table-directions", type=int, default=None,
                    help="--ao: directions of the Table 6 AO frame and the side-by-side run (default 66)")
    ap.add_argument("--table-map-size", type=int, default=None,
                    help="--ao: map size of Tables 6 and 7 (default 1024; --quick 128)")
    ap.add_argument("--grid", choices=("full", "cross"), default="full",
                    help="--ao: every directions x map size (full), or every count at --table-map-size and every "
                         "size at --table-directions (cross)")
    ap.add_argument("--ao-samples", type=int, default=None,
                    help="--ao: N; the Monte Carlo reference traces 4N rays per pixel, and a second one N rays for "
                         "its noise (default 256; --quick 64)")
    ap.add_argument("--ref-threads", type=int, default=2, help="--ao: threads of the references (not timed against us)")
    ap.add_argument("--ref-timeout", type=float, default=14400, help="--ao: s per reference")
    ap.add_argument("--reuse-references", action="store_true",
                    help="--ao: reuse the references already in --out traced from identical scenes (e.g. after a "
                         "change to the renderer only)")
    ap.add_argument("--amortise", type=float, default=100,
                    help="--ao: frames over which the maps (VTK's warm-up, Tachyon's grid) are amortised")
    ap.add_argument("--pdb", default="/usr/share/pymol/data/tut/1hpv.pdb", help="--ao: the protein set 1hpv")
    ap.add_argument("--tachyon", action="store_true", help="--ao: Tachyon's AO side by side (tachyon-bin-nox)")
    ap.add_argument("--tachyon-bin", default="tachyon", help=argparse.SUPPRESS)
    ap.add_argument("--tachyon-samples", default=None, help="--ao: Tachyon's AO sample counts (default 4,16,64,256)")
    ap.add_argument("--tachyon-timeout", type=float, default=7200, help="--ao: s per Tachyon run")
    ap.add_argument("--keep-tachyon-scene", action="store_true", help="--ao: keep the sets' Tachyon scene files")
    ap.add_argument("--ssao-radius", default="4,16,64",
                    help="--ao --vtk: vtkSSAOPass radii, in mean sphere radii (one row each; the ratios take the "
                         "most accurate)")
    ap.add_argument("--ssao-bias", type=float, default=0.05, help="--ao --vtk: vtkSSAOPass bias, in mean radii")
    ap.add_argument("--ssao-kernel", type=int, default=128, help="--ao --vtk: vtkSSAOPass kernel size")
    ap.add_argument("--vtk-worker", help=argparse.SUPPRESS)
    ap.add_argument("--vtk-translucent", action="store_true", help=argparse.SUPPRESS)
    return ap


def parse(argv):
    """(options, parser) of `scripts/bench spheres ARGV`, with the defaults
    that depend on the mode filled in; options.command: the command line, as
    the tables' captions name it."""
    ap = parser()
    a = ap.parse_args(argv)
    if a.render_timeout is None:  # AO maps of C4 take long
        a.render_timeout = 7200 if a.ao else 900
    if a.memory_budget is None:
        a.memory_budget = 12288 if a.ao else 4096
    if not a.ao:
        a.sets = a.sets or "c1,c2,c3,c4"
    a.command = ("scripts/bench-spheres " + " ".join(argv)).strip()
    return a, ap


def sets_and_counts(a, ap, quick):
    """--sets, checked, and their sphere counts: --counts, else `quick`'s
    with --quick, else the full sets'."""
    sets = a.sets.split(",")
    for s in sets:
        if s not in FULL:
            ap.error(f"unknown set {s} (c1, c2, c3, c4)")
    if a.counts:
        counts = [int(float(c)) for c in a.counts.split(",")]
        if len(counts) != len(sets):
            ap.error("--counts needs one count per set")
    else:
        counts = [(quick if a.quick else FULL)[s] for s in sets]
    return sets, counts
