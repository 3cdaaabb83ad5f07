#include "raster/triangle_clip.h"

namespace zs {

namespace {

// The point of edge in → out (in.z > z_near > out.z) on the plane.
ClipVertex cut(const ClipVertex& in, const ClipVertex& out, int n_attrs, double z_near) {
  const double t = (in.z - z_near) / (in.z - out.z);  // in (0, 1)
  ClipVertex c;
  c.x = in.x + t * (out.x - in.x);
  c.y = in.y + t * (out.y - in.y);
  c.z = z_near;
  const float tf = float(t);
  for (int k = 0; k < n_attrs; ++k) c.attr[k] = in.attr[k] + tf * (out.attr[k] - in.attr[k]);
  for (int k = n_attrs; k < kClipMaxAttrs; ++k) c.attr[k] = 0;
  return c;
}

}  // namespace

int clip_triangle_near(const ClipVertex in[3], int n_attrs, double z_near, ClipPolygon* out) {
  out->n = 0;
  const bool inside[3] = {in[0].z >= z_near, in[1].z >= z_near, in[2].z >= z_near};
  if (inside[0] && inside[1] && inside[2]) {
    for (int k = 0; k < 3; ++k) out->v[k] = in[k];
    return out->n = 3;
  }
  ClipVertex poly[4];
  int n = 0;
  bool strictly_inside = false;  // some vertex off the plane on the kept side
  for (int k = 0; k < 3; ++k) {
    const ClipVertex& s = in[k];
    const ClipVertex& e = in[(k + 1) % 3];
    const bool s_strict = s.z > z_near, e_strict = e.z > z_near;
    strictly_inside |= s_strict;
    // Cut only where the edge crosses the plane strictly (a vertex on the
    // plane is its own cut point).
    if (inside[(k + 1) % 3]) {
      if (!inside[k] && e_strict) poly[n++] = cut(e, s, n_attrs, z_near);
      poly[n++] = e;
    } else if (s_strict) {
      poly[n++] = cut(s, e, n_attrs, z_near);
    }
  }
  if (n < 3 || !strictly_inside) return 0;  // a point, an edge, or flat on the plane
  for (int k = 0; k < n; ++k) out->v[k] = poly[k];
  return out->n = n;
}

int fan_triangles(const ClipPolygon& poly, ClipVertex out[2][3]) {
  if (poly.n < 3) return 0;
  int t = 0;
  for (int k = 1; k + 1 < poly.n; ++k, ++t) {
    out[t][0] = poly.v[0];
    out[t][1] = poly.v[k];
    out[t][2] = poly.v[k + 1];
  }
  return t;
}

}  // namespace zs
