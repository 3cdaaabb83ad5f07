# The ParaView recipe (examples/paraview_zsweep.py) in headless pvpython: a
# .vtu opened with ParaView's reader, its Clip filter's output rendered by
# zsweep with the render view's camera. Skips where python3-paraview is absent.
import os
import shutil
import subprocess

import numpy as np
import pytest

import zsweep

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "..", "examples", "paraview_zsweep.py")


def test_paraview_example_headless(tmp_path):
    pv, xvfb = shutil.which("pvpython"), shutil.which("xvfb-run")
    if not pv:
        pytest.skip("pvpython is absent: install python3-paraview (on Debian 12 it conflicts with python3-vtk9, "
                    "which libvtk9-dev needs to build zsweep: build first, then swap; docs/python.md)")
    if not xvfb:
        pytest.skip("xvfb-run is absent (package xvfb)")
    shared = os.environ.get("ZSWEEP_SHARED", os.path.join(HERE, "..", "..", "..", "shared", "datasets"))
    mesh = os.path.join(shared, "kiefer.vtu")
    if not os.path.exists(mesh):
        pytest.skip("%s is absent (../shared/datasets)" % mesh)
    out, shot = tmp_path / "zsweep.png", tmp_path / "paraview.png"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [os.path.dirname(zsweep.__path__[0]),
                                                                    os.environ.get("PYTHONPATH")])))
    r = subprocess.run([xvfb, "-a", pv, EXAMPLE, mesh, "--clip", "--size", "200x150", "-o", str(out),
                        "--paraview-screenshot", str(shot), "--threads", "1"],
                       capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "wrote" in r.stdout
    import OpenImageIO as oiio

    def alpha(path):
        f = oiio.ImageInput.open(str(path))
        img = np.asarray(f.read_image(format="float"))
        f.close()
        assert img.shape[:2] == (150, 200) and img.shape[2] == 4
        return img[:, :, 3] > 0

    ours, theirs = alpha(out), alpha(shot)
    # The camera came across: zsweep's coverage is ParaView's own silhouette
    # of the same clipped mesh (up to edge pixels).
    iou = np.count_nonzero(ours & theirs) / np.count_nonzero(ours | theirs)
    assert theirs.sum() > 1000 and iou > 0.9, iou
