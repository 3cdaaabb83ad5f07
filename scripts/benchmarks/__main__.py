"""scripts/bench NAME [options]: runs one benchmark (scripts/bench NAME --help:
its options)."""
import importlib
import sys

from .lib.spheres_cli import parser as spheres_parser

# NAME: (module, what it measures)
BENCHMARKS = {
    "spheres": ("spheres.orbit", "sphere renderer on C1-C4: orbit, culling on/off, VTK, Embree "
                "(--translucent, --ao: the two below)"),
    "spheres-translucent": ("spheres_translucent.translucent", "translucent sphere modes: time, layers, error "
                            "(= spheres --translucent)"),
    "spheres-ao": ("spheres_ao.ao", "ambient occlusion on spheres: Phong vs AO, maps, error, VTK SSAO, Tachyon "
                   "(= spheres --ao)"),
    "shadows": ("shadows.shadows", "shadow maps against exact shadow rays and VTK's vtkShadowMapPass"),
    "vs-vtk": ("vs_vtk", "volume rendering against VTK's unstructured-grid mappers"),
    "vs-paraview": ("vs_paraview", "zsweep in pvpython against ParaView's volume mappers"),
    "scaling": ("scaling", "thread scaling and peak memory at large sizes"),
    "scale": ("scale.scale", "mesh size up to 100 M tets: time per phase, bytes per tet, VTK on 10 M (issue 41)"),
}
MODE_FLAG = {"spheres-translucent": "--translucent", "spheres-ao": "--ao"}


def usage():
    return "usage: scripts/bench NAME [options]   (scripts/bench NAME --help)\n\nNAME:\n" + "\n".join(
        f"  {n:20s}{what}" for n, (_, what) in BENCHMARKS.items())


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(usage(), file=sys.stdout if argv else sys.stderr)
        return 0 if argv else 2
    name, rest = argv[0], argv[1:]
    if name not in BENCHMARKS:
        print(f"bench: unknown benchmark '{name}'\n\n{usage()}", file=sys.stderr)
        return 2
    if name in MODE_FLAG and MODE_FLAG[name] not in rest:
        rest = [MODE_FLAG[name]] + rest
    if name.startswith("spheres"):
        # One set of options for the three; --ao wins over --translucent.
        a = spheres_parser().parse_args(rest)
        name = "spheres-ao" if a.ao else "spheres-translucent" if a.translucent else "spheres"
    module = importlib.import_module("." + BENCHMARKS[name][0], __package__)
    return module.main(rest)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
