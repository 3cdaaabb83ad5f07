"""zsweep.generate: the generators of `zsweep mesh generate` and `zsweep
spheres generate`, returning scene data (numpy arrays) instead of files.

Tet meshes come back as {"points": (N, 3), "tets": (M, 4), "scalar": (N,)},
sphere sets as {"centers": (N, 3), "radii": (N,), "colors": (N, 4)}: each can
be a scene's "mesh" or "spheres" as it is.
"""
import numbers
import os

from . import _zsweep  # loaded by zsweep/__init__.py first

__all__ = ["shape", "surface", "implicit", "image", "grid", "spheres", "shapes", "implicit_solids", "fields"]


def shape(name, tets=10000, quality=1.414, field="radial", seed=1):
    """TetGen mesh of a synthetic shape (zsweep.generate.shapes()) near `tets` tets."""
    return _zsweep.generate_shape(name, int(tets), float(quality), field, int(seed))


def surface(path, quality=1.414, max_volume=0.0, preserve_surface=False, field="distance", seed=1,
            max_tets=5000000):
    """TetGen mesh of the volume inside a closed surface file (.off, .stl, .ply, .obj).

    A max_volume that needs more than max_tets tets is refused, and TetGen
    stops with an error after adding max_tets / 4 points."""
    return _zsweep.generate_surface(os.fspath(path), float(quality), float(max_volume), bool(preserve_surface), field,
                                    int(seed), int(max_tets))


def implicit(name, size=None, field="distance", seed=1, max_points=250000):
    """CGAL Mesh_3 mesh of an implicit solid (zsweep.generate.implicit_solids()).

    The same arguments give the same mesh, here and from `zsweep mesh
    generate implicit`. A size that needs more than max_points points is
    refused; refinement stops with an error there."""
    return _zsweep.generate_implicit(name, None if size is None else float(size), field, int(seed), int(max_points))


def image(path, iso, below=False, size=None, field="image", seed=1, max_points=250000):
    """CGAL Mesh_3 mesh of a grey-level 3D image's iso-region (.inr, .inr.gz).

    An iso value that selects no voxel or every voxel is an error naming the
    image's value range. Deterministic and bounded as implicit()."""
    return _zsweep.generate_image(os.fspath(path), float(iso), bool(below), None if size is None else float(size), field,
                                  int(seed), int(max_points))


def grid(cells, split=5, jitter=0.0, field="gaussians", seed=1):
    """A box of cubes split into tets, as `zsweep mesh generate grid`.

    cells is N (N³ cubes) or (NX, NY, NZ); the longest axis spans [-1, 1].
    split 5 (alternating by parity) or 6 (around each cube's main diagonal);
    interior nodes move by up to jitter (at most 0.16) cell sizes per axis,
    the same for the same seed."""
    c = [cells] * 3 if isinstance(cells, numbers.Integral) else list(cells)
    return _zsweep.generate_grid([int(n) for n in c], int(split), float(jitter), field, int(seed))


def spheres(set, count=0, seed=1):
    """The sphere test sets C1-C4 ("c1".."c4"); count 0: the set's full size."""
    return _zsweep.generate_spheres(set, int(count), int(seed))


def shapes():
    return _zsweep.shapes()


def implicit_solids():
    return _zsweep.implicit_solids()


def fields():
    return _zsweep.fields() + ["none"]
