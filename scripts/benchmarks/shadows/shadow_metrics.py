"""Image metrics of scripts/bench shadows: a map-mode lit0 against the exact
(Embree shadow-ray) lit0 of the same view.

- levels: distinct lit0 values over the surface pixels (finite lit0); the
  bound is n·k + 1 (digest §2.6.4).
- exact edge pixels: surface pixels whose exact lit0 differs from that of a
  4-neighbour surface pixel.
- band: pixels within `band_texels` map texels (world units: the --stats
  texel) of an exact edge pixel; a pixel's distance to the nearest edge pixel
  (scipy's Euclidean distance transform, pixels) is turned into world units
  with the pixel footprint at that pixel, Z·2·tan(fov_y/2)/H (perspective).
- inside the band: RMSE and max |lit_map − lit_exact|; outside it: wrongly lit
  (exact 0, map ≥ 0.5) and wrongly shadowed (exact 1, map < 0.5) pixels.
- peter-panning: wrongly lit pixels anywhere.
"""
import math

import numpy as np
from scipy import ndimage

from ..lib.common import luminance


def read_exr(path):
    """{channel name: float32 H×W} of an EXR/TIFF written by zsweep."""
    import OpenImageIO as oiio
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        raise RuntimeError(f"{path}: {buf.geterror()}")
    px = buf.get_pixels(oiio.FLOAT)
    if px is None or px.ndim != 3:
        raise RuntimeError(f"{path}: cannot read pixels")
    return {n: px[:, :, i] for i, n in enumerate(buf.spec().channelnames)}


class Reference:
    """The exact view of one scene and image size, with its edge distances."""

    def __init__(self, exr, fov_y):
        ch = read_exr(exr)
        self.lit = ch["lit0"].astype(np.float64)
        self.z = ch["Z"].astype(np.float64)
        self.rgb = np.stack([ch["R"], ch["G"], ch["B"]], axis=-1).astype(np.float64)
        self.surf = np.isfinite(self.lit)
        h = self.lit.shape[0]
        self.footprint = np.where(self.surf, self.z, 0.0) * 2.0 * math.tan(math.radians(fov_y) / 2) / h
        lit = np.where(self.surf, self.lit, np.nan)
        edge = np.zeros_like(self.surf)
        for axis in (0, 1):
            for shift in (1, -1):
                nb = np.roll(lit, shift, axis=axis)
                nsurf = np.roll(self.surf, shift, axis=axis)
                # np.roll wraps around: the wrapped row/column is no neighbour
                if axis == 0:
                    nsurf[0 if shift == 1 else -1, :] = False
                else:
                    nsurf[:, 0 if shift == 1 else -1] = False
                edge |= self.surf & nsurf & (nb != lit)
        self.edge = edge
        self.edges = int(edge.sum())
        self.dist_px = ndimage.distance_transform_edt(~edge) if edge.any() else np.full(edge.shape, np.inf)
        self.dist_world = self.dist_px * self.footprint
        self.pixels = int(self.surf.sum())


def compare(ref, map_exr, texel, band_texels, depths, pcf):
    """The metrics of one map-mode render against `ref` (dict)."""
    ch = read_exr(map_exr)
    lit = ch["lit0"].astype(np.float64)
    surf = ref.surf
    if not np.array_equal(np.isfinite(lit), surf):
        raise RuntimeError(f"{map_exr}: its surface pixels differ from the exact render's "
                           f"({int(np.isfinite(lit).sum())} vs {int(surf.sum())})")
    return metrics(ref, lit, texel, band_texels, depths, pcf)


def metrics(ref, lit, texel, band_texels, depths, pcf):
    surf = ref.surf
    exact = ref.lit
    levels = int(np.unique(lit[surf]).size)
    max_levels = int(depths * pcf + 1)
    band = surf & (ref.dist_world <= band_texels * texel)
    far = surf & ~band
    diff = np.abs(lit - exact)
    wrong_lit = (exact == 0) & (lit >= 0.5)
    wrong_shadowed = (exact == 1) & (lit < 0.5)
    nb = int(band.sum())
    return {
        "surface_pixels": int(surf.sum()),
        "footprint_median": float(np.median(ref.footprint[surf])) if surf.any() else 0.0,
        "levels": levels, "max_levels": max_levels, "levels_reached": levels == max_levels,
        "edge_pixels": ref.edges, "band_pixels": nb,
        "band_rmse": float(math.sqrt(np.mean(diff[band] ** 2))) if nb else 0.0,
        "band_max": float(diff[band].max()) if nb else 0.0,
        "rmse_all": float(math.sqrt(np.mean(diff[surf] ** 2))) if surf.any() else 0.0,
        "far_wrong_lit": int((wrong_lit & far).sum()),
        "far_wrong_shadowed": int((wrong_shadowed & far).sum()),
        "wrong_lit_all": int((wrong_lit & surf).sum()),
        "wrong_shadowed_all": int((wrong_shadowed & surf).sum()),
    }


def darker_pixels(shadowed_exr, plain_exr):
    """Pixels at least 0.1 darker (luminance) with shadows than without: the
    VTK worker's shadow_check, on our images."""
    a, b = read_exr(shadowed_exr), read_exr(plain_exr)
    la = luminance(np.stack([a["R"], a["G"], a["B"]], axis=-1).astype(np.float64))
    lb = luminance(np.stack([b["R"], b["G"], b["B"]], axis=-1).astype(np.float64))
    return int(np.count_nonzero(lb - la > 0.1))
