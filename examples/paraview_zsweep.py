"""Render a ParaView pipeline's dataset with zsweep, from ParaView's own Python.

In pvpython (or ParaView's Python shell), with the zsweep module importable
(PYTHONPATH=build/python, or installed):

    from paraview_zsweep import zsweep_render
    rgba = zsweep_render()                 # the active source, the active render view's camera
    zsweep.save("out.png", rgba)

or headless from a shell (docs/python.md):

    xvfb-run -a pvpython examples/paraview_zsweep.py MESH.vtu --clip --output out.png

The dataset is fetched from the pipeline (servermanager.Fetch), the camera is
the render view's (position, focal point, view up, view angle or parallel
scale, size), and the transfer function is ParaView's colour map and opacity
function of the array (RGBPoints and the opacity points; midpoint and
sharpness are not modelled: they are ParaView's defaults 0.5 and 0, linear)
with the representation's ScalarOpacityUnitDistance, when the view shows the
source; otherwise zsweep's automatic transfer function.
"""
import argparse
import os
import sys

from paraview import servermanager
from paraview import simple

import zsweep


def camera_of(view):
    """zsweep's camera block for a ParaView render view: its live vtkCamera
    (the proxy's Camera* properties lag until the view has rendered)."""
    c = view.GetActiveCamera()
    cam = {"eye": list(c.GetPosition()), "target": list(c.GetFocalPoint()), "up": list(c.GetViewUp())}
    if c.GetParallelProjection():
        cam.update(projection="orthographic", height=2.0 * c.GetParallelScale())
    else:
        cam.update(projection="perspective", fov_y=c.GetViewAngle())
    return cam


def transfer_function_of(array, representation):
    """zsweep's transfer function from ParaView's colour map and opacity of `array`."""
    lut = simple.GetColorTransferFunction(array)
    pwf = simple.GetOpacityTransferFunction(array)
    rgb = list(lut.RGBPoints)
    opa = list(pwf.Points)
    color = [rgb[i:i + 4] for i in range(0, len(rgb), 4)]
    opacity = [opa[i:i + 2] for i in range(0, len(opa), 4)]
    tf = {"color": color, "opacity": opacity}
    unit = getattr(representation, "ScalarOpacityUnitDistance", None) if representation is not None else None
    if unit:
        tf["unit_distance"] = float(unit)
    return tf


def zsweep_scene(source=None, view=None, array=None):
    """The zsweep scene (a dict) of `source` as `view` shows it."""
    source = source or simple.GetActiveSource()
    if source is None:
        raise RuntimeError("no active source in the pipeline")
    view = view or simple.GetActiveViewOrCreate("RenderView")
    data = servermanager.Fetch(source)
    if data.IsA("vtkMultiBlockDataSet") or data.IsA("vtkPartitionedDataSetCollection"):
        merge = simple.MergeBlocks(Input=source)
        data = servermanager.Fetch(merge)
        simple.Delete(merge)
    rep = simple.GetDisplayProperties(source, view)
    if array is None and rep is not None and rep.ColorArrayName and rep.ColorArrayName[1]:
        array = rep.ColorArrayName[1]
    w, h = view.ViewSize
    scene = {"mesh": {"data": data, "scalar": array} if array else data,
             "camera": camera_of(view), "image": {"width": int(w), "height": int(h)}}
    if array:
        scene["transfer_function"] = transfer_function_of(array, rep)
    return scene


def zsweep_render(source=None, view=None, array=None, **options):
    """zsweep.render of `source` (default: the active one) with the camera of
    `view` (default: the active render view). Returns (height, width, 4) RGBA."""
    return zsweep.render(zsweep_scene(source, view, array), **options)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mesh", help="an unstructured grid ParaView can open (.vtu, .vtk, ...)")
    ap.add_argument("--array", help="point or cell array (default: the reader's first)")
    ap.add_argument("--clip", action="store_true", help="render the output of ParaView's Clip filter instead")
    ap.add_argument("--size", default="640x480", help="view size WxH")
    ap.add_argument("--output", "-o", default="zsweep.png", help="image to write (.png, .exr, .tif)")
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--paraview-screenshot", help="also save ParaView's own rendering of the view (transparent "
                    "background), to compare")
    a = ap.parse_args(argv)
    src = simple.OpenDataFile(a.mesh)
    if src is None:
        sys.exit("%s: ParaView cannot open it" % a.mesh)
    if a.clip:
        src = simple.Clip(Input=src)
    view = simple.GetActiveViewOrCreate("RenderView")
    view.ViewSize = [int(v) for v in a.size.lower().split("x")]
    rep = simple.Show(src, view)
    if a.array:
        simple.ColorBy(rep, ("POINTS" if src.PointData.GetArray(a.array) else "CELLS", a.array))
    simple.SetActiveSource(src)
    view.ResetCamera()
    simple.Render(view)
    img, stats = zsweep.render_stats(zsweep_scene(src, view, a.array), threads=a.threads)
    zsweep.save(a.output, img)
    if a.paraview_screenshot:
        simple.SaveScreenshot(a.paraview_screenshot, view, ImageResolution=view.ViewSize, TransparentBackground=1)
    print("wrote %s: %dx%d, %d tets, %d rendered pixels, %.1f ms" % (
        a.output, img.shape[1], img.shape[0], stats["mesh"]["tets"], stats["rendered_pixels"],
        stats["time_ms"]["total"]))


if __name__ == "__main__":
    main()
