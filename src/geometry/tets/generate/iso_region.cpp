#include "geometry/tets/generate/iso_region.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace zs {

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

}  // namespace

IsoRegion find_iso_region(const VoxelImage& img, double iso, bool above, size_t max_crossings) {
  if (!std::isfinite(iso)) throw std::invalid_argument("iso value " + num(iso) + " is not a finite number");
  IsoRegion r;
  const auto [lo, hi] = std::minmax_element(img.values.begin(), img.values.end());
  r.lo = *lo;
  r.hi = *hi;
  const std::string side = above ? "above" : "below";
  const std::string range = " (the image's values are " + num(r.lo) + " to " + num(r.hi) + ")";
  if (above ? !(r.hi > iso) : !(r.lo < iso))
    throw std::invalid_argument("no voxel is " + side + " iso " + num(iso) + range);
  if (above ? r.lo > iso : r.hi < iso)
    throw std::invalid_argument("every voxel is " + side + " iso " + num(iso) + range +
                                ": the solid would be the whole image box");

  // Index -1 and n - 1 are outside (CGAL's value_outside), so edges to them
  // are the crossings that close the solid at the image border.
  const long nx = static_cast<long>(img.nx), ny = static_cast<long>(img.ny), nz = static_cast<long>(img.nz);
  auto inside = [&](long i, long j, long k) {
    if (i < 0 || j < 0 || k < 0 || i >= nx - 1 || j >= ny - 1 || k >= nz - 1) return false;
    const double v = img.at(static_cast<size_t>(i), static_cast<size_t>(j), static_cast<size_t>(k));
    return above ? v > iso : v < iso;
  };
  // Two passes: count the inside points and crossings, then keep an evenly
  // spread few of the crossings.
  size_t n_inside = 0, total = 0, count = 0;
  const size_t want = std::max<size_t>(max_crossings, 1);
  auto pick = [&](size_t kept) {
    return total <= want ? kept : static_cast<size_t>((static_cast<double>(kept) + 0.5) * total / want);
  };
  auto visit = [&](bool keep) {
    const long step[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (long k = -1; k < nz; ++k)
      for (long j = -1; j < ny; ++j)
        for (long i = -1; i < nx; ++i) {
          const bool a = inside(i, j, k);
          n_inside += !keep && a;
          for (const auto& s : step) {
            if (a == inside(i + s[0], j + s[1], k + s[2])) continue;
            if (keep && r.crossings.size() < want && count == pick(r.crossings.size())) {
              glm::dvec3 p = img.origin + glm::dvec3(i, j, k) * img.spacing;
              glm::dvec3 q = img.origin + glm::dvec3(i + s[0], j + s[1], k + s[2]) * img.spacing;
              if (!a) std::swap(p, q);
              r.crossings.push_back({p, q});
            }
            ++count;
          }
        }
  };
  visit(false);
  if (count == 0) throw std::invalid_argument("no voxel edge inside the image crosses iso " + num(iso) + range);
  r.volume = static_cast<double>(n_inside) * img.spacing.x * img.spacing.y * img.spacing.z;
  total = count;
  count = 0;
  visit(true);
  return r;
}

}  // namespace zs
