# zsweep.Renderer: a scene loaded once, rendered from several cameras; each
# image bit for bit what zsweep.render gives for that camera, and the mesh's
# topology built once (its time in the stats does not change).
import numpy as np
import pytest

import zsweep


def grid_scene(cells=6):
    m = zsweep.generate.grid(cells, jitter=0.1)
    return {"mesh": m, "image": {"width": 48, "height": 40},
            "transfer_function": {"color": [[0, 0.2, 0.3, 0.9], [1, 1, 0.6, 0.1]], "opacity": [[0, 0.1], [1, 0.9]],
                                  "unit_distance": 0.5}}


CAMERAS = [
    {"projection": "orthographic", "eye": [0.3, 0.4, 4], "target": [0, 0, 0], "up": [0, 1, 0], "height": 3},
    {"projection": "perspective", "eye": [3, 1.5, 2], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 40},
    {"eye": [-2.5, -1, 1.5]},  # changes the eye only: the rest stays
]


def test_renders_match_fresh_renders_and_keep_the_topology():
    scene = grid_scene()
    r = zsweep.Renderer(scene, threads=2)
    topo_ms = None
    current = {}
    for cam in CAMERAS:
        current.update(cam)
        img, st = r.render_stats(camera=cam)
        want = zsweep.render(dict(scene, camera=dict(current)), threads=2)
        assert np.array_equal(img, want), cam
        assert st["fragments"] > 0
        if topo_ms is None:
            topo_ms = st["time_ms"]["topology"]
        assert st["time_ms"]["topology"] == topo_ms  # built once, not per render
    # No camera: the last one again, the same image.
    assert np.array_equal(r.render(), want)


def test_sphere_scene_and_bad_camera():
    s = zsweep.generate.spheres("c1", count=50)
    r = zsweep.Renderer({"spheres": s, "image": {"width": 32, "height": 32}})
    cam = {"projection": "perspective", "eye": [0, 0, 30], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 30}
    assert np.array_equal(r.render(camera=cam),
                          zsweep.render({"spheres": s, "image": {"width": 32, "height": 32}, "camera": cam}))
    with pytest.raises(RuntimeError, match="camera.up must not be parallel"):
        r.render(camera={"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 0, 1]})
    with pytest.raises(RuntimeError, match="unknown key 'camera.fov'"):
        r.render(camera={"fov": 3})
