"""The volume benchmarks' VTK side: one of VTK's unstructured-grid volume
mappers on a .vtu with a benchmark scene's camera and transfer function
(lib/volume.scene_for). Used by vs-vtk and scale, so it lives here."""
import time

# VTK's ray caster's integrators. With one scalar and independent components
# (our scenes) it picks `preintegration` itself: a table of (front scalar,
# back scalar, length) built once per transfer function, looked up per
# segment. `linear` is VTK's own integrator that is "correct" for piecewise
# linear transfer functions, `partial` Moreland and Angel's partial
# pre-integration (a table of its psi function; VTK 9.1's crashes on post).
VTK_INTEGRATORS = {
    "preintegration": "vtkUnstructuredGridPreIntegration",
    "partial": "vtkUnstructuredGridPartialPreIntegration",
    "linear": "vtkUnstructuredGridLinearRayIntegrator",
}


class VtkRenderer:
    """One VTK mapper set up on the mesh, camera and transfer function; its
    first frame (which builds VTK's caches) is rendered and not counted as a
    frame (load_s: reading the .vtu; first_s: that first frame)."""

    def __init__(self, vtu, scene, mapper_kind, vtk_threads=1, integrator=None):
        import vtk
        t0 = time.perf_counter()
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(vtu)
        reader.Update()
        self.load_s = time.perf_counter() - t0
        grid = reader.GetOutput()
        tf = scene["transfer_function"]
        color = vtk.vtkColorTransferFunction()
        for s, r, g, b in tf["color"]:
            color.AddRGBPoint(s, r, g, b)
        opacity = vtk.vtkPiecewiseFunction()
        for s, a in tf["opacity"]:
            opacity.AddPoint(s, a)
        prop = vtk.vtkVolumeProperty()
        prop.SetColor(color)
        prop.SetScalarOpacity(opacity)
        prop.SetScalarOpacityUnitDistance(tf["unit_distance"])
        prop.ShadeOff()
        prop.SetInterpolationTypeToLinear()
        if mapper_kind == "zsweep":
            mapper = vtk.vtkUnstructuredGridVolumeZSweepMapper()
        else:
            mapper = vtk.vtkUnstructuredGridVolumeRayCastMapper()
            # VTK's ray caster runs one thread per core by default; the targets
            # compare one thread with one thread.
            mapper.SetNumberOfThreads(vtk_threads)
            if integrator:
                mapper.SetRayIntegrator(getattr(vtk, VTK_INTEGRATORS[integrator])())
        # Full resolution every frame: no sample-distance adjustment from the
        # previous frame's time.
        mapper.SetAutoAdjustSampleDistances(0)
        mapper.SetImageSampleDistance(1.0)
        mapper.SetInputData(grid)
        self.volume = vtk.vtkVolume()
        self.volume.SetMapper(mapper)
        self.volume.SetProperty(prop)
        ren = vtk.vtkRenderer()
        ren.AddVolume(self.volume)
        ren.SetBackground(0, 0, 0)
        self.win = vtk.vtkRenderWindow()
        self.win.SetOffScreenRendering(1)
        self.win.AddRenderer(ren)
        w, h = scene["image"]["width"], scene["image"]["height"]
        self.win.SetSize(w, h)
        cam = ren.GetActiveCamera()
        c = scene["camera"]
        cam.SetPosition(*c["eye"])
        cam.SetFocalPoint(*c["target"])
        cam.SetViewUp(*c["up"])
        cam.ParallelProjectionOn()
        cam.SetParallelScale(c["height"] / 2)
        ren.ResetCameraClippingRange()
        t0 = time.perf_counter()
        self.win.Render()
        self.first_s = time.perf_counter() - t0

    def frame(self):
        """Seconds for one steady-state frame."""
        self.volume.Modified()  # force the mapper to redraw, as a new view would
        t0 = time.perf_counter()
        self.win.Render()
        return time.perf_counter() - t0

    def save(self, out_png):
        import vtk
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(self.win)
        grab.Update()
        writer = vtk.vtkPNGWriter()
        writer.SetFileName(out_png)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()
