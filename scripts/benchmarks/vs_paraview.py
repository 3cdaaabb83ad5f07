"""zsweep against ParaView 5.11's own unstructured volume mappers (Projected
Tetrahedra, Z sweep, Bunyk ray cast), all called from pvpython on the same
.vtu, camera and transfer function, one thread each (llvmpipe with
LP_NUM_THREADS=1), with every image's error against `zsweep reference`.

Run through scripts/bench vs-paraview (alias scripts/bench-vs-paraview; it
checks pvpython and xvfb, and puts build/python on PYTHONPATH). Each
mesh goes through `zsweep mesh convert` to .vtu first, so every renderer sees
the same tets. ParaView's images are screen grabs over black (8-bit RGB), so
errors compare RGB only, against the reference composited over black.
"""
import argparse
import datetime
import json
import os
import subprocess
import sys
import tempfile

from .lib.common import ROOT, ZSWEEP, cpu_name, replace_block, run, write_csv
from .lib.volume import mesh_args, scene_for

# Run by path in pvpython (it imports nothing of this package).
WORKER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "paraview_worker.py")


def read(path):
    import OpenImageIO as oiio
    import numpy as np
    f = oiio.ImageInput.open(path)
    img = np.asarray(f.read_image(format="float"), dtype=np.float32)
    f.close()
    if img.shape[2] == 3:
        img = np.concatenate([img, np.ones(img.shape[:2] + (1,), np.float32)], axis=2)
    return img


def main(argv):
    ap = argparse.ArgumentParser(
        prog="bench vs-paraview",
        description="zsweep.render from pvpython against ParaView 5.11's unstructured volume mappers (Projected "
                    "Tetrahedra, Z sweep, Bunyk ray cast), one thread each, with errors against `zsweep "
                    "reference` (docs/python.md).",
        epilog="Needs pvpython (python3-paraview) and xvfb. On Debian 12, python3-paraview conflicts with "
               "python3-vtk9, which libvtk9-dev (the build) needs: build zsweep first, then `apt-get install "
               "python3-paraview` (it removes the two; the VTK runtime zsweep uses stays), run this, and "
               "reinstall libvtk9-dev to build again.")
    ap.add_argument("--meshes", default="spx,blunt")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--mappers", default="Projected tetra,Z sweep,Bunyk ray cast")
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "bench-vs-paraview"))
    ap.add_argument("--doc", action="store_true", help="write the table into docs/python.md")
    a = ap.parse_args(argv)
    import zsweep  # build/python, on PYTHONPATH (scripts/bench)
    os.makedirs(a.out, exist_ok=True)
    work = tempfile.mkdtemp(prefix="zsweep-pv-")
    rows = []
    for name in a.meshes.split(","):
        vtu = os.path.join(work, name + ".vtu")
        run([ZSWEEP, "mesh", "convert"] + mesh_args(name) + [vtu])
        info = json.loads(run([ZSWEEP, "mesh", "info", vtu, "--json"]).stdout)
        scene = scene_for(info, vtu, a.size, "span")
        scene_path = os.path.join(work, name + ".json")
        with open(scene_path, "w") as f:
            json.dump(scene, f)
        ref = os.path.join(a.out, "%s-%d-reference.exr" % (name, a.size))
        run([ZSWEEP, "reference", scene_path, "-o", ref])
        reference = read(ref)
        env = dict(os.environ, LP_NUM_THREADS="1", PYTHONPATH=os.path.join(ROOT, "build", "python"))
        p = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "pvpython", WORKER, "--scene", scene_path,
                            "--out", os.path.join(a.out, "%s-%d" % (name, a.size)), "--repeat", str(a.repeat),
                            "--mappers", a.mappers], capture_output=True, text=True, env=env)
        if p.returncode != 0:
            sys.exit("pvpython failed on %s:\n%s" % (name, p.stderr[-3000:]))
        results = [json.loads(line) for line in p.stdout.splitlines() if line.startswith("{")]
        ours = next(r for r in results if r["renderer"].startswith("zsweep"))
        for r in results:
            d = zsweep.compare(read(r["image"]), reference, rgb=True)
            row = {"mesh": name, "tets": info["tets"], "size": a.size, "renderer": r["renderer"],
                   "frame_s": round(r["frame_s"], 4), "first_s": round(r["first_s"], 4),
                   "zsweep_speedup": round(r["frame_s"] / ours["frame_s"], 2),
                   "max_abs": round(d["max_abs"], 5), "rmse": round(d["rmse"], 6),
                   "pixels_over_1_255": d["pixels_over_1_255"]}
            rows.append(row)
            print(json.dumps(row), flush=True)
    write_csv(os.path.join(a.out, "bench-vs-paraview.csv"), rows)
    lines = ["| mesh | tets | size | renderer (one thread) | frame (s) | first frame (s) | ParaView ÷ zsweep "
             "| max abs vs reference | RMSE | pixels > 1/255 |",
             "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append("| %s | %d | %d² | %s | %.3f | %.3f | %s | %.4f | %.5f | %d |" % (
            r["mesh"], r["tets"], r["size"], r["renderer"], r["frame_s"], r["first_s"],
            "—" if r["renderer"].startswith("zsweep") else "%.1f×" % r["zsweep_speedup"], r["max_abs"], r["rmse"],
            r["pixels_over_1_255"]))
    lines.append("")
    lines.append("Machine: %s; %s; `scripts/bench-vs-paraview --meshes %s --size %d --repeat %d`." % (
        cpu_name(), datetime.date.today().isoformat(), a.meshes, a.size, a.repeat))
    with open(os.path.join(a.out, "bench-vs-paraview.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    if a.doc:
        replace_block(os.path.join(ROOT, "docs", "python.md"), "bench-vs-paraview", lines,
                      "## Against ParaView's own volume mappers", source="scripts/bench-vs-paraview")
    print("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
