"""The scenes of scripts/bench shadows: meshes written as .obj (world
coordinates) or the CGAL elephant (.off, with a transform), the ground square
zsweep adds (src/scene/surface_input.cpp), a perspective camera that frames the
surfaces and their shadows, the zsweep scene JSON and the VTK worker's job
(shadow_vtk.py) for the same scene."""
import math
import os
import subprocess

import numpy as np

FOV_Y = 35.0
SHADING = {"model": "phong", "ambient": 0.2, "diffuse": 0.7, "specular": 0.3, "shininess": 32}
GROUND_COLOR = [0.9, 0.9, 0.9]
CGAL_ARCHIVES = ["/usr/share/doc/libcgal-dev/data.tar.gz", "/usr/share/doc/libcgal-demo/data.tar.gz",
                 "/usr/share/doc/libcgal-demo/demo.tar.gz"]


# ---------------------------------------------------------------- geometry

def rotate(p, deg):
    """p' = Rz·Ry·Rx·p (x first), as zsweep's transform (surface_input.cpp)."""
    ax, ay, az = (math.radians(a) for a in deg)
    cx, sx, cy, sy, cz, sz = math.cos(ax), math.sin(ax), math.cos(ay), math.sin(ay), math.cos(az), math.sin(az)
    rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return np.asarray(p, dtype=np.float64) @ (rz @ ry @ rx).T


def transform(p, t):
    t = t or {}
    return rotate(float(t.get("scale", 1.0)) * np.asarray(p, dtype=np.float64), t.get("rotate_deg", [0, 0, 0])) + \
        np.asarray(t.get("translate", [0, 0, 0]), dtype=np.float64)


def box(centre, half, rot_deg=(0, 0, 0)):
    """(points 8×3, triangles 12×3) of a box, counter-clockwise seen from
    outside (zsweep culls back faces)."""
    s = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=np.float64)
    local = s * np.asarray(half, dtype=np.float64)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    tris = []
    for a, b, c, d in quads:
        for t in ((a, b, c), (a, c, d)):
            n = np.cross(local[t[1]] - local[t[0]], local[t[2]] - local[t[0]])
            if np.dot(n, local[list(t)].mean(axis=0)) < 0:
                t = (t[0], t[2], t[1])
            tris.append(t)
    return rotate(local, rot_deg) + np.asarray(centre, dtype=np.float64), np.array(tris, dtype=np.int64)


def merge(parts):
    pts, tris, base = [], [], 0
    for p, t in parts:
        pts.append(p)
        tris.append(t + base)
        base += len(p)
    return np.vstack(pts), np.vstack(tris)


def write_obj(path, pts, tris):
    with open(path, "w") as f:
        f.write("# written by scripts/benchmarks/shadows/shadow_scenes.py\n")
        for p in pts:
            f.write("v %.9g %.9g %.9g\n" % tuple(p))
        for t in tris:
            f.write("f %d %d %d\n" % tuple(int(i) + 1 for i in t))


def read_points(path):
    """The vertices of an .obj or .off (enough for bounds)."""
    if path.endswith(".obj"):
        with open(path) as f:
            return np.array([l.split()[1:4] for l in f if l.startswith("v ")], dtype=np.float64)
    with open(path) as f:
        toks = [l.split("#", 1)[0].split() for l in f]
    toks = [t for t in toks if t]
    head, i = toks[0][1:], 1
    if len(head) < 2:
        head, i = toks[1], 2
    return np.array([t[:3] for t in toks[i:i + int(head[0])]], dtype=np.float64)


# ---------------------------------------------------------------- scenes

def make_bars(d):
    """Thin long bars on thin posts, three of them turned 20-35° about the
    vertical, under an oblique light: long straight slanted shadow edges."""
    parts = []
    for (x, z, y, rot, length) in [(-0.3, -1.1, 0.7, 0.0, 3.2), (0.2, -0.2, 0.9, 23.0, 3.0),
                                   (-0.1, 0.7, 1.1, -31.0, 2.8), (0.3, 1.5, 0.8, 35.0, 2.6)]:
        a = math.radians(rot)
        along = np.array([math.cos(a), 0.0, -math.sin(a)])  # rotate_deg y: x axis goes to (cos, 0, -sin)
        parts.append(box([x, y, z], [length / 2, 0.05, 0.07], (0, rot, 0)))
        for s in (-0.42, 0.42):
            c = np.array([x, 0.0, z]) + along * s * length
            parts.append(box([c[0], (y - 0.05) / 2, c[2]], [0.02, (y - 0.05) / 2, 0.02], (0, rot, 0)))
    pts, tris = merge(parts)
    path = os.path.join(d, "bars.obj")
    write_obj(path, pts, tris)
    return {"name": "bars", "surfaces": [{"path": path, "color": [0.75, 0.55, 0.4]}], "ground_height": 0.0,
            "light": [-1.0, -1.3, -0.5], "azimuth": 25.0, "elevation": 40.0}


def make_tilted(d):
    """A slab tilted 60° (its lower edge on the ground) and a cube resting on
    it; the light grazes the slab at ~61° from its normal."""
    tilt, half, thick, cube = 60.0, 1.0, 0.02, 0.2
    n = rotate([0, 1, 0], (tilt, 0, 0))
    lift = half * math.sin(math.radians(tilt)) + thick
    slab_c = np.array([0.0, lift, 0.0])
    parts = [box(slab_c, [half, thick, half], (tilt, 0, 0)),
             box(slab_c + n * (thick + cube), [cube, cube, cube], (tilt, 0, 0))]
    pts, tris = merge(parts)
    path = os.path.join(d, "tilted.obj")
    write_obj(path, pts, tris)
    return {"name": "tilted", "surfaces": [{"path": path, "color": [0.7, 0.7, 0.75]}], "ground_height": None,
            "light": [-0.6, -0.8, -0.1], "azimuth": 20.0, "elevation": 38.0}


def make_elephant(d):
    """The CGAL elephant (its z up turned to y), 2 units long, over the ground."""
    for a in CGAL_ARCHIVES:
        if not os.path.isfile(a):
            continue
        r = subprocess.run(["tar", "xzf", a, "-C", d, "--wildcards", "*/meshes/elephant.off"],
                           capture_output=True, text=True)
        for root, _dirs, files in os.walk(d):
            if "elephant.off" in files and r.returncode == 0:
                path = os.path.join(root, "elephant.off")
                return {"name": "elephant",
                        "surfaces": [{"path": path, "color": [0.8, 0.6, 0.5],
                                      "transform": {"translate": [0, 0.6, 0], "rotate_deg": [-90, -60, 0], "scale": 2}}],
                        "ground_height": None, "light": [-1.0, -2.0, -1.0], "azimuth": -40.0, "elevation": 40.0}
    return None


def make_scenes(names, d):
    """{name: scene} for the names that can be made; messages for those that cannot."""
    os.makedirs(d, exist_ok=True)
    makers = {"bars": make_bars, "elephant": make_elephant, "tilted": make_tilted}
    out, notes = {}, []
    for n in names:
        s = makers[n](d)
        if s is None:
            notes.append(f"scene {n} skipped: no CGAL data archive with elephant.off ({', '.join(CGAL_ARCHIVES)})")
            continue
        finish(s)
        out[n] = s
    return out, notes


def finish(s):
    """Bounds, ground square and the framing camera of a scene."""
    pts = np.vstack([transform(read_points(x["path"]), x.get("transform")) for x in s["surfaces"]])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    c = 0.5 * (lo + hi)
    ext = max(hi[0] - lo[0], hi[2] - lo[2], 1e-300)
    h = lo[1] if s["ground_height"] is None else s["ground_height"]
    g = 2.0 * ext  # half side
    s["ground"] = [[c[0] - g, h, c[2] - g], [c[0] + g, h, c[2] - g], [c[0] + g, h, c[2] + g], [c[0] - g, h, c[2] + g]]
    s["ground_y"], s["ground_half"], s["ground_centre"] = float(h), float(g), [float(c[0]), float(c[2])]
    s["extent"] = float(np.linalg.norm(hi - lo))
    # Frame the surfaces and their shadows on the ground.
    dl = np.asarray(s["light"], dtype=np.float64)
    t = np.clip((pts[:, 1] - h) / max(-dl[1], 1e-9), 0, 4 * ext)
    shadow = pts + t[:, None] * dl
    both = np.vstack([pts, shadow])
    blo, bhi = both.min(axis=0), both.max(axis=0)
    s["camera"] = orbit_camera(0.5 * (blo + bhi), 0.5 * float(np.linalg.norm(bhi - blo)), s["azimuth"], s["elevation"])


def orbit_camera(target, radius, azimuth, elevation, fill=0.8):
    """Perspective camera looking down `elevation` degrees at `target`, far
    enough that a sphere of `radius` about it nearly fills the view."""
    az, el = math.radians(azimuth), math.radians(elevation)
    dist = fill * radius / math.sin(math.radians(FOV_Y / 2))
    eye = np.asarray(target) + dist * np.array([math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az)])
    return {"projection": "perspective", "eye": [float(x) for x in eye], "target": [float(x) for x in target],
            "up": [0.0, 1.0, 0.0], "fov_y": FOV_Y}


def ground_camera(s, elevation=55.0, azimuth=25.0):
    """A camera on `s` that sees ground (or surfaces) in every pixel: it looks
    down at the bars' centre from as far as its corner rays still land on the
    ground square (the Eq. 5.7 deferred-shading case, f = h·w)."""
    g, (cx, cz), h = s["ground_half"], s["ground_centre"], s["ground_y"]
    target = np.array([cx, h, cz])
    dist = 2.0 * g
    while dist > 1e-3 * g:
        cam = orbit_camera(target, dist * math.sin(math.radians(FOV_Y / 2)), azimuth, elevation, fill=1.0)
        if all(corner_on_ground(cam, a, b, g, cx, cz, h) for a in (-1, 1) for b in (-1, 1)):
            return cam
        dist *= 0.95
    raise RuntimeError("no camera sees only ground")


def corner_on_ground(cam, a, b, g, cx, cz, h):
    eye, tgt = np.array(cam["eye"]), np.array(cam["target"])
    f = (tgt - eye) / np.linalg.norm(tgt - eye)
    r = np.cross(f, cam["up"])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    t = math.tan(math.radians(cam["fov_y"] / 2))
    d = f + a * t * r + b * t * u
    if d[1] >= 0:
        return False
    p = eye + d * ((h - eye[1]) / d[1])
    return abs(p[0] - cx) < 0.98 * g and abs(p[2] - cz) < 0.98 * g


# ---------------------------------------------------------------- scene files

def scene_json(s, width, height, shadows, camera=None):
    """The zsweep scene of `s` (shadows: dict, or False for no shadows)."""
    ground = {"color": GROUND_COLOR}
    if s["ground_height"] is not None:
        ground["height"] = s["ground_height"]
    return {"image": {"width": width, "height": height, "background": [0.0, 0.0, 0.0, 1.0]},
            "camera": camera or s["camera"],
            "surfaces": [dict(x) for x in s["surfaces"]],
            "ground": ground,
            "lights": [{"type": "directional", "direction": s["light"]}],
            "shading": SHADING,
            "shadows": shadows}


def vtk_job(s, width, height, map_size, repeat, png):
    cam = s["camera"]
    return {"surfaces": s["surfaces"], "ground": s["ground"], "ground_color": GROUND_COLOR,
            "camera": {"eye": cam["eye"], "target": cam["target"], "up": cam["up"], "fov_y": cam["fov_y"]},
            "light": {"direction": s["light"]}, "map_size": map_size, "width": width, "height": height,
            "repeat": repeat, "png": png, "rebake": True}
