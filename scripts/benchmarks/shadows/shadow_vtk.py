"""VTK side of the shadow-map benchmark: renders a triangle-mesh scene with
VTK 9.1's vtkShadowMapPass (+ its vtkShadowMapBakerPass) offscreen on Mesa
llvmpipe and prints the timings as one JSON line on stdout.

  LP_NUM_THREADS=1 PYTHONPATH=scripts xvfb-run -a -s "-screen 0 1280x1024x24" \
      /usr/bin/python3 -m benchmarks.shadows.shadow_vtk JOB.json

JOB.json: {"surfaces": [{"path", "color", "transform": {"translate", "rotate_deg",
"scale"}}], "ground": [4 corners, optional], "ground_color", "camera": {"eye",
"target", "up", "fov_y"}, "light": {"direction"}, "map_size", "width", "height",
"repeat", "png" (optional), "rebake" (optional, default true), "light_kind"
(optional: "directional" (default; VTK 9.1 bakes ortho maps for it) or "spot")}.

VTK only re-bakes its shadow map when a light or prop is modified, so with
"rebake" true every timed frame touches the light (light.Modified()) and thus
includes the map pass, like a renderer that builds its map per frame;
"frame_cached_ms" is the best frame that reuses the map; "frame_plain_ms" the best
frame of the same scene without the shadow passes. Transform: p' = t +
Rz*Ry*Rx*(s*p). Errors: one line on stderr, exit 1.
"""
import json
import math
import os
import sys
import time

os.environ.setdefault("LP_NUM_THREADS", "1")

import numpy as np  # noqa: E402
import vtk  # noqa: E402
from vtk.util import numpy_support  # noqa: E402

from ..lib import common  # noqa: E402

PROG = "shadow_vtk"


def set_points(pd, pts):
    vp = vtk.vtkPoints()
    vp.SetData(numpy_support.numpy_to_vtk(np.ascontiguousarray(pts), deep=True))
    pd.SetPoints(vp)
    return pd


def read_off(path):
    with open(path) as f:
        lines = [l.split("#", 1)[0].split() for l in f]
    lines = [l for l in lines if l]
    if not lines or not lines[0][0].endswith("OFF"):
        common.fail(PROG, f"{path}: not an OFF file")
    head, i = lines[0][1:], 1
    if len(head) < 2:
        head, i = lines[1], 2
    nv, nf = int(head[0]), int(head[1])
    if len(lines) < i + nv + nf:
        common.fail(PROG, f"{path}: truncated OFF file")
    pts = np.array([l[:3] for l in lines[i:i + nv]], dtype=np.float64)
    offsets, conn = [0], []
    for l in lines[i + nv:i + nv + nf]:
        k = int(l[0])
        conn.extend(int(x) for x in l[1:1 + k])
        offsets.append(len(conn))
    conn = np.array(conn, dtype=np.int64)
    if conn.size and (conn.min() < 0 or conn.max() >= nv):
        common.fail(PROG, f"{path}: face index out of range")
    pd = set_points(vtk.vtkPolyData(), pts)
    cells = vtk.vtkCellArray()
    cells.SetData(numpy_support.numpy_to_vtkIdTypeArray(np.array(offsets, dtype=np.int64), deep=True),
                  numpy_support.numpy_to_vtkIdTypeArray(conn, deep=True))
    pd.SetPolys(cells)
    return pd


def read_mesh(path):
    if not os.path.isfile(path):
        common.fail(PROG, f"{path}: no such file")
    ext = os.path.splitext(path)[1].lower()
    readers = {".obj": vtk.vtkOBJReader, ".ply": vtk.vtkPLYReader, ".stl": vtk.vtkSTLReader}
    if ext in readers:
        r = readers[ext]()
        r.SetFileName(path)
        r.Update()
        pd = r.GetOutput()
    else:
        pd = read_off(path)
    out = triangulate(pd)
    if out.GetNumberOfPolys() == 0:
        common.fail(PROG, f"{path}: no triangles")
    return out


def triangulate(pd):
    tri = vtk.vtkTriangleFilter()
    tri.SetInputData(pd)
    tri.Update()
    return tri.GetOutput()


def apply_transform(pd, t):
    ax, ay, az = (math.radians(a) for a in t.get("rotate_deg", [0, 0, 0]))
    cx, sx, cy, sy, cz, sz = math.cos(ax), math.sin(ax), math.cos(ay), math.sin(ay), math.cos(az), math.sin(az)
    rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    m = rz @ ry @ rx * float(t.get("scale", 1.0))
    pts = numpy_support.vtk_to_numpy(pd.GetPoints().GetData()).astype(np.float64)
    return set_points(pd, pts @ m.T + np.array(t.get("translate", [0, 0, 0]), dtype=np.float64))


def make_actor(pd, color):
    n = vtk.vtkPolyDataNormals()
    n.SetInputData(pd), n.SplittingOff(), n.ConsistencyOn(), n.Update()
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(n.GetOutput())
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    p = actor.GetProperty()
    p.SetColor(*color), p.SetAmbient(0.2), p.SetDiffuse(0.7), p.SetSpecular(0.3)
    p.SetSpecularPower(32), p.SetInterpolationToPhong()
    return actor


def grab(win):
    w2i = vtk.vtkWindowToImageFilter()
    w2i.SetInput(win), w2i.ReadFrontBufferOff(), w2i.ShouldRerenderOff()
    w2i.SetInputBufferTypeToRGB(), w2i.Update()
    img = vtk.vtkImageData()
    img.DeepCopy(w2i.GetOutput())
    return img


def luminance(img):
    return common.luminance(numpy_support.vtk_to_numpy(img.GetPointData().GetScalars()).astype(np.float64) / 255.0)


def main():
    if len(sys.argv) != 2:
        common.fail(PROG, "usage: python3 -m benchmarks.shadows.shadow_vtk JOB.json")
    try:
        with open(sys.argv[1]) as f:
            job = json.load(f)
        cam, direction = job["camera"], np.array(job["light"]["direction"], dtype=float)
        width, height = int(job["width"]), int(job["height"])
        map_size, repeat = int(job["map_size"]), max(1, int(job.get("repeat", 3)))
        surfaces = job["surfaces"]
    except (OSError, ValueError, KeyError, TypeError) as e:
        common.fail(PROG, f"bad job file {sys.argv[1]}: {e!r}")
    if np.linalg.norm(direction) == 0:
        common.fail(PROG, "light direction is zero")
    light_kind = job.get("light_kind", "directional")
    rebake = bool(job.get("rebake", True))

    t0 = time.perf_counter()
    ren = vtk.vtkRenderer()
    ren.AutomaticLightCreationOff()
    ren.SetBackground(0, 0, 0)
    triangles = 0
    for s in surfaces:
        pd = apply_transform(read_mesh(s["path"]), s.get("transform", {}))
        triangles += pd.GetNumberOfPolys()
        ren.AddActor(make_actor(pd, s.get("color", [0.8, 0.8, 0.8])))
    if job.get("ground"):
        g = set_points(vtk.vtkPolyData(), np.array(job["ground"], dtype=np.float64).reshape(4, 3))
        quad = vtk.vtkCellArray()
        quad.InsertNextCell(4, [0, 1, 2, 3])
        g.SetPolys(quad)
        g = triangulate(g)
        triangles += g.GetNumberOfPolys()
        ren.AddActor(make_actor(g, job.get("ground_color", [0.9, 0.9, 0.9])))

    b = ren.ComputeVisiblePropBounds()
    centre = np.array([(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2])
    radius = 0.5 * math.dist(b[0::2], b[1::2])
    d = direction / np.linalg.norm(direction)
    light = vtk.vtkLight()
    light.SetLightTypeToSceneLight(), light.SetColor(1, 1, 1), light.SetIntensity(1.0)
    if light_kind == "spot":  # far along -d, cone just covering the bounding sphere
        dist = 20.0 * radius
        light.SetPositional(True)
        light.SetPosition(*(centre - d * dist))
        light.SetFocalPoint(*centre)
        light.SetConeAngle(math.degrees(math.asin(radius / dist)) * 1.05)
        light.SetExponent(0), light.SetAttenuationValues(1, 0, 0)
    else:
        light.SetPositional(False)
        light.SetFocalPoint(0, 0, 0)
        light.SetPosition(*(-d))
    ren.AddLight(light)

    camera = ren.GetActiveCamera()
    camera.ParallelProjectionOff()
    camera.SetPosition(*cam["eye"])
    camera.SetFocalPoint(*cam["target"])
    camera.SetViewUp(*cam.get("up", [0, 1, 0]))
    camera.SetViewAngle(float(cam.get("fov_y", 30)))
    ren.ResetCameraClippingRange()

    shadows = vtk.vtkShadowMapPass()
    shadows.GetShadowMapBakerPass().SetResolution(map_size)
    passes = vtk.vtkRenderPassCollection()
    passes.AddItem(shadows.GetShadowMapBakerPass())
    passes.AddItem(shadows)
    seq = vtk.vtkSequencePass()
    seq.SetPasses(passes)
    camera_pass = vtk.vtkCameraPass()
    camera_pass.SetDelegatePass(seq)
    ren.SetPass(camera_pass)

    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1), win.SetMultiSamples(0), win.SetSize(width, height)
    win.AddRenderer(ren)
    load_s = time.perf_counter() - t0

    t0 = time.perf_counter()
    win.Render()
    win.WaitForCompletion()
    warmup_s = time.perf_counter() - t0
    if not shadows.GetShadowMapBakerPass().GetHasShadows():
        common.fail(PROG, "vtkShadowMapBakerPass made no shadow map (light kind %s)" % light_kind)

    def timed(touch):
        ms = []
        for _ in range(repeat):
            if touch:
                light.Modified()  # forces vtkShadowMapBakerPass to re-bake the map
            t = time.perf_counter()
            win.Render()
            win.WaitForCompletion()
            ms.append((time.perf_counter() - t) * 1e3)
        return ms

    cached = timed(False)
    frames = timed(True) if rebake else cached
    shadow_img = grab(win)

    ren.SetPass(None)  # default (shadowless) passes, same scene
    win.Render()
    plain_img = grab(win)
    plain = timed(False)  # the frame without the shadow-map pass
    darker = int(np.count_nonzero(luminance(plain_img) - luminance(shadow_img) > 0.1))

    if job.get("png"):
        w = vtk.vtkPNGWriter()
        w.SetFileName(job["png"]), w.SetInputData(shadow_img), w.Write()
    gl = next((l.split(":", 1)[1].strip() for l in win.ReportCapabilities().splitlines()
               if l.startswith("OpenGL renderer string")), None)
    shadows.ReleaseGraphicsResources(win)  # else the baker complains at exit
    shadows.GetShadowMapBakerPass().ReleaseGraphicsResources(win)
    print(json.dumps({
        "load_s": round(load_s, 4), "warmup_s": round(warmup_s, 4),
        "frame_ms": round(min(frames), 3), "frames_ms": [round(x, 3) for x in frames],
        "frame_cached_ms": round(min(cached), 3), "rebake": rebake,
        "frame_plain_ms": round(min(plain), 3),
        "peak_rss_mb": common.peak_rss_mb(), "triangles": triangles, "light_kind": light_kind,
        "map_size": map_size, "width": width, "height": height,
        "shadow_check": {"darker_pixels": darker, "pixels": width * height},
        "gl_renderer": gl, "vtk_version": vtk.vtkVersion.GetVTKVersion()}))


if __name__ == "__main__":
    main()
