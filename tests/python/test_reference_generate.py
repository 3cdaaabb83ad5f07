# zsweep.reference, zsweep.compare and zsweep.generate against the CLI.
import json
import subprocess

import numpy as np
import pytest

import zsweep
from conftest import ZSWEEP


def cli_json(*args):
    return json.loads(subprocess.run([ZSWEEP, *map(str, args)], check=True, capture_output=True, text=True).stdout)


def read_off(path):
    """(points with the scalar as column 4, tets) of an OFF tet mesh the CLI wrote."""
    lines = [l for l in path.read_text().split("\n") if l.strip() and not l.startswith("#")]
    n, m = int(lines[0]), int(lines[1])
    pts = np.array([[float(x) for x in l.split()] for l in lines[2:2 + n]])
    tets = np.array([[int(x) for x in l.split()] for l in lines[2 + n:2 + n + m]])
    return pts, tets


def test_generated_mesh_renders_and_matches_its_reference():
    m = zsweep.generate.shape("sphere", tets=1500, field="radial")
    assert m["points"].shape[1] == 3 and m["tets"].shape[1] == 4 and m["scalar"].shape == (len(m["points"]),)
    assert 1500 * 0.8 < len(m["tets"]) < 1500 * 1.25  # the generator's target, within its tolerance
    img, st = zsweep.render_stats({"mesh": m}, width=48, height=48)
    assert st["mesh"]["tets"] == len(m["tets"])
    ref, rst = zsweep.reference_stats({"mesh": m}, width=48, height=48)
    assert rst["rays_hit"] > 0
    d = zsweep.compare(img, ref)
    assert d["max_abs"] < 1e-4 and d["pixels_over_1_255"] == 0  # the engine is exact to float rounding
    assert zsweep.compare(img, img)["psnr"] is None


def test_reference_matches_the_cli(cli, tmp_path):
    s = zsweep.generate.spheres("c1", count=500, seed=2)
    assert s["centers"].shape == (500, 3) and s["colors"].shape == (500, 4)
    # The CLI's own file of the same set, so both read identical doubles.
    subprocess.run([ZSWEEP, "spheres", "generate", "c1", "--count", "500", "--seed", "2", "-o", tmp_path / "c.sphb"],
                   check=True, stdout=subprocess.DEVNULL)
    scene = {"image": {"width": 40, "height": 30}, "spheres": "c.sphb", "ao": {"directions": 6, "map_size": 64}}
    (tmp_path / "s.json").write_text(json.dumps(scene))
    out = tmp_path / "ref.exr"
    subprocess.run([ZSWEEP, "reference", tmp_path / "s.json", "-o", out], check=True, stdout=subprocess.DEVNULL)
    import OpenImageIO as oiio
    f = oiio.ImageInput.open(str(out))
    want = np.asarray(f.read_image(format="float"))
    f.close()
    got = zsweep.reference(tmp_path / "s.json", channels="all")
    assert np.array_equal(got["RGBA"], want[:, :, :4])
    assert np.array_equal(got["AO"], want[:, :, 5])
    # And the renderer against it, as `zsweep compare --json` says.
    ren = zsweep.render(tmp_path / "s.json", channels="all")
    rpath = tmp_path / "ren.exr"
    subprocess.run([ZSWEEP, "render", tmp_path / "s.json", "-o", rpath], check=True, stdout=subprocess.DEVNULL)
    c = cli_json("compare", rpath, out, "--json")
    py = zsweep.compare(ren, got)
    assert py["max_abs"] == pytest.approx(c["max_abs"], rel=1e-12, abs=0)
    assert py["pixels_over_1_255"] == c["pixels_over_1_255"]
    assert py["z"]["coverage_mismatches"] == c["z"]["coverage_mismatches"]


def test_surface_reference_is_the_exact_mode():
    m = {"points": np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float),
         "triangles": np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])}
    scene = {"image": {"width": 32, "height": 32}, "surfaces": [m], "ground": {"height": 0},
             "lights": [{"type": "directional", "direction": [1, -2, 0.5]}]}
    ref, st = zsweep.reference_stats(scene)
    assert st["shadows"]["mode"] == "exact" and st["shadows"]["rays"] > 0


def test_generator_errors():
    with pytest.raises(ValueError, match="unknown shape 'cube'"):
        zsweep.generate.shape("cube")
    with pytest.raises(ValueError, match="field must be one of"):
        zsweep.generate.implicit("torus", field="nope")
    with pytest.raises(ValueError, match="unknown sphere test set 'c9'"):
        zsweep.generate.spheres("c9")
    with pytest.raises(RuntimeError, match="missing.off"):
        zsweep.generate.surface("missing.off")


def test_generate_image_is_deterministic_and_matches_the_cli(tmp_path):
    import os
    src = os.path.join(os.path.dirname(__file__), "..", "data", "images", "ball12.inr")
    a = zsweep.generate.image(src, 2.0, below=True, size=0.2)
    b = zsweep.generate.image(src, 2.0, below=True, size=0.2)
    assert len(a["tets"]) > 100
    for k in ("points", "tets", "scalar"):
        assert np.array_equal(a[k], b[k])
    # The CLI writes the same mesh (.off keeps every double: shortest round-trip text).
    out = tmp_path / "img.off"
    subprocess.run([ZSWEEP, "mesh", "generate", "image", src, "--iso", "2", "--below", "--size", "0.2", "-o", out],
                   check=True, stdout=subprocess.DEVNULL)
    pts, tets = read_off(out)
    assert np.array_equal(pts[:, :3], a["points"]) and np.array_equal(pts[:, 3], a["scalar"])
    assert np.array_equal(tets, a["tets"])
    with pytest.raises(RuntimeError, match=r"no voxel is above iso 1000 \(the image's values are 0.433013 to 4.76314\)"):
        zsweep.generate.image(src, 1000)
    with pytest.raises(RuntimeError, match="over the limit of 100 "):
        zsweep.generate.image(src, 2.0, below=True, size=0.05, max_points=100)
    with pytest.raises(ValueError, match="max_volume must be 0"):
        zsweep.generate.surface(src, max_volume=-1)


def test_generate_grid_matches_the_cli(tmp_path):
    a = zsweep.generate.grid((4, 3, 2), split=6, jitter=0.16, seed=3)
    assert a["points"].shape == (5 * 4 * 3, 3) and a["tets"].shape == (6 * 24, 4)
    assert a["points"][:, 0].min() == -1 and a["points"][:, 0].max() == 1  # the longest axis spans [-1, 1]
    plain = zsweep.generate.grid(4, field="none")
    assert plain["tets"].shape == (5 * 64, 4) and "scalar" not in plain
    out = tmp_path / "g.off"
    subprocess.run([ZSWEEP, "mesh", "generate", "grid", "--cells", "4,3,2", "--split", "6", "--jitter", "0.16",
                    "--seed", "3", "-o", out], check=True, stdout=subprocess.DEVNULL)
    pts, tets = read_off(out)
    assert np.array_equal(pts[:, :3], a["points"]) and np.array_equal(pts[:, 3], a["scalar"])
    assert np.array_equal(tets, a["tets"])
    p = a["points"][a["tets"]]
    assert (np.linalg.det(p[:, 1:] - p[:, :1]) > 0).all()  # every tet positive
    img, st = zsweep.render_stats({"mesh": a}, width=32, height=32)
    assert st["mesh"]["tets"] == 144
    with pytest.raises(ValueError, match=r"jitter must be in \[0, 0.16\], not 0.25"):
        zsweep.generate.grid(2, jitter=0.25)
    with pytest.raises(ValueError, match="split must be 5 or 6, not 4"):
        zsweep.generate.grid(2, split=4)
    with pytest.raises(ValueError, match=r"cells must be in \[1, 4294967294\], not 0"):
        zsweep.generate.grid((2, 0, 2))
    with pytest.raises(ValueError, match="cells must be N or"):
        zsweep.generate.grid((2, 2))
    with pytest.raises(ValueError, match="over the 4294967295 that 32-bit point ids allow"):
        zsweep.generate.grid(2000)
