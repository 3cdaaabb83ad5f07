"""zsweep from Python: the renderers of the `zsweep` command, without files.

    import zsweep
    rgba = zsweep.render({"mesh": {"points": P, "tets": T, "scalar": S}}, width=256, height=256)

See docs/python.md. `render` takes a scene as the JSON contract describes it
(docs/scene.md), as a dict or a path; wherever the scene names a file it may
hold the data instead: numpy arrays, a vtkUnstructuredGrid or a vtkPolyData.
"""
import json
import os

import numpy as np



def _load_extension():
    """Imports _zsweep. Inside ParaView's pvpython another VTK (ParaView's
    own, libvtk*-pv5.11) is already loaded under the same C++ symbol names as
    the Debian VTK the extension uses; without RTLD_DEEPBIND the dynamic
    linker would bind Debian VTK's calls to ParaView's and crash. Deep binding
    keeps the extension and its libraries to their own symbols."""
    import sys
    try:
        with open("/proc/self/maps") as f:
            other_vtk = "-pv5." in f.read()
    except OSError:
        other_vtk = False
    if not other_vtk:
        from . import _zsweep as ext
        return ext
    old = sys.getdlopenflags()
    sys.setdlopenflags(os.RTLD_NOW | os.RTLD_DEEPBIND)
    try:
        from . import _zsweep as ext
    finally:
        sys.setdlopenflags(old)
    return ext


_zsweep = _load_extension()
from . import generate  # noqa: F401  (zsweep.generate.shape(...) etc.)

__all__ = ["render", "render_stats", "Renderer", "reference", "reference_stats", "compare", "save", "generate"]

_DATA_ROOT = "/<zsweep-data>/"  # keys standing for data in place of a path (never a real file)


def _is_path(v):
    return isinstance(v, (str, os.PathLike))


def _is_vtk(v):
    return hasattr(v, "IsA") and hasattr(v, "GetClassName")


def _vtk_numpy(arr):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    return vtk_to_numpy(arr)


def _grid_arrays(grid, scalar=None, association="auto"):
    """A VTK dataset's cells as arrays (numpy views of VTK's own where it can)."""
    if not grid.IsA("vtkDataSet"):
        raise ValueError("mesh: a %s is not a VTK dataset" % grid.GetClassName())
    if not grid.IsA("vtkUnstructuredGrid"):
        from vtkmodules.vtkFiltersCore import vtkAppendFilter
        f = vtkAppendFilter()
        f.AddInputData(grid)
        f.Update()
        grid = f.GetOutput()
    if grid.GetNumberOfCells() == 0 or grid.GetPoints() is None:
        raise ValueError("mesh: the grid has no cells")
    cells = grid.GetCells()
    out = {
        "points": _vtk_numpy(grid.GetPoints().GetData()),
        "offsets": _vtk_numpy(cells.GetOffsetsArray()),
        "connectivity": _vtk_numpy(cells.GetConnectivityArray()),
        "types": _vtk_numpy(grid.GetCellTypesArray()),
        "association": association,
    }
    # The scalar as the .vtu reader picks it: the named array (point data
    # first, then cell data), else the active point scalar, else the first
    # one-component point array; cell data only when the grid has no usable
    # point array; and when that default is constant, the first array that
    # varies — among the arrays the association allows. Cell data stay per
    # cell unless the association is "cell_to_point".
    key, a = _pick_scalar(grid.GetPointData(), grid.GetCellData(), scalar, association)
    if a is not None:
        out[key] = _values(a)
    return out


def _pick_scalar(pd, cd, name, association="auto"):
    def names(attrs):
        return [attrs.GetArrayName(i) or "?" for i in range(attrs.GetNumberOfArrays())]

    kinds = [(k, a) for k, a in (("scalar", pd), ("cell_scalar", cd))
             if not (k == "scalar" and association == "cell") and not (k == "cell_scalar" and association == "point")]
    if name:
        for key, attrs in kinds:
            if attrs.GetArray(name) is not None:
                return key, attrs.GetArray(name)
        for key, attrs in (("point", pd), ("cell", cd)):
            if attrs.GetArray(name) is not None:
                raise ValueError("mesh: array '%s' is %s data, and association is '%s'" % (name, key, association))
        raise ValueError("mesh: no point or cell array '%s' (point arrays: %s; cell arrays: %s)"
                         % (name, ", ".join(names(pd)) or "none", ", ".join(names(cd)) or "none"))
    default = ("scalar", None)
    for key, attrs in kinds:
        if attrs.GetScalars() is not None:
            default = key, attrs.GetScalars()
            break
        ones = [attrs.GetArray(i) for i in range(attrs.GetNumberOfArrays())]
        ones = [c for c in ones if c is not None and c.GetNumberOfComponents() == 1]
        if ones:
            default = key, ones[0]
            break
    # A constant default (a uniform field) gives way to the first array that
    # varies, point data first, as the readers choose (docs/scene.md).
    if default[1] is not None and not _varies(default[1]):
        for key, attrs in kinds:
            for i in range(attrs.GetNumberOfArrays()):
                c = attrs.GetArray(i)
                if c is not None and c.GetName() and c.GetNumberOfComponents() > 0 and _varies(c):
                    return key, c
    return default


def _values(a):
    v = _vtk_numpy(a)
    if v.ndim == 2:  # several components: their magnitude, as the reader takes
        v = np.sqrt(np.square(v.astype(np.float64)).sum(axis=1))
    return v


def _varies(a):
    v = _values(a)
    v = v[np.isfinite(v)]
    return v.size > 0 and v.min() < v.max()


def _polydata_arrays(poly):
    if not poly.IsA("vtkPolyData"):
        raise ValueError("surfaces: a %s is not a vtkPolyData" % poly.GetClassName())
    from vtkmodules.vtkFiltersCore import vtkTriangleFilter
    f = vtkTriangleFilter()  # polygons and strips to triangles, as the readers split them
    f.SetInputData(poly)
    f.PassVertsOff()
    f.PassLinesOff()
    f.Update()
    tri = f.GetOutput()
    if tri.GetPoints() is None or tri.GetNumberOfPolys() == 0:
        raise ValueError("surfaces: the polydata has no polygons")
    conn = _vtk_numpy(tri.GetPolys().GetConnectivityArray())
    return {"points": _vtk_numpy(tri.GetPoints().GetData()), "triangles": conn.reshape(-1, 3)}


def _mesh_data(v):
    """mesh entry -> (arrays or None, the rest of the entry)."""
    if isinstance(v, dict) and "points" in v:
        return dict(v), None
    if _is_vtk(v):
        return _grid_arrays(v), None
    if isinstance(v, dict) and ("data" in v or ("path" in v and not _is_path(v["path"]))):
        rest = {k: x for k, x in v.items() if k not in ("data", "path")}
        d = v["data"] if "data" in v else v["path"]
        scalar = rest.pop("scalar", None)
        association = rest.pop("association", None)
        if association is not None and association not in ("auto", "point", "cell", "cell_to_point"):
            raise ValueError('mesh: association must be "auto", "point", "cell" or "cell_to_point"')
        if isinstance(d, dict):
            arrays = dict(d)
            if scalar is not None and scalar != "scalar":
                raise ValueError("mesh: 'scalar' names a VTK point array; give numpy data its 'scalar' array")
            if association is not None:
                arrays["association"] = association
        elif _is_vtk(d):
            arrays = _grid_arrays(d, scalar, association or "auto")
        else:
            raise ValueError("mesh: data must be a dict of numpy arrays or a VTK dataset")
        return arrays, rest
    return None, None


def _prepare(scene):
    """A scene dict -> (JSON text, data dict for _zsweep.render)."""
    s = dict(scene)
    data = {"mesh": {}, "spheres": {}, "surfaces": {}}
    if "mesh" in s and not _is_path(s["mesh"]):
        arrays, rest = _mesh_data(s["mesh"])
        if arrays is not None:
            key = _DATA_ROOT + "mesh"
            data["mesh"][key] = arrays
            s["mesh"] = key if not rest else dict(rest, path=key)
    if "spheres" in s and not _is_path(s["spheres"]):
        v = s["spheres"]
        if isinstance(v, dict) and ("centers" in v or "centres" in v):
            data["spheres"][_DATA_ROOT + "spheres"] = dict(v)
            s["spheres"] = _DATA_ROOT + "spheres"
        elif isinstance(v, dict) and "path" in v and not _is_path(v["path"]):
            if not isinstance(v["path"], dict):
                raise ValueError("spheres: data must be a dict of numpy arrays")
            data["spheres"][_DATA_ROOT + "spheres"] = dict(v["path"])
            s["spheres"] = dict(v, path=_DATA_ROOT + "spheres")
    if "surfaces" in s and isinstance(s["surfaces"], (list, tuple)):
        entries = []
        for i, v in enumerate(s["surfaces"]):
            key = _DATA_ROOT + "surface/%d" % i
            d = v
            if isinstance(v, dict) and "path" in v and not _is_path(v["path"]):
                d = v["path"]
            elif isinstance(v, dict) and "points" not in v:
                d = None
            elif _is_path(v):
                d = None
            if d is None:
                entries.append(os.fspath(v) if _is_path(v) else v)
                continue
            data["surfaces"][key] = _polydata_arrays(d) if _is_vtk(d) else dict(d)
            entries.append(dict(v, path=key) if d is not v else key)
        s["surfaces"] = entries

    return json.dumps(s, default=_json_default), data


def _json_default(o):  # numbers from numpy, paths
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, os.PathLike):
        return os.fspath(o)
    raise TypeError("scene: %r is not JSON data" % (o,))


def _call(fn, scene, options, *extra):
    if scene is None:  # the embedded default scene
        return fn("", "", "", {}, options, *extra)
    if _is_path(scene):
        path = os.fspath(scene)
        if not path.endswith(".json"):  # a bare mesh, sphere or surface file
            return fn("", path, "", {}, options, *extra)
        try:
            with open(path) as f:
                text = f.read()
        except OSError as e:
            raise RuntimeError("%s: %s" % (path, e.strerror)) from None
        return fn(text, path, os.path.dirname(os.path.abspath(path)), {}, options, *extra)
    if not isinstance(scene, dict):
        raise TypeError("scene must be a dict, a path or None, not %s" % type(scene).__name__)
    text, data = _prepare(scene)
    return fn(text, "scene", os.getcwd(), data, options, *extra)


def _result(img, names, channels):
    if channels is None:
        return img if img.shape[2] == 4 else np.ascontiguousarray(img[:, :, :4])
    want = list(names[4:]) if channels == "all" else [channels] if isinstance(channels, str) else list(channels)
    out = {"RGBA": np.ascontiguousarray(img[:, :, :4])}
    for c in want:
        if c not in names[4:]:
            raise ValueError("no channel '%s' in this render (it has: %s)" % (c, ", ".join(names[4:]) or "none"))
        out[c] = np.ascontiguousarray(img[:, :, names.index(c)])
    return out


def render_stats(scene=None, channels=None, **options):
    """Like render, and the render's statistics: the dict `zsweep render --stats` writes."""
    img, names, stats = _call(_zsweep.render, scene, options)
    return _result(img, names, channels), json.loads(stats)


def render(scene=None, channels=None, **options):
    """Renders `scene` (a dict of the JSON contract, a path to a .json scene,
    a mesh, sphere or surface file, or None for the embedded default scene).

    Returns a (height, width, 4) float32 array of premultiplied RGBA, row 0 at
    the top. With `channels` (a list of names such as ["Z", "AO"], or "all"):
    a dict with "RGBA" and one (height, width) float32 array per channel.
    Options are the command line's: width, height, threads, projection,
    memory_budget (MiB), scan, variant, integrator, precision,
    early_termination, max_list_length, tile_size, no_culling, frames; for
    molecule files (.pdb, .ent, .cif, .mmcif, and .gz), as the scene's
    spheres keys: model (a MODEL number), waters=False, hydrogens=False.
    Raises ValueError for bad arrays, RuntimeError with the command line's
    one-line message for bad input; Ctrl-C stops the render.
    """
    return render_stats(scene, channels, **options)[0]


class Renderer:
    """A scene loaded once and rendered many times: for an orbit, or any
    series of views of one large mesh. The mesh is read and what does not
    depend on the view (a volume's topology) is built once, here; each
    render() then pays only for its view. Takes what render() takes.

        r = zsweep.Renderer("mesh.zsm", width=512, height=512)
        for eye in eyes:
            img = r.render(camera={"eye": eye, "target": [0, 0, 0]})

    `camera` is the scene's "camera" object (projection, eye, target, up,
    height, fov_y): the keys given replace the current camera's, and the
    camera stays for the following renders.
    """

    def __init__(self, scene=None, **options):
        self._session = _call(_zsweep.Session, scene, options)

    def render_stats(self, camera=None, channels=None):
        """Like render, and the render's statistics (time_ms.load and
        time_ms.topology are this Renderer's, paid once)."""
        text = "" if camera is None else json.dumps(camera, default=_json_default)
        img, names, stats = self._session.render(text)
        return _result(img, names, channels), json.loads(stats)

    def render(self, camera=None, channels=None):
        """One image of the scene, as zsweep.render returns it."""
        return self.render_stats(camera, channels)[0]


def reference_stats(scene=None, channels=None, ao_samples=0, **options):
    """Like reference, and the ray caster's statistics (`zsweep reference --stats`)."""
    img, names, stats = _call(_zsweep.reference, scene, options, int(ao_samples))
    return _result(img, names, channels), json.loads(stats)


def reference(scene=None, channels=None, ao_samples=0, **options):
    """The ground truth `zsweep reference` computes, for the same scenes and
    options as render: the tet ray caster (volumes), Embree with exact hits
    (spheres; `ao_samples` > 0: Monte Carlo AO with that many rays per pixel)
    or exact shadow rays (surfaces). Returns what render returns."""
    return reference_stats(scene, channels, ao_samples, **options)[0]


def compare(a, b, rgb=False):
    """`zsweep compare` of two images: arrays (height, width, 4+) or dicts
    from render(channels=...). Returns max_abs, rmse, psnr (None when
    identical), pixels_over_1_255 and worst_pixel (x, y); with a Z channel in
    both, "z": coverage_mismatches and max_rel as the command prints them."""
    za = a.get("Z") if isinstance(a, dict) else None
    zb = b.get("Z") if isinstance(b, dict) else None
    out = _zsweep.compare(a["RGBA"] if isinstance(a, dict) else a, b["RGBA"] if isinstance(b, dict) else b, bool(rgb))
    if za is not None and zb is not None and za.shape == zb.shape:
        ia, ib = np.isinf(za), np.isinf(zb)
        both = ~ia & ~ib
        za64, zb64 = za[both].astype(np.float64), zb[both].astype(np.float64)
        den = np.maximum(np.abs(za64), np.abs(zb64))
        ok = den > 0
        rel = np.abs(za64 - zb64)[ok] / den[ok]
        out["z"] = {"coverage_mismatches": int(np.count_nonzero(ia != ib)),
                    "max_rel": float(rel.max()) if rel.size else 0.0}
    return out


def save(path, image):
    """Writes an image from render (an array, or the dict's "RGBA") as the
    command line writes RGBA: .png (8-bit), .exr or .tif (float). Nothing is
    left under `path` when it fails."""
    _zsweep.write_image(os.fspath(path), image["RGBA"] if isinstance(image, dict) else image)
