"""The VTK worker of `scripts/bench scale` (scale_vtk.py starts one per
mapper, so each one's peak RSS is its own): reads the .vtu, sets up one of
VTK's unstructured-grid mappers with the scene's camera and transfer function
(lib/volume_vtk.VtkRenderer), times its first frame (which builds its caches)
and frames 2..F (redraws of the same view), saves the image and prints one
JSON line: load_s, first_s, later_s (list), peak_rss_mb.

  python3 -m benchmarks.scale.scale_vtk_worker JOB_JSON   (scripts/ on PYTHONPATH, an X display)
"""
import json
import sys

from ..lib.common import peak_rss_mb
from ..lib.volume_vtk import VtkRenderer


def main(arg):
    import vtk
    p = json.loads(arg)
    vtk.vtkObject.GlobalWarningDisplayOff()  # VTK's ZSweep mapper warns "Undefined edge case" per face
    with open(p["scene"]) as f:
        scene = json.load(f)
    r = VtkRenderer(p["vtu"], scene, p["mapper"], vtk_threads=p["threads"])
    out = {"load_s": r.load_s, "first_s": r.first_s}
    out["later_s"] = [r.frame() for _ in range(p["frames"] - 1)]
    r.save(p["out"])
    out["peak_rss_mb"] = peak_rss_mb()
    print(json.dumps(out), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
