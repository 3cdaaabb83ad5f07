# zsweep.render against the CLI on the same scenes, bit for bit, from
# files, numpy arrays and VTK objects; bad arrays; the GIL released.
import json
import threading
import time

import numpy as np
import pytest

import zsweep

vtk = pytest.importorskip("vtkmodules.vtkCommonDataModel", reason="python3-vtk9 is not installed")
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkAppendFilter  # noqa: E402
from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter  # noqa: E402


def hex_grid(n=3):
    """An n^3 block of hexahedra with a point scalar 'density' (x + 2y) and a second array."""
    img = vtk.vtkImageData()
    img.SetDimensions(n + 1, n + 1, n + 1)
    img.SetSpacing(1.0 / n, 1.0 / n, 1.0 / n)
    app = vtkAppendFilter()
    app.AddInputData(img)
    app.Update()
    g = app.GetOutput()
    p = vtk_to_numpy(g.GetPoints().GetData()).astype(np.float64)
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(p, deep=True))
    g.SetPoints(pts)
    dens = numpy_to_vtk(p[:, 0] + 2 * p[:, 1], deep=True)
    dens.SetName("density")
    other = numpy_to_vtk(p[:, 2].copy(), deep=True)
    other.SetName("height")
    g.GetPointData().AddArray(other)
    g.GetPointData().SetScalars(dens)
    return g


def write_vtu(g, path):
    w = vtkXMLUnstructuredGridWriter()
    w.SetFileName(str(path))
    w.SetInputData(g)
    w.SetDataModeToAscii()  # doubles written exactly (17 digits)
    assert w.Write() == 1


VOLUME = {"image": {"width": 48, "height": 40}}


def same(a, b):
    assert a.shape == b.shape
    assert np.array_equal(a, b), "max |diff| %g" % np.max(np.abs(a - b))


def test_default_scene_matches_cli(cli):
    ref, names = cli("", "--width", 64, "--height", 48)
    img = zsweep.render(width=64, height=48)
    assert img.dtype == np.float32 and img.shape == (48, 64, 4)
    same(img, ref[:, :, :4])
    assert img[:, :, 3].max() > 0


def test_vtk_grid_and_numpy_match_the_vtu_file(cli, tmp_path):
    g = hex_grid()
    path = tmp_path / "hex.vtu"
    write_vtu(g, path)
    scene = dict(VOLUME, mesh={"path": str(path), "scalar": "density"})
    (tmp_path / "s.json").write_text(json.dumps(scene))
    ref, _ = cli(tmp_path / "s.json")
    # The grid itself (hexahedra split as the reader splits them), its active scalar.
    same(zsweep.render(dict(VOLUME, mesh=g)), ref[:, :, :4])
    # A named array instead of the active one changes the image.
    other = zsweep.render(dict(VOLUME, mesh={"data": g, "scalar": "height"}))
    assert not np.array_equal(other, ref[:, :, :4])
    # Plain numpy tets: the reader's split of the same grid.
    tf = vtkDataSetTriangleFilter()
    tf.SetInputData(g)
    tf.TetrahedraOnlyOn()
    tf.Update()
    t = tf.GetOutput()
    conn = vtk_to_numpy(t.GetCells().GetConnectivityArray()).reshape(-1, 4)
    tets_path = tmp_path / "tets.vtu"
    write_vtu(t, tets_path)
    ref2, _ = cli(tets_path, "--width", 48, "--height", 40)
    arrays = {"points": vtk_to_numpy(t.GetPoints().GetData()), "tets": conn,
              "scalar": vtk_to_numpy(t.GetPointData().GetArray("density"))}
    same(zsweep.render({"mesh": arrays}, width=48, height=40), ref2[:, :, :4])


def test_clip_planes_match_the_cli(cli, tmp_path):
    g = hex_grid()
    path = tmp_path / "hex.vtu"
    write_vtu(g, path)
    clip = {"clip": [{"plane": [1, -0.5, 0.2, -0.4]}], "crop": [0, 1, 0.1, 0.9, 0, 1]}
    scene = dict(VOLUME, mesh={"path": str(path), "scalar": "density"}, **clip)
    (tmp_path / "s.json").write_text(json.dumps(scene))
    ref, _ = cli(tmp_path / "s.json")
    img, st = zsweep.render_stats(dict(VOLUME, mesh=g, **clip))
    same(img, ref[:, :, :4])
    assert st["tets_clipped"] > 0 and st["segments_clipped"] > 0
    assert not np.array_equal(img, zsweep.render(dict(VOLUME, mesh=g)))


def test_volume_with_spheres_matches_the_cli(cli, tmp_path):
    g = hex_grid()
    path = tmp_path / "hex.vtu"
    write_vtu(g, path)
    centres, radii, scalar = np.array([[0.5, 0.5, 0.5], [0.2, 0.7, 0.3]]), np.array([0.2, 0.1]), np.array([0.3, 2.0])
    (tmp_path / "s.sph").write_text("".join("%r %r %r %r %r\n" % (*c, r, v) for c, r, v in zip(centres, radii, scalar)))
    rest = {"shading": {"model": "phong"}, "clip": [{"plane": [0, 0, 1, -0.8]}]}
    scene = dict(VOLUME, mesh={"path": str(path), "scalar": "density"},
                 spheres={"path": str(tmp_path / "s.sph"), "color": "scalar"}, **rest)
    (tmp_path / "s.json").write_text(json.dumps(scene))
    ref, _ = cli(tmp_path / "s.json")
    img, st = zsweep.render_stats(dict(VOLUME, mesh={"data": g, "scalar": "density"},
                                       spheres={"path": {"centers": centres, "radii": radii, "scalar": scalar},
                                                "color": "scalar"}, **rest))
    same(img, ref[:, :, :4])
    assert st["rays_stopped_by_geometry"] > 0 and st["geometry"]["renderer"] == "spheres"
    r, rst = zsweep.reference_stats(dict(VOLUME, mesh={"data": g, "scalar": "density"},
                                         spheres={"path": {"centers": centres, "radii": radii, "scalar": scalar},
                                                  "color": "scalar"}, **rest))
    assert np.max(np.abs(r - img)) <= 1e-5
    assert rst["rays_stopped_by_geometry"] > 0


def test_volume_with_its_isosurface_matches_the_cli(cli, tmp_path):
    g = hex_grid()
    path = tmp_path / "hex.vtu"
    write_vtu(g, path)
    rest = {"surfaces": [{"isosurface": [1.5], "color": [0.9, 0.7, 0.2]}], "shadows": {"mode": "exact"}}
    (tmp_path / "s.json").write_text(json.dumps(dict(VOLUME, mesh={"path": str(path), "scalar": "density"}, **rest)))
    ref, _ = cli(tmp_path / "s.json")
    img, st = zsweep.render_stats(dict(VOLUME, mesh={"data": g, "scalar": "density"}, **rest))
    same(img, ref[:, :, :4])
    assert st["geometry"]["triangles"]["total"] > 0


def test_stats_have_the_cli_keys(cli, tmp_path):
    img, st = zsweep.render_stats(dict(VOLUME, mesh=hex_grid()))
    for k in ("time_ms", "fragments", "rendered_pixels", "faces_projected", "mesh", "image", "tiles"):
        assert k in st
    assert st["mesh"]["tets"] >= 27 * 5  # 5 or 6 tets per hex
    assert st["image"] == {"width": 48, "height": 40}
    assert st["rendered_pixels"] == int(np.count_nonzero(img[:, :, 3] > 0))


def write_sph(path, c, r):
    with open(path, "w") as f:
        f.write("# x y z r\n")
        for p, q in zip(c, r):
            f.write("%r %r %r %r\n" % (p[0], p[1], p[2], q))


def sphere_arrays(n=60, seed=3):
    rng = np.random.default_rng(seed)
    return rng.uniform(-1, 1, (n, 3)), rng.uniform(0.1, 0.3, n)


def test_spheres_numpy_match_file_with_ao_channel(cli, tmp_path):
    c, r = sphere_arrays()
    write_sph(tmp_path / "s.sph", c, r)
    common = {"image": {"width": 40, "height": 32}, "ao": {"directions": 18, "map_size": 128}}
    (tmp_path / "s.json").write_text(json.dumps(dict(common, spheres="s.sph")))
    ref, names = cli(tmp_path / "s.json")
    out = zsweep.render(dict(common, spheres={"centers": c, "radii": r}), channels="all")
    assert names == ["R", "G", "B", "A", "Z", "AO"]
    same(out["RGBA"], ref[:, :, :4])
    same(out["Z"], ref[:, :, 4])
    same(out["AO"], ref[:, :, 5])
    hit = out["RGBA"][:, :, 3] > 0
    assert np.all(np.isinf(out["AO"][~hit])) and np.all((out["AO"][hit] >= 0) & (out["AO"][hit] <= 1))


def test_sphere_colours_from_numpy():
    c, r = sphere_arrays(5)
    red = np.tile([1.0, 0.0, 0.0, 1.0], (5, 1))
    img = zsweep.render({"image": {"width": 32, "height": 32}, "shading": {"specular": 0},
                         "spheres": {"path": {"centers": c, "radii": r, "colors": red}, "color": "rgba"}})
    hit = img[:, :, 3] > 0
    assert hit.any()
    assert np.all(img[hit][:, 1] == 0) and np.all(img[hit][:, 2] == 0) and img[hit][:, 0].max() > 0


CUBE_PTS = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
CUBE_QUADS = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5], [0, 4, 7, 3]]


def write_obj(path, faces):
    with open(path, "w") as f:
        for p in CUBE_PTS:
            f.write("v %g %g %g\n" % tuple(p))
        for q in faces:
            f.write("f " + " ".join(str(i + 1) for i in q) + "\n")


SURFACE = {"image": {"width": 48, "height": 36}, "ground": {"height": 0},
           "lights": [{"type": "directional", "direction": [1, -2, 0.5]}], "shadows": {"map_size": 256}}


def surface_cli(cli, tmp_path, faces):
    write_obj(tmp_path / "cube.obj", faces)
    (tmp_path / "s.json").write_text(json.dumps(dict(SURFACE, surfaces=[{"path": "cube.obj", "color": [0.8, 0.2, 0.2]}])))
    return cli(tmp_path / "s.json")


def test_surface_numpy_matches_obj_file(cli, tmp_path):
    tris = np.array([[q[0], q[1], q[2]] for q in CUBE_QUADS] + [[q[0], q[2], q[3]] for q in CUBE_QUADS])
    ref, names = surface_cli(cli, tmp_path, tris)
    assert names[5:] == ["lit0"]
    out = zsweep.render(dict(SURFACE, surfaces=[{"path": {"points": CUBE_PTS, "triangles": tris},
                                                  "color": [0.8, 0.2, 0.2]}]), channels=["lit0"])
    same(out["RGBA"], ref[:, :, :4])
    same(out["lit0"], ref[:, :, 5])
    assert 0 < np.count_nonzero(out["lit0"] == 0) < out["lit0"].size  # the cube's shadow on the ground


def test_surface_polydata_matches_obj_file(cli, tmp_path):
    ref, _ = surface_cli(cli, tmp_path, CUBE_QUADS)  # quads, split as the reader splits them
    poly = vtk.vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(CUBE_PTS, deep=True))
    poly.SetPoints(pts)
    cells = vtk.vtkCellArray()
    for q in CUBE_QUADS:
        cells.InsertNextCell(4, q)
    poly.SetPolys(cells)
    same(zsweep.render(dict(SURFACE, surfaces=[{"path": poly, "color": [0.8, 0.2, 0.2]}])), ref[:, :, :4])


@pytest.mark.parametrize("mesh, message", [
    ({"points": np.zeros((4, 2)), "tets": [[0, 1, 2, 3]]}, "'points' must have shape"),
    ({"points": np.zeros((4, 3)), "tets": [[0, 1, 2, 4]]}, "out of range"),
    ({"points": np.zeros((4, 3)), "tets": [[0, 1, 2, -1]]}, "out of range"),
    ({"points": np.zeros((4, 3)), "tets": [[0, 1, 2]]}, "'tets' must have shape"),
    ({"points": np.zeros((4, 3)), "tets": [[0.5, 1, 2, 3]]}, "'tets' must be an integer array"),
    ({"points": np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, np.nan]]), "tets": [[0, 1, 2, 3]]}, "non-finite"),
    ({"points": np.eye(4, 3), "tets": [[0, 1, 2, 3]], "scalar": np.zeros(3)}, "'scalar' has 3 values"),
    ({"points": np.eye(4, 3), "tets": [[0, 1, 2, 3]], "scalar": [0, 1, np.inf, 0]}, "non-finite"),
    ({"points": "abc", "tets": [[0, 1, 2, 3]]}, "'points' must be a numeric array"),
    ({"points": np.eye(4, 3), "offsets": [0, 3], "connectivity": [0, 1, 2], "types": [10]}, "has 3 points"),
    ({"points": np.eye(4, 3), "offsets": [0, 4], "connectivity": [0, 1, 2, 3], "types": [200]}, "not taken"),
    ({"points": np.eye(4, 3), "offsets": [0, 5], "connectivity": [0, 1, 2, 3], "types": [10]}, "out of range"),
])
def test_bad_mesh_arrays_raise_value_error(mesh, message):
    with pytest.raises(ValueError, match=message):
        zsweep.render({"mesh": mesh})


def test_bad_sphere_and_surface_arrays():
    with pytest.raises(ValueError, match="'radii' must be positive"):
        zsweep.render({"spheres": {"centers": np.zeros((2, 3)), "radii": [1, 0]}})
    with pytest.raises(ValueError, match="'radii' has 1 rows"):
        zsweep.render({"spheres": {"centers": np.zeros((2, 3)), "radii": [1]}})
    with pytest.raises(ValueError, match=r"values must lie in \[0, 1\]"):
        zsweep.render({"spheres": {"centers": np.zeros((1, 3)), "radii": [1], "colors": [[2, 0, 0]]}})
    with pytest.raises(ValueError, match="out of range"):
        zsweep.render({"surfaces": [{"points": CUBE_PTS, "triangles": [[0, 1, 8]]}]})


def test_errors_carry_the_cli_message(tmp_path):
    with pytest.raises(RuntimeError, match="no_such.off"):
        zsweep.render(str(tmp_path / "no_such.off"))
    bad = tmp_path / "bad.json"
    bad.write_text('{"mesh": "x.off", "image": {"width": "wide"}}')
    with pytest.raises(RuntimeError, match="bad.json"):
        zsweep.render(bad)
    with pytest.raises(TypeError, match="unexpected option 'widht'"):
        zsweep.render(widht=3)
    with pytest.raises(ValueError, match="no channel 'AO'"):
        zsweep.render(width=8, height=8, channels=["AO"])


def test_options_are_checked_as_on_the_command_line(tmp_path):
    off = tmp_path / "t.off"
    off.write_text("4 1\n0 0 0 0\n1 0 0 1\n0 1 0 2\n0 0 1 3\n0 1 2 3\n")
    # An unknown array name lists the arrays there are.
    with pytest.raises(RuntimeError, match=r"no array named 'nosuch'; available: scalar \(point\)"):
        zsweep.render(off, scalar="nosuch", width=8, height=8)
    # A scene's own mesh: the keyword would be ignored, so it is refused.
    with pytest.raises(ValueError, match="scalar applies to a mesh file"):
        zsweep.render({"mesh": {"points": np.eye(4, 3), "tets": [[0, 1, 2, 3]]}}, scalar="nosuch")
    with pytest.raises(ValueError, match="width: 64.5 is not a whole number"):
        zsweep.render(width=64.5)
    with pytest.raises(ValueError, match=r"width: 0 is out of range: must be in \[1, 1048576\]"):
        zsweep.render(width=0)
    with pytest.raises(ValueError, match=r"early_termination: -1 is out of range: must be in \[0, 255\]"):
        zsweep.render(early_termination=-1)
    with pytest.raises(ValueError, match=r"max_list_length: -5 is out of range"):
        zsweep.render(max_list_length=-5)
    with pytest.raises(TypeError, match="width must be a number"):
        zsweep.render(width="wide")
    sph = tmp_path / "s.sph"
    sph.write_text("0 0 0 1\n")
    with pytest.raises(ValueError, match="integrator applies to tet meshes only, and this is a sphere set"):
        zsweep.render(sph, integrator="exact")
    with pytest.raises(ValueError, match="variant applies to the bconvert scan"):
        zsweep.render(variant="dilate", width=8, height=8)
    with pytest.raises(ValueError, match="ao_samples applies to sphere sets only"):
        zsweep.reference(ao_samples=4, width=8, height=8)
    assert zsweep.render(off, scalar="scalar", width=8, height=8).shape == (8, 8, 4)


def test_constant_default_scalar_gives_way_as_in_the_file_reader(cli, tmp_path):
    g = hex_grid()
    flat = numpy_to_vtk(np.ones(g.GetNumberOfPoints()), deep=True)
    flat.SetName("density")
    g.GetPointData().SetScalars(flat)  # constant: 'height' is the first array that varies
    write_vtu(g, tmp_path / "flat.vtu")
    ref, _ = cli(tmp_path / "flat.vtu", "--width", 48, "--height", 40)
    img = zsweep.render(dict(VOLUME, mesh=g))
    same(img, ref[:, :, :4])
    named = zsweep.render(dict(VOLUME, mesh={"data": g, "scalar": "height"}))
    same(img, named)


def test_render_releases_the_gil():
    c, r = sphere_arrays(3000, seed=5)
    scene = {"image": {"width": 256, "height": 256}, "spheres": {"centers": c, "radii": r * 0.3},
             "ao": {"directions": 66, "map_size": 512}}
    ticks = []
    done = threading.Event()

    def work():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=work)
    t.start()
    try:
        t0 = time.perf_counter()
        zsweep.render(scene, threads=1)
        t1 = time.perf_counter()
    finally:
        done.set()
        t.join()
    during = [x for x in ticks if t0 < x < t1]
    # The other thread kept running: ticks spread over the render, not one burst.
    assert t1 - t0 > 0.05
    assert len(during) >= 10, (len(during), t1 - t0)


def test_ctrl_c_stops_a_long_render():
    import os
    import signal
    import subprocess
    import sys
    code = ("import zsweep, sys\n"
            "print('started', flush=True)\n"
            "try:\n"
            "    zsweep.render(width=3000, height=3000, threads=1, frames=40)\n"
            "    print('finished', flush=True)\n"
            "except KeyboardInterrupt:\n"
            "    print('interrupted', flush=True)\n"
            "print(zsweep.render(width=8, height=8).shape, flush=True)\n")  # the module still works
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=dict(os.environ))
    assert p.stdout.readline().strip() == "started"
    time.sleep(1.0)
    t0 = time.perf_counter()
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    stopped = time.perf_counter() - t0
    assert p.returncode == 0, err
    assert out.split() == ["interrupted", "(8,", "8,", "4)"], out
    assert stopped < 10, stopped


def test_real_quadratic_grid_with_cell_data_matches_the_file(cli, tmp_path):
    import os
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    shared = os.environ.get("ZSWEEP_SHARED", os.path.join(os.path.dirname(__file__), "../../../shared/datasets"))
    path = os.path.join(shared, "kiefer.vtu")
    if not os.path.exists(path):
        pytest.skip("%s is absent (../shared/datasets)" % path)
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    assert g.GetPointData().GetNumberOfArrays() == 0  # von Mises stress per cell only
    scene = {"image": {"width": 64, "height": 48}}
    (tmp_path / "k.json").write_text(json.dumps(dict(scene, mesh=path)))
    ref, _ = cli(tmp_path / "k.json")
    img, st = zsweep.render_stats(dict(scene, mesh=g))  # quadratic tets by their corners, cell data per tet
    assert st["mesh"]["tets"] == 56786
    assert st["mesh"]["association"] == "cell" and st["cell_data_tets"] > 50000
    same(img, ref[:, :, :4])
    # The old averaging on request, the same from the file and from the grid, and another image.
    (tmp_path / "a.json").write_text(json.dumps(dict(scene, mesh={"path": path, "association": "cell_to_point"})))
    ref_avg, _ = cli(tmp_path / "a.json")
    avg, st_avg = zsweep.render_stats(dict(scene, mesh={"data": g, "association": "cell_to_point"}))
    assert st_avg["mesh"]["association"] == "point" and st_avg["cell_data_tets"] == 0
    same(avg, ref_avg[:, :, :4])
    assert np.max(np.abs(avg - img)) > 0.01
    same(zsweep.render(path, association="cell_to_point", width=64, height=48), ref_avg[:, :, :4])


def test_numpy_scalar_per_tet_is_cell_data(cli, tmp_path):
    m = zsweep.generate.grid(4, field="gaussians")
    pts, tets = m["points"], m["tets"]
    per_tet = m["scalar"][tets].mean(axis=1)
    scene = dict(VOLUME, camera={"projection": "orthographic", "eye": [2, 1.5, 3], "target": [0, 0, 0],
                                 "up": [0, 1, 0], "height": 3})
    img, st = zsweep.render_stats(dict(scene, mesh={"points": pts, "tets": tets, "scalar": per_tet}))
    assert st["mesh"]["association"] == "cell" and st["cell_data_tets"] > 0
    assert st["cell_data_tets"] + st["tets_invisible"] + st["tets_degenerate"] == len(tets)
    avg, st_avg = zsweep.render_stats(dict(scene, mesh={"points": pts, "tets": tets, "scalar": per_tet,
                                                       "association": "cell_to_point"}))
    assert st_avg["mesh"]["association"] == "point"
    assert np.max(np.abs(avg - img)) > 0.01
    # The same tets from a .vtu with the values as cell data, through the CLI.
    g = vtk.vtkUnstructuredGrid()
    p = vtkPoints()
    p.SetData(numpy_to_vtk(np.ascontiguousarray(pts, dtype=np.float64), deep=True))
    g.SetPoints(p)
    from vtkmodules.vtkCommonCore import vtkIdTypeArray
    from vtkmodules.vtkCommonDataModel import vtkCellArray
    conn = numpy_to_vtk(np.ascontiguousarray(tets.reshape(-1), dtype=np.int64), deep=True,
                        array_type=vtkIdTypeArray().GetDataType())
    off = numpy_to_vtk(np.arange(0, 4 * len(tets) + 1, 4, dtype=np.int64), deep=True,
                       array_type=vtkIdTypeArray().GetDataType())
    cells = vtkCellArray()
    cells.SetData(off, conn)
    g.SetCells(10, cells)  # VTK_TETRA
    v = numpy_to_vtk(np.ascontiguousarray(per_tet, dtype=np.float64), deep=True)
    v.SetName("value")
    g.GetCellData().SetScalars(v)
    write_vtu(g, tmp_path / "cells.vtu")
    (tmp_path / "c.json").write_text(json.dumps(dict(scene, mesh=str(tmp_path / "cells.vtu"))))
    ref, _ = cli(tmp_path / "c.json")
    same(img, ref[:, :, :4])
    with pytest.raises(ValueError, match="one per point"):
        zsweep.render(dict(scene, mesh={"points": pts, "tets": tets, "scalar": per_tet, "association": "point"}))
    with pytest.raises(ValueError, match="one per point .* or one per tet"):
        zsweep.render(dict(scene, mesh={"points": pts, "tets": tets, "scalar": per_tet[:-1]}))
