// Clipping a camera-space triangle against the near plane z >= z_near
// (z = view depth), before projection: positions and attributes are affine
// in camera space, so cut vertices interpolate them linearly along the edge.
//
// Sutherland–Hodgman against one plane: a triangle gives a convex polygon of
// 0, 3 or 4 vertices, in the input's cyclic order (winding preserved). A
// vertex exactly on the plane counts as inside and is never cut again.
// Degenerate results (only vertices on the plane: zero area) are empty.
// A cut point is computed from the inside end towards the outside end, so an
// edge shared by two triangles is cut at the same point whichever way round
// each walks it (no cracks), and its z is set to exactly z_near.
#pragma once

namespace zs {

constexpr int kClipMaxAttrs = 8;

struct ClipVertex {
  double x, y, z;              // camera space
  float attr[kClipMaxAttrs];   // the first n_attrs are carried
};

struct ClipPolygon {
  ClipVertex v[4];
  int n = 0;  // 0, 3 or 4
};

// Clips `in` against z >= z_near, carrying the first n_attrs (<= kClipMaxAttrs)
// attributes; returns out->n.
int clip_triangle_near(const ClipVertex in[3], int n_attrs, double z_near, ClipPolygon* out);

// Fans a clipped polygon into 0–2 triangles with the polygon's winding
// ((v0, v1, v2), (v0, v2, v3)); returns how many.
int fan_triangles(const ClipPolygon& poly, ClipVertex out[2][3]);

}  // namespace zs
