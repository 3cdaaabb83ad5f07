"""Runs inside pvpython (scripts/bench vs-paraview starts it, by path): one mesh, one
scene, ParaView 5.11's unstructured volume mappers and zsweep.render called
from the same pvpython, one thread each. Prints one JSON object per line.

ParaView's frames: the first Render() of each mapper (its caches) is
discarded, then the best of `repeat` StillRender() calls. zsweep's: the best
of `repeat` frames after one discarded, by its own stats (time_ms.total), as
in scripts/bench vs-vtk; the wall time of the whole call (the fetch of the
dataset from the pipeline and its conversion included) is reported too."""
import argparse
import json
import os
import sys
import time

from paraview import servermanager
from paraview import simple

MAPPERS = ["Projected tetra", "Z sweep", "Bunyk ray cast"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", required=True)
    ap.add_argument("--out", required=True, help="image prefix")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--mappers", default=",".join(MAPPERS))
    a = ap.parse_args()
    with open(a.scene) as f:
        scene = json.load(f)
    import zsweep  # after ParaView: the module binds its own VTK (zsweep/__init__.py)

    w, h = scene["image"]["width"], scene["image"]["height"]
    simple._DisableFirstRenderCameraReset()  # the scene's camera, not ParaView's framing
    src = simple.XMLUnstructuredGridReader(FileName=[scene["mesh"]["path"]])
    src.UpdatePipeline()
    name = src.PointData.keys()[0]
    view = simple.CreateView("RenderView")
    view.ViewSize = [w, h]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0, 0, 0]
    rep = simple.Show(src, view)
    simple.ColorBy(rep, ("POINTS", name))
    tf = scene["transfer_function"]
    lut = simple.GetColorTransferFunction(name)
    lut.RGBPoints = [v for p in tf["color"] for v in p]
    lut.ColorSpace = "RGB"
    pwf = simple.GetOpacityTransferFunction(name)
    pwf.Points = [v for s, o in tf["opacity"] for v in (s, o, 0.5, 0.0)]
    rep.Representation = "Volume"
    rep.ScalarOpacityUnitDistance = tf["unit_distance"]
    c = scene["camera"]
    view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = c["eye"], c["target"], c["up"]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = c["height"] / 2
    for m in a.mappers.split(","):
        rep.SelectMapper = m
        t0 = time.perf_counter()
        simple.Render(view)  # caches
        first = time.perf_counter() - t0
        best = float("inf")
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            view.StillRender()
            best = min(best, time.perf_counter() - t0)
        png = "%s-pv-%s.png" % (a.out, m.replace(" ", "_"))
        simple.SaveScreenshot(png, view, ImageResolution=[w, h])
        print(json.dumps({"renderer": "paraview " + m, "frame_s": best, "first_s": first, "image": png}), flush=True)
    data = servermanager.Fetch(src)
    s = dict(scene, mesh={"data": data, "scalar": name})
    t0 = time.perf_counter()
    img, st = zsweep.render_stats(s, threads=1, frames=a.repeat + 1)
    wall = time.perf_counter() - t0
    exr = a.out + "-zsweep-pvpython.exr"
    zsweep.save(exr, img)
    print(json.dumps({"renderer": "zsweep (pvpython)", "frame_s": min(st["frame_ms"][1:]) / 1000.0,
                      "first_s": st["frame_ms"][0] / 1000.0, "call_s": wall, "image": exr}), flush=True)


if __name__ == "__main__":
    main()
    sys.stdout.flush()
    # pvpython's teardown of the render view under Xvfb ends in a GLX error
    # (GLXBadContext) after all is done; the results are out, skip it.
    os._exit(0)
