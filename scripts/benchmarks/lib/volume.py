"""The volume benchmarks' meshes (../shared/datasets, as `zsweep mesh convert`
and `zsweep render` take them) and the scene the VTK and ParaView comparisons
give both renderers."""
import math
import os

from .common import SHARED

MESHES = {
    "spx": ["spx.off"],
    "blunt": ["bluntfinxyz.bin", "--q", "bluntfinq.bin", "--scalar", "density"],
    "post": ["postxyz.bin", "--q", "postq.bin", "--scalar", "velocity-magnitude"],
}


def mesh_args(name):
    """`zsweep mesh convert` (and `zsweep render`) arguments of a benchmark mesh in ../shared/datasets."""
    args = list(MESHES[name])
    args[0] = os.path.join(SHARED, args[0])
    if "--q" in args:
        i = args.index("--q") + 1
        args[i] = os.path.join(SHARED, args[i])
    return args


def scene_for(info, vtu, size, scan, precision="double"):
    """The scene both renderers get: orthographic down -z onto the mesh, a
    blue-white-red ramp with opacity 0 -> 0.6, unit distance diagonal / 50."""
    lo, hi = info["bounds"]
    c = [(a + b) / 2 for a, b in zip(lo, hi)]
    r = 0.5 * math.dist(lo, hi)
    smin, smax = info["scalar"]["min"], info["scalar"]["max"]
    mid = 0.5 * (smin + smax)
    return {
        "mesh": {"path": vtu},
        "image": {"width": size, "height": size, "background": [0, 0, 0, 0]},
        "camera": {"projection": "orthographic", "eye": [c[0], c[1], c[2] + 4 * r], "target": c,
                   "up": [0, 1, 0], "height": 2.2 * r},
        "transfer_function": {
            "color": [[smin, 0.23, 0.30, 0.75], [mid, 0.87, 0.87, 0.87], [smax, 0.71, 0.02, 0.15]],
            "opacity": [[smin, 0.0], [smax, 0.6]],
            "unit_distance": 2 * r / 50,
        },
        "render": {"scan": scan, "integrator": "exact", "precision": precision},
    }
