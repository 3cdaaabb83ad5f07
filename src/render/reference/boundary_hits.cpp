#include "render/reference/boundary_hits.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace zs {

bool line_hits_triangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
                        const glm::dvec3& c, double* t) {
  // Shear so the line is the +z axis; the 2-D edge functions of a shared edge
  // are then computed from the same numbers in both triangles (exact
  // negatives), so a point on an edge is inside at least one of them.
  const double ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (d[kz] < 0) std::swap(kx, ky);
  const double sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1.0 / d[kz];
  const glm::dvec3 A = a - o, B = b - o, C = c - o;
  const double Ax = A[kx] - sx * A[kz], Ay = A[ky] - sy * A[kz];
  const double Bx = B[kx] - sx * B[kz], By = B[ky] - sy * B[kz];
  const double Cx = C[kx] - sx * C[kz], Cy = C[ky] - sy * C[kz];
  const double U = Cx * By - Cy * Bx, V = Ax * Cy - Ay * Cx, W = Bx * Ay - By * Ax;
  if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0)) return false;
  const double det = U + V + W;
  if (det == 0) return false;  // the line lies in the triangle's plane: it grazes, no crossing
  *t = (U * A[kz] + V * B[kz] + W * C[kz]) * sz / det;
  return std::isfinite(*t);
}

BoundaryBins::BoundaryBins(const TetMesh& m, const Topology& topo, const SolidFaces& solid, const View& view)
    : m_(m), topo_(topo) {
  for (uint32_t f = 0; f < topo.num_faces(); ++f)
    if (solid.boundary(f)) faces_.push_back(f);
  // Outward side: away from the fourth vertex of the face's tet.
  outward_sign_.resize(faces_.size());
  for (size_t k = 0; k < faces_.size(); ++k) {
    const auto fv = topo.face(faces_[k]);
    const Tet& t = m.tets[solid.tets[faces_[k]][0]];
    uint32_t opp = t[0];
    for (uint32_t v : t)
      if (v != fv[0] && v != fv[1] && v != fv[2]) opp = v;
    const glm::dvec3 &a = m.points[fv[0]], &b = m.points[fv[1]], &c = m.points[fv[2]];
    outward_sign_[k] = glm::dot(glm::cross(b - a, c - a), m.points[opp] - a) < 0;
  }

  const uint32_t W = view.width(), H = view.height();
  // About four million bins at most, whatever the resolution.
  bin_px_ = std::max<uint32_t>(8, uint32_t(std::ceil(std::sqrt(double(W) * H / 4.0e6))));
  bins_x_ = (W + bin_px_ - 1) / bin_px_;
  bins_y_ = (H + bin_px_ - 1) / bin_px_;
  const glm::dvec3 eye = view.eye(), fwd = view.forward();

  // Screen rectangle (in bins) covered by the lines of sight through a face.
  // Perspective: a face wholly behind the eye is seen along the same lines as
  // its mirror image through the eye; one straddling the eye plane can be
  // anywhere on screen.
  struct Rect {
    int x0, y0, x1, y1;
  };
  auto rect_of = [&](uint32_t f, Rect* r) {
    const auto fv = topo.face(f);
    double z[3];
    for (int k = 0; k < 3; ++k) z[k] = glm::dot(m.points[fv[k]] - eye, fwd);
    bool mirror = false;
    if (view.perspective()) {
      const double scale = std::max({std::abs(z[0]), std::abs(z[1]), std::abs(z[2])});
      const double eps = 1e-9 * scale;
      if (z[0] > eps && z[1] > eps && z[2] > eps) mirror = false;
      else if (z[0] < -eps && z[1] < -eps && z[2] < -eps) mirror = true;
      else return false;
    }
    double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 p = mirror ? 2.0 * eye - m.points[fv[k]] : m.points[fv[k]];
      const ViewPoint vp = view.project(p);
      lo_x = std::min(lo_x, vp.x), hi_x = std::max(hi_x, vp.x);
      lo_y = std::min(lo_y, vp.y), hi_y = std::max(hi_y, vp.y);
    }
    if (!(hi_x >= -1 && lo_x <= W && hi_y >= -1 && lo_y <= H)) {
      *r = {1, 1, 0, 0};  // off screen: empty
      return true;
    }
    // One pixel of slack against rounding in the projection.
    auto bin = [&](double v, uint32_t n) {
      return int(std::clamp(std::floor((v + 0.5) / bin_px_), 0.0, double(n - 1)));
    };
    *r = {bin(lo_x - 1, bins_x_), bin(lo_y - 1, bins_y_), bin(hi_x + 1, bins_x_), bin(hi_y + 1, bins_y_)};
    return true;
  };

  std::vector<Rect> rects(faces_.size());
  std::vector<uint8_t> bounded(faces_.size());
  offsets_.assign(size_t(bins_x_) * bins_y_ + 1, 0);
  for (size_t k = 0; k < faces_.size(); ++k) {
    bounded[k] = rect_of(faces_[k], &rects[k]);
    if (!bounded[k]) {
      everywhere_.push_back(uint32_t(k));
      continue;
    }
    for (int y = rects[k].y0; y <= rects[k].y1; ++y)
      for (int x = rects[k].x0; x <= rects[k].x1; ++x) ++offsets_[size_t(y) * bins_x_ + x + 1];
  }
  for (size_t b = 1; b < offsets_.size(); ++b) offsets_[b] += offsets_[b - 1];
  items_.resize(offsets_.back());
  std::vector<uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (size_t k = 0; k < faces_.size(); ++k) {
    if (!bounded[k]) continue;
    for (int y = rects[k].y0; y <= rects[k].y1; ++y)
      for (int x = rects[k].x0; x <= rects[k].x1; ++x) items_[fill[size_t(y) * bins_x_ + x]++] = uint32_t(k);
  }
}

void BoundaryBins::hits(uint32_t i, uint32_t j, const glm::dvec3& o, const glm::dvec3& d,
                        std::vector<BoundaryHit>* out) const {
  out->clear();
  auto test = [&](uint32_t k) {
    const auto fv = topo_.face(faces_[k]);
    const glm::dvec3 &a = m_.points[fv[0]], &b = m_.points[fv[1]], &c = m_.points[fv[2]];
    double t;
    if (!line_hits_triangle(o, d, a, b, c, &t)) return;
    const double dn = glm::dot(glm::cross(b - a, c - a), d);
    if (dn == 0) return;
    const bool entry = (dn < 0) == bool(outward_sign_[k]);
    out->push_back({t, faces_[k], entry});
  };
  const size_t bin = size_t(j / bin_px_) * bins_x_ + i / bin_px_;
  for (uint32_t q = offsets_[bin]; q < offsets_[bin + 1]; ++q) test(items_[q]);
  for (uint32_t k : everywhere_) test(k);
  std::sort(out->begin(), out->end(), [](const BoundaryHit& x, const BoundaryHit& y) {
    if (x.t != y.t) return x.t < y.t;
    return x.entry > y.entry;
  });
}

}  // namespace zs
