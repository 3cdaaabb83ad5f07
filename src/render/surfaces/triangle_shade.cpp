#include "render/surfaces/triangle_shade.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace zs {

TriangleShade triangle_shade(const TriangleMesh& mesh, uint32_t t, const View& view, ShadingModel model,
                             const glm::dvec3& color) {
  using glm::dot;
  const auto& tri = mesh.tris[t];
  const glm::dvec3 &A = mesh.points[tri[0]], &B = mesh.points[tri[1]], &C = mesh.points[tri[2]];
  const glm::dvec3 E = view.eye(), F = view.forward(), R = view.right(), U = view.up();
  const bool persp = view.perspective();
  const glm::dvec3 f = glm::cross(B - A, C - A);
  const double n2 = dot(f, f);
  glm::dvec3 g = f * (1.0 / std::sqrt(n2));
  // Turned to the eye: the side the pixels' rays come from (for a plane in
  // front of a perspective eye, the sign of g·(A − E) is that of g·ray).
  const double fl = (persp ? dot(g, A - E) : dot(g, F)) > 0 ? -1.0 : 1.0;
  g *= fl;
  const double K = dot(g, A - E), al = dot(g, F), be = dot(g, R), ga = dot(g, U);
  TriangleShade s;
  if (persp) {
    s.num[0] = K, s.num[1] = 0, s.num[2] = 0;
    s.den[0] = al, s.den[1] = be, s.den[2] = ga;
  } else {
    s.num[0] = K, s.num[1] = -be, s.num[2] = -ga;
    s.den[0] = al, s.den[1] = 0, s.den[2] = 0;
  }
  for (int k = 0; k < 3; ++k) s.g[k] = g[k], s.color[k] = float(color[k]);
  if (model != ShadingModel::Phong) {
    for (int k = 0; k < 3; ++k) s.m[0][k] = g[k], s.m[1][k] = 0, s.m[2][k] = 0;
    return s;
  }
  // Barycentrics of a point P of the plane: wa = 1 + ga·(P − A),
  // wb = gb·(P − A) (relative to A: no cancellation far from the origin).
  const glm::dvec3 gA = glm::cross(f, C - B) / n2, gB = glm::cross(f, A - C) / n2;
  const double qa = 1.0 + dot(gA, E - A), qb = dot(gB, E - A);
  // den·wa and den·wb as (1, a, b) coefficients: P − A = (E − A) + s·w
  // (perspective, num = K) or (E − A) + a·R + b·U + s·F (orthographic,
  // den = α).
  double Wa[3], Wb[3];
  if (persp) {
    const glm::dvec3 d(al, be, ga);
    const glm::dvec3 pa(dot(gA, F), dot(gA, R), dot(gA, U)), pb(dot(gB, F), dot(gB, R), dot(gB, U));
    for (int j = 0; j < 3; ++j) Wa[j] = d[j] * qa + K * pa[j], Wb[j] = d[j] * qb + K * pb[j];
  } else {
    Wa[0] = al * qa + K * dot(gA, F), Wa[1] = al * dot(gA, R) - be * dot(gA, F), Wa[2] = al * dot(gA, U) - ga * dot(gA, F);
    Wb[0] = al * qb + K * dot(gB, F), Wb[1] = al * dot(gB, R) - be * dot(gB, F), Wb[2] = al * dot(gB, U) - ga * dot(gB, F);
  }
  const glm::dvec3 Na = fl * mesh.normals[tri[0]], Nb = fl * mesh.normals[tri[1]], Nc = fl * mesh.normals[tri[2]];
  // den·N = den·Nc + (den·wa)(Na − Nc) + (den·wb)(Nb − Nc). With g turned to
  // the eye, den < 0 wherever the hit is in front of it (num/den > 0 with
  // num = g·(A − E) < 0; orthographic: den = g·F < 0): −(den·N) points as N.
  for (int j = 0; j < 3; ++j) {
    const double dj = s.den[j];
    const glm::dvec3 mj = -(dj * Nc + Wa[j] * (Na - Nc) + Wb[j] * (Nb - Nc));
    for (int k = 0; k < 3; ++k) s.m[j][k] = mj[k];
  }
  // Scaled so that the direction is about unit length over the triangle (1
  // at its centroid): the pixels normalize it in floats, whose squares
  // would leave their range for scenes of large coordinates.
  const glm::dvec3 G = (A - E) + ((B - A) + (C - A)) / 3.0;
  const double ga_ = persp ? dot(G, R) / dot(G, F) : dot(G, R), gb_ = persp ? dot(G, U) / dot(G, F) : dot(G, U);
  glm::dvec3 M;
  for (int k = 0; k < 3; ++k) M[k] = s.m[0][k] + s.m[1][k] * ga_ + s.m[2][k] * gb_;
  const double len = std::sqrt(dot(M, M));
  if (len > 0 && len < INFINITY)
    for (auto& row : s.m)
      for (double& v : row) v /= len;
  return s;
}

void triangle_shades(const TriangleMesh& mesh, const std::vector<uint32_t>& source, const View& view,
                     ShadingModel model, const std::vector<glm::dvec3>& colors, int threads,
                     std::vector<TriangleShade>* out) {
  out->resize(source.size());
  auto run = [&](size_t i0, size_t i1) {
    for (size_t i = i0; i < i1; ++i) {
      const uint32_t t = source[i];
      (*out)[i] = triangle_shade(mesh, t, view, model, colors[mesh.surface[t]]);
    }
  };
  if (threads <= 1 || source.size() < 4096) {
    run(0, source.size());
    return;
  }
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, source.size(), 1024),
                      [&](const tbb::blocked_range<size_t>& r) { run(r.begin(), r.end()); });
  });
}

}  // namespace zs
