"""What the benchmark scripts share: the machine's name, the CSV of their rows,
and their table between <!-- NAME:begin ... --> and <!-- NAME:end --> markers
of docs/benchmarks.md (appended under `heading` when the markers are missing);
the volume meshes and the scene the VTK and ParaView comparisons give both
renderers."""
import csv
import math
import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ZSWEEP = os.environ.get("ZSWEEP", os.path.join(ROOT, "build", "src", "zsweep"))
SHARED = os.environ.get("ZSWEEP_SHARED", os.path.join(ROOT, "..", "shared", "datasets"))

MESHES = {
    "spx": (["spx.off"], None),
    "blunt": (["bluntfinxyz.bin", "--q", "bluntfinq.bin", "--scalar", "density"], None),
    "post": (["postxyz.bin", "--q", "postq.bin", "--scalar", "velocity-magnitude"], None),
}


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, capture_output=True, text=True, **kw)


def mesh_args(name):
    """`zsweep mesh convert` arguments of a benchmark mesh in ../shared/datasets."""
    args = list(MESHES[name][0])
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


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def cpu_vector_isa():
    """The widest vector kernel zsweep picks on this CPU (segment_batch.cpp):
    the hosts this project runs on differ in it, and it moves the timings."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("flags"):
                    flags = set(line.split(":", 1)[1].split())
                    if "avx512f" in flags:
                        return "AVX-512"
                    if "avx2" in flags and "fma" in flags:
                        return "AVX2, no AVX-512"
                    return "no AVX2"
    except OSError:
        pass
    return "unknown vector ISA"


def write_csv(path, rows):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def replace_block(path, name, lines, heading, source=None):
    """Replaces (or appends under `heading`) the block marked `name` in the
    Markdown file `path`; `source`: the command named as its writer
    (default scripts/NAME)."""
    begin, end = f"<!-- {name}:begin", f"<!-- {name}:end -->"
    source = source or f"scripts/{name}"
    block = "\n".join([f"{begin} (written by {source}; do not edit by hand) -->"] + lines + [end])
    text = open(path).read() if os.path.exists(path) else "# Benchmarks\n\n"
    if begin in text and end in text:
        text = text[:text.index(begin)] + block + text[text.index(end) + len(end):]
    else:
        text = text.rstrip() + f"\n\n{heading}\n\n" + block + "\n"
    with open(path, "w") as f:
        f.write(text)
