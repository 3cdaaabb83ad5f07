"""zsweep vs VTK's unstructured-grid volume mappers, same mesh/camera/TF/size.

Run through scripts/bench vs-vtk (alias scripts/bench-vs-vtk; it provides
python3-vtk9 and a virtual X display). Every mesh goes through `zsweep mesh convert` to .vtu first, so both
renderers see the same tets; the camera and transfer function are computed
here and given to both. Times are steady-state frames: VTK's first Render()
(which builds its caches) is discarded; zsweep's time is its render time
(time_ms.total: view transform, classification, sweep, compositing), without
mesh loading and topology, which VTK also keeps between frames.
"""
import argparse
import datetime
import json
import os
import sys
import tempfile

from .lib.common import ROOT, ZSWEEP, cpu_name, cpu_vector_isa, replace_block, run, write_csv
from .lib.volume import mesh_args, scene_for
from .lib.volume_vtk import VTK_INTEGRATORS, VtkRenderer


def time_zsweep(scene_path, out_exr, repeat):
    """Best steady-state frame, all in one process (`render --frames`): like
    VTK's, the first frame (cold caches, page faults) is discarded, and so is
    the last, which also writes the image file (VTK's frames write nothing)."""
    stats = out_exr + ".stats.json"
    run([ZSWEEP, "render", scene_path, "-o", out_exr, "--threads", "1", "--frames", str(repeat + 2),
         "--stats", stats])
    with open(stats) as f:
        frames = json.load(f)["frame_ms"]
    return min(frames[1:-1]) / 1000.0


def check_against_reference(scene_path, out_exr, ref):
    """Max abs difference of our image from our reference ray caster (ref:
    its image, rendered here the first time)."""
    if not os.path.exists(ref):
        run([ZSWEEP, "reference", scene_path, "-o", ref])
    c = json.loads(run([ZSWEEP, "compare", out_exr, ref, "--json"]).stdout)
    return c["max_abs"]


def parser():
    ap = argparse.ArgumentParser(
        prog="bench vs-vtk",
        description="Times zsweep against VTK's vtkUnstructuredGridVolumeZSweepMapper and "
                    "vtkUnstructuredGridVolumeRayCastMapper on the same meshes, resolutions, camera and transfer "
                    "function, in one run. Writes docs/benchmarks.csv and the table in docs/benchmarks.md between "
                    "the bench-vs-vtk markers.",
        epilog="Needs python3-vtk9 and xvfb (scripts/bench installs them if missing).")
    ap.add_argument("--sizes", default="512,1024")
    ap.add_argument("--meshes", default="spx,blunt,post")
    ap.add_argument("--repeat", type=int, default=3,
                    help="interleaved rounds; each times one steady-state frame of every renderer")
    ap.add_argument("--scan", default="span", help="zsweep's scan strategy (bbox, span, bconvert)")
    ap.add_argument("--mappers", default="zsweep,raycast",
                    help="VTK mappers to time: zsweep (vtkUnstructuredGridVolumeZSweepMapper), "
                         "raycast (vtkUnstructuredGridVolumeRayCastMapper)")
    ap.add_argument("--vtk-zsweep-max-work", type=float, default=1.5e11,
                    help="skip VTK's ZSweep mapper when tets x pixels exceeds this (default: spx both sizes, "
                         "blunt and post 512²)")
    ap.add_argument("--vtk-zsweep-rounds", type=int, default=1,
                    help="rounds that time VTK's ZSweep mapper (it is the slow one) unless its frames are "
                         "cheap (--vtk-zsweep-all-rounds-below)")
    ap.add_argument("--vtk-zsweep-all-rounds-below", type=float, default=10.0,
                    help="seconds: where VTK's ZSweep frame takes less, it is timed in every round and its "
                         "best counts, as ours and the ray caster's do (spx)")
    ap.add_argument("--vtk-integrators", default="default",
                    help="integrators to time VTK's ray caster with: default (its own pick, which is "
                         "preintegration here), and any of " + ", ".join(VTK_INTEGRATORS) +
                         " (each gets its own columns)")
    ap.add_argument("--precisions", default="double,single",
                    help="the exact integrator's kernel: double (bit-identical on every CPU), single, or both")
    ap.add_argument("--csv", default=os.path.join(ROOT, "docs", "benchmarks.csv"))
    ap.add_argument("--images", default=os.path.join(ROOT, "build", "bench-vs-vtk"))
    ap.add_argument("--no-doc", action="store_true", help="do not update docs/benchmarks.md")
    return ap


def main(argv):
    ap = parser()
    a = ap.parse_args(argv)
    import vtk
    vtk.vtkObject.GlobalWarningDisplayOff()  # VTK ZSweep warns "Undefined edge case" per face
    integrators = a.vtk_integrators.split(",")
    for i in integrators:
        if i != "default" and i not in VTK_INTEGRATORS:
            ap.error(f"--vtk-integrators: unknown integrator '{i}' (default, {', '.join(VTK_INTEGRATORS)})")
    extra = [i for i in integrators if i != "default"]
    os.makedirs(a.images, exist_ok=True)
    rows = []
    work = tempfile.mkdtemp(prefix="zsweep-bench-")
    for name in a.meshes.split(","):
        vtu = os.path.join(work, name + ".vtu")
        run([ZSWEEP, "mesh", "convert"] + mesh_args(name) + [vtu])
        info = json.loads(run([ZSWEEP, "mesh", "info", vtu, "--json"]).stdout)
        for size in [int(s) for s in a.sizes.split(",")]:
            precs = a.precisions.split(",")
            scene = scene_for(info, vtu, size, a.scan)
            scenes = {}
            for p in precs:
                scenes[p] = os.path.join(work, f"{name}-{size}-{p}.json")
                with open(scenes[p], "w") as f:
                    json.dump(scene_for(info, vtu, size, a.scan, p), f)
            base = os.path.join(a.images, f"{name}-{size}")
            if os.path.exists(base + "-reference.exr"):
                os.remove(base + "-reference.exr")  # a previous run's, perhaps of another scene
            mappers = [m for m in ("zsweep", "raycast") if m in a.mappers.split(",")]
            # VTK's ZSweep mapper takes minutes per frame on large meshes
            # (hours at 1024² of post): left out above a work limit.
            if "zsweep" in mappers and info["tets"] * size * size > a.vtk_zsweep_max_work:
                mappers.remove("zsweep")
                print(f"{name} {size}²: VTK ZSweep not run (tets x pixels above --vtk-zsweep-max-work)", flush=True)
            # One renderer per VTK mapper, and per integrator for the ray caster
            # ("raycast" is its default pick, "raycast-NAME" another).
            vtks = {}
            for m in mappers:
                for i in (integrators if m == "raycast" else ["default"]):
                    key = m if i == "default" else f"{m}-{i}"
                    vtks[key] = VtkRenderer(vtu, scene, m, integrator=None if i == "default" else i)
            timed = list(vtks)
            # Interleaved rounds (this machine's speed drifts by tens of per
            # cent within minutes): best of each, so every ratio is measured
            # in one stretch of time.
            nan = float("nan")
            best = {**{p: nan for p in precs}, **{m: nan for m in timed}}
            for rnd in range(a.repeat):
                for p in precs:
                    t = time_zsweep(scenes[p], base + f"-zsweep-{p}.exr", 1)
                    best[p] = t if best[p] != best[p] else min(best[p], t)
                for m in timed:
                    # Every renderer gets the same best-of-rounds where
                    # that is affordable: a single VTK frame against our
                    # best of several would favour us.
                    if m == "zsweep" and rnd >= a.vtk_zsweep_rounds and not best[m] < a.vtk_zsweep_all_rounds_below:
                        continue
                    t = vtks[m].frame()
                    best[m] = t if best[m] != best[m] else min(best[m], t)
            for m in timed:
                vtks[m].save(base + f"-vtk-{m}.png")
            vtks.clear()
            vz = best.get("zsweep", nan)
            vr = best.get("raycast", nan)
            for p in precs:
                ours = best[p]
                err = check_against_reference(scenes[p], base + f"-zsweep-{p}.exr", base + "-reference.exr")
                row = {"mesh": name, "tets": info["tets"], "size": size, "precision": p, "zsweep_s": ours,
                       "vtk_zsweep_s": vz, "vtk_raycast_s": vr,
                       "speedup_vs_vtk_zsweep": vz / ours, "speedup_vs_vtk_raycast": vr / ours,
                       "max_abs_vs_reference": err}
                for i in extra:
                    t = best.get("raycast-" + i, nan)
                    row[f"vtk_raycast_{i}_s"] = t
                    row[f"speedup_vs_vtk_raycast_{i}"] = t / ours
                rows.append(row)
                print(f"{name:6s} {size:5d}² {p:6s}  zsweep {ours:7.3f} s (max abs vs reference {err:.2g})   "
                      f"VTK ZSweep {vz:7.3f} s ({vz / ours:5.1f}x)   "
                      f"VTK ray cast {vr:7.3f} s ({vr / ours:5.2f}x)" +
                      "".join(f"   VTK ray cast, {i} {row[f'vtk_raycast_{i}_s']:7.3f} s "
                              f"({row[f'speedup_vs_vtk_raycast_{i}']:5.2f}x)" for i in extra), flush=True)
    write_csv(a.csv, rows)
    if not a.no_doc:
        update_doc(rows, a)


def update_doc(rows, a):
    path = os.path.join(ROOT, "docs", "benchmarks.md")
    extra = [i for i in a.vtk_integrators.split(",") if i != "default"]
    # The options that change what is timed, where they are not the defaults.
    defaults = parser()
    opts = "".join(f" --{k.replace('_', '-')} {getattr(a, k):g}" if isinstance(getattr(a, k), float)
                   else f" --{k.replace('_', '-')} {getattr(a, k)}"
                   for k in ("mappers", "vtk_zsweep_max_work", "vtk_integrators", "precisions")
                   if getattr(a, k) != defaults.get_default(k))
    lines = [
        f"Measured {datetime.date.today().isoformat()} on {cpu_name()} ({os.cpu_count()} cores, {cpu_vector_isa()}), one thread each "
        f"(VTK's ray caster set to one thread), `exact` integrator ({a.precisions.replace(',', ' and ')} kernel), `{a.scan}` scan, "
        f"`scripts/bench-vs-vtk --sizes {a.sizes} --meshes {a.meshes} --repeat {a.repeat}{opts}`: best of {a.repeat} "
        f"interleaved rounds of one steady-state frame each (VTK's ZSweep mapper: every round where its frame "
        f"takes under {a.vtk_zsweep_all_rounds_below:g} s, else {a.vtk_zsweep_rounds}, "
        f"and only where tets × pixels ≤ {a.vtk_zsweep_max_work:.1e}; \"–\" where not run). Targets: ≥ 25× VTK's "
        f"ZSweep mapper, ≥ 3× VTK's ray caster, image within 1/255 of our reference.",
        "",
        "| mesh | tets | size | kernel | zsweep (s) | vs reference | VTK ZSweep (s) | ratio | ≥ 25× | VTK ray cast (s) | ratio | ≥ 3× |"
        + "".join(f" VTK ray cast, {i} (s) | ratio |" for i in extra),
        "| --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | :---: | ---: | ---: | :---: |" + " ---: | ---: |" * len(extra),
    ]
    def mark(ratio, target):
        return "–" if ratio != ratio else ("yes" if ratio >= target else "**no**")
    def sec(t):
        return "–" if t != t else f"{t:.3f}"
    def ratio(x, digits):
        return "–" if x != x else f"{x:.{digits}f}×"
    for r in rows:
        lines.append(f"| {r['mesh']} | {r['tets']:,} | {r['size']}² | {r['precision']} | {r['zsweep_s']:.3f} | "
                     f"{r['max_abs_vs_reference']:.1e} | {sec(r['vtk_zsweep_s'])} | "
                     f"{ratio(r['speedup_vs_vtk_zsweep'], 1)} | {mark(r['speedup_vs_vtk_zsweep'], 25)} | "
                     f"{sec(r['vtk_raycast_s'])} | {ratio(r['speedup_vs_vtk_raycast'], 2)} | "
                     f"{mark(r['speedup_vs_vtk_raycast'], 3)} |" +
                     "".join(f" {sec(r[f'vtk_raycast_{i}_s'])} | {ratio(r[f'speedup_vs_vtk_raycast_{i}'], 2)} |"
                             for i in extra))
    replace_block(path, "bench-vs-vtk", lines, "## zsweep vs VTK's unstructured-grid mappers")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
