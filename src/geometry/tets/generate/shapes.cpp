#include "geometry/tets/generate/shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace zs {

namespace {

constexpr double kPi = std::numbers::pi;

int segments(double length, double h, int min_n) {
  return std::max(min_n, static_cast<int>(std::ceil(length / h)));
}

// Box [lo, hi] whose 12 edges carry points about h apart, facets in
// box_surface's order (z lo, z hi, y lo, y hi, x lo, x hi). Edge points give
// the count a resolution knob: TetGen's -a alone refines the few equal
// tets of a bare box in steps of up to 40 %.
Plc edged_box(const glm::dvec3& lo, const glm::dvec3& hi, double h) {
  Plc plc;
  for (int k = 0; k < 8; ++k) plc.add_point({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> inner;  // a < b, points from a to b
  auto edge = [&](uint32_t a, uint32_t b) {
    const bool flip = a > b;
    auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = inner.find(key);
    if (it == inner.end()) {
      const glm::dvec3 p = plc.points[key.first], q = plc.points[key.second];
      const int n = segments(glm::length(q - p), h, 1);
      std::vector<uint32_t> v;
      for (int i = 1; i < n; ++i) v.push_back(plc.add_point(p + (q - p) * (static_cast<double>(i) / n)));
      it = inner.emplace(key, std::move(v)).first;
    }
    std::vector<uint32_t> v = it->second;
    if (flip) std::reverse(v.begin(), v.end());
    return v;
  };
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    std::vector<uint32_t> loop;
    for (int i = 0; i < 4; ++i) {
      loop.push_back(q[i]);
      for (uint32_t v : edge(q[i], q[(i + 1) % 4])) loop.push_back(v);
    }
    plc.add_polygon(loop);
  }
  return plc;
}

// Unit icosahedron.
void icosahedron(std::vector<glm::dvec3>& v, std::vector<std::array<int, 3>>& f) {
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  v = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
       {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  for (auto& x : v) x = glm::normalize(x);
  f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
       {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
       {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
}

// Unit directions of a geodesic sphere and its triangles. Points shared by
// neighbouring faces are identified by their integer barycentric weights on
// icosahedron vertices, so each is computed exactly once.
void geodesic(int n, std::vector<glm::dvec3>& dirs, std::vector<std::array<uint32_t, 3>>& tris) {
  std::vector<glm::dvec3> iv;
  std::vector<std::array<int, 3>> faces;
  icosahedron(iv, faces);
  std::map<std::array<int, 6>, uint32_t> index;
  auto point = [&](std::array<int, 3> vid, std::array<int, 3> w) {
    // Canonical key: (vertex, weight) pairs with nonzero weight, sorted by vertex.
    std::array<std::pair<int, int>, 3> pw = {{{vid[0], w[0]}, {vid[1], w[1]}, {vid[2], w[2]}}};
    std::sort(pw.begin(), pw.end());
    std::array<int, 6> key{-1, 0, -1, 0, -1, 0};
    int k = 0;
    glm::dvec3 pos(0.0);
    for (auto [v, wt] : pw)
      if (wt) {
        key[2 * k] = v;
        key[2 * k + 1] = wt;
        ++k;
        pos += iv[v] * static_cast<double>(wt);
      }
    auto [it, fresh] = index.try_emplace(key, static_cast<uint32_t>(dirs.size()));
    if (fresh) dirs.push_back(glm::normalize(pos));
    return it->second;
  };
  for (const auto& f : faces) {
    auto P = [&](int i, int j) { return point(f, {n - i - j, i, j}); };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        tris.push_back({P(i, j), P(i + 1, j), P(i, j + 1)});
        if (i + j + 2 <= n) tris.push_back({P(i + 1, j), P(i + 1, j + 1), P(i, j + 1)});
      }
  }
}

// Smooth random bumps on the sphere: radius factor 1 + sum of Gaussians of
// angular distance, deterministic per seed.
struct Bumps {
  std::vector<glm::dvec3> centres;
  std::vector<double> amps;
  explicit Bumps(uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> nd;
    std::uniform_real_distribution<double> ud(-0.25, 0.35);
    for (int k = 0; k < 7; ++k) {
      centres.push_back(glm::normalize(glm::dvec3(nd(rng), nd(rng), nd(rng))));
      amps.push_back(ud(rng));
    }
  }
  double operator()(const glm::dvec3& d) const {
    double r = 1.0;
    for (size_t k = 0; k < centres.size(); ++k) {
      glm::dvec3 e = d - centres[k];
      r += amps[k] * std::exp(-glm::dot(e, e) / (2 * 0.35 * 0.35));
    }
    return std::max(r, 0.4);
  }
};

Plc sphere_like(const glm::dvec3& c, const glm::dvec3& radii, int freq, const Bumps* bumps) {
  std::vector<glm::dvec3> dirs;
  std::vector<std::array<uint32_t, 3>> tris;
  geodesic(freq, dirs, tris);
  Plc plc;
  for (const glm::dvec3& d : dirs) plc.add_point(c + radii * d * (bumps ? (*bumps)(d) : 1.0));
  for (const auto& t : tris) plc.add_triangle(t[0], t[1], t[2]);
  return plc;
}

int ellipsoid_freq(const glm::dvec3& radii, double h) {
  // Icosahedron edge on the unit sphere is ~1.05; a geodesic edge is 1.05 r/n.
  double r = std::max({radii.x, radii.y, radii.z});
  return segments(1.05 * r, h, 2);
}

// Box with a vertical cylindrical tunnel (a "post" in a flow channel).
Plc post_shape(double h) {
  const glm::dvec3 lo(-1.5, -1.0, 0.0), hi(1.5, 1.0, 1.0);
  const double r = 0.3;
  const int n = segments(2 * kPi * r, h, 16);
  Plc plc = edged_box(lo, hi, h);
  const uint32_t c0 = static_cast<uint32_t>(plc.points.size());
  for (int z = 0; z < 2; ++z)
    for (int i = 0; i < n; ++i) {
      double a = 2 * kPi * i / n;
      plc.add_point({r * std::cos(a), r * std::sin(a), z ? hi.z : lo.z});
    }
  auto ring = [&](int z, int i) { return c0 + static_cast<uint32_t>(z * n + (i % n)); };
  // The z caps (facets 0 and 1) get the tunnel's circle as a hole.
  for (int z = 0; z < 2; ++z) {
    PlcFacet& cap = plc.facets[static_cast<size_t>(z)];
    std::vector<uint32_t> circle;
    for (int i = 0; i < n; ++i) circle.push_back(ring(z, i));
    cap.polygons.push_back(circle);
    cap.holes.push_back({0.0, 0.0, z ? hi.z : lo.z});
  }
  for (int i = 0; i < n; ++i) plc.add_polygon({ring(0, i), ring(0, i + 1), ring(1, i + 1), ring(1, i)});
  return plc;
}

// Channel around a thin triangular (delta) wing, which is cut out as a hole.
Plc delta_shape() {
  Plc plc = box_surface({-1.0, -1.0, -0.5}, {2.0, 1.0, 0.5});
  const double t = 0.05;
  const glm::dvec3 apex(-0.5, 0.0, 0.0), left(1.0, -0.7, 0.0), right(1.0, 0.7, 0.0);
  const glm::dvec3 dz(0, 0, t);
  uint32_t b = static_cast<uint32_t>(plc.points.size());
  for (const glm::dvec3& p : {apex - dz, left - dz, right - dz, apex + dz, left + dz, right + dz})
    plc.add_point(p);
  plc.add_polygon({b, b + 1, b + 2});
  plc.add_polygon({b + 3, b + 4, b + 5});
  plc.add_polygon({b, b + 1, b + 4, b + 3});
  plc.add_polygon({b + 1, b + 2, b + 5, b + 4});
  plc.add_polygon({b + 2, b, b + 3, b + 5});
  plc.holes.push_back((apex + left + right) / 3.0);
  return plc;
}

// Torso-like: an ellipsoid with an off-centre ellipsoidal cavity.
Plc shell_shape(double h) {
  const glm::dvec3 outer(0.9, 0.6, 1.5), inner(0.35, 0.25, 0.5), ic(0.2, 0.0, 0.3);
  Plc plc = ellipsoid_surface(glm::dvec3(0.0), outer, ellipsoid_freq(outer, h));
  append_plc(plc, ellipsoid_surface(ic, inner, ellipsoid_freq(inner, h)));
  plc.holes.push_back(ic);
  return plc;
}

}  // namespace

Plc ellipsoid_surface(const glm::dvec3& centre, const glm::dvec3& radii, int freq) {
  return sphere_like(centre, radii, std::max(freq, 1), nullptr);
}

Plc torus_surface(double major, double minor, int nu, int nv) {
  Plc plc;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
      double rr = major + minor * std::cos(v);
      plc.add_point({rr * std::cos(u), rr * std::sin(u), minor * std::sin(v)});
    }
  auto id = [&](int i, int j) { return static_cast<uint32_t>((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      plc.add_triangle(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      plc.add_triangle(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return plc;
}

Plc box_surface(const glm::dvec3& lo, const glm::dvec3& hi) {
  Plc plc;
  for (int k = 0; k < 8; ++k)
    plc.add_point({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
  plc.add_polygon({0, 2, 3, 1});  // z = lo
  plc.add_polygon({4, 5, 7, 6});  // z = hi
  plc.add_polygon({0, 1, 5, 4});  // y = lo
  plc.add_polygon({2, 6, 7, 3});  // y = hi
  plc.add_polygon({0, 4, 6, 2});  // x = lo
  plc.add_polygon({1, 3, 7, 5});  // x = hi
  return plc;
}

void append_plc(Plc& a, const Plc& b) {
  const uint32_t off = static_cast<uint32_t>(a.points.size());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (PlcFacet f : b.facets) {
    for (auto& poly : f.polygons)
      for (uint32_t& v : poly) v += off;
    a.facets.push_back(std::move(f));
  }
  a.holes.insert(a.holes.end(), b.holes.begin(), b.holes.end());
}

const std::vector<ShapeInfo>& shape_catalog() {
  static const std::vector<ShapeInfo> cat = {
      {"box", "cube [-1,1]^3", 8.0, false},
      {"sphere", "unit sphere", 4.0 / 3.0 * kPi, true},
      {"blob", "sphere with random smooth bumps (--seed)", 4.0 / 3.0 * kPi * 1.3, true},
      {"torus", "torus R=1 r=0.4 (non-convex, one handle)", 2 * kPi * kPi * 0.16, true},
      {"shell", "ellipsoid with an ellipsoidal cavity (torso-like)",
       4.0 / 3.0 * kPi * (0.9 * 0.6 * 1.5 - 0.35 * 0.25 * 0.5), true},
      {"post", "box with a cylindrical tunnel (post-like)", 6.0 - kPi * 0.09, false},
      {"delta", "channel around a thin delta wing (delta-like)", 6.0, false},
  };
  return cat;
}

const ShapeInfo* find_shape(const std::string& name) {
  for (const ShapeInfo& s : shape_catalog())
    if (s.name == name) return &s;
  return nullptr;
}

Plc make_shape(const std::string& name, double h, uint64_t seed) {
  if (!(h > 0)) throw std::invalid_argument("shape resolution must be positive");
  if (name == "box") return edged_box(glm::dvec3(-1.0), glm::dvec3(1.0), h);
  if (name == "sphere") return ellipsoid_surface(glm::dvec3(0.0), glm::dvec3(1.0), ellipsoid_freq(glm::dvec3(1.0), h));
  if (name == "blob") {
    Bumps bumps(seed);
    // Bumps stretch the surface by up to ~1.6x; refine accordingly.
    return sphere_like(glm::dvec3(0.0), glm::dvec3(1.0), ellipsoid_freq(glm::dvec3(1.5), h), &bumps);
  }
  if (name == "torus") {
    const double R = 1.0, r = 0.4;
    return torus_surface(R, r, segments(2 * kPi * (R + r), h, 12), segments(2 * kPi * r, h, 6));
  }
  if (name == "shell") return shell_shape(h);
  if (name == "post") return post_shape(h);
  if (name == "delta") return delta_shape();
  throw std::invalid_argument("unknown shape '" + name + "'");
}

}  // namespace zs
