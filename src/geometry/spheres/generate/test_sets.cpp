// Synthetic C1, C3 and C4. Each sphere consumes a fixed number of random
// draws, so a set is a pure function of (count, seed).
#include "geometry/spheres/generate/test_sets.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "geometry/spheres/generate/portable_random.h"

namespace zs {

namespace {

void reserve(SphereSet& s, size_t n) {
  s.centres.reserve(n);
  s.radii.reserve(n);
  s.rgba.reserve(n);
}

void add(SphereSet& s, const glm::dvec3& c, double r, const glm::vec4& rgba) {
  s.centres.push_back(c);
  s.radii.push_back(r);
  s.rgba.push_back(rgba);
}

// A saturated-ish random colour: each channel in [0.2, 1].
glm::vec4 random_colour(PortableRandom& rng, float alpha) {
  const float r = float(rng.uniform(0.2, 1.0)), g = float(rng.uniform(0.2, 1.0)), b = float(rng.uniform(0.2, 1.0));
  return {r, g, b, alpha};
}

}  // namespace

bool parse_sphere_test_set(const std::string& s, SphereTestSet* out) {
  std::string l = s;
  std::transform(l.begin(), l.end(), l.begin(), [](unsigned char c) { return std::tolower(c); });
  if (l == "c1") *out = SphereTestSet::C1;
  else if (l == "c2") *out = SphereTestSet::C2;
  else if (l == "c3") *out = SphereTestSet::C3;
  else if (l == "c4") *out = SphereTestSet::C4;
  else return false;
  return true;
}

const char* to_string(SphereTestSet t) {
  switch (t) {
    case SphereTestSet::C1: return "c1";
    case SphereTestSet::C2: return "c2";
    case SphereTestSet::C3: return "c3";
    case SphereTestSet::C4: return "c4";
  }
  return "?";
}

size_t default_sphere_count(SphereTestSet t) {
  switch (t) {
    case SphereTestSet::C1: return 1'000'000;
    case SphereTestSet::C2: return 2'463'048;
    case SphereTestSet::C3: return 8'000'000;
    case SphereTestSet::C4: return 27'000'000;
  }
  return 0;
}

SphereSet generate_c1(size_t count, uint64_t seed) {
  PortableRandom rng(seed);
  SphereSet s;
  reserve(s, count);
  for (size_t i = 0; i < count; ++i) {
    const bool cluster = rng.uniform() < 0.3;
    glm::dvec3 c;
    double r;
    if (cluster) {
      c = {5.0 * rng.normal(), 5.0 * rng.normal(), 5.0 * rng.normal()};
      c = glm::clamp(c, glm::dvec3(-50.0), glm::dvec3(50.0));
      r = rng.uniform(0.1, 0.3);
    } else {
      c = {rng.uniform(-50.0, 50.0), rng.uniform(-50.0, 50.0), rng.uniform(-50.0, 50.0)};
      r = rng.uniform(0.2, 0.6);
    }
    const bool opaque = rng.uniform() < 0.8;
    const float alpha = opaque ? 1.f : float(rng.uniform(0.2, 0.6));
    if (opaque) rng.bits();  // keep the draw count per sphere fixed
    add(s, c, r, random_colour(rng, alpha));
  }
  return s;
}

SphereSet generate_c3(size_t count, uint64_t seed) {
  constexpr size_t kPerCluster = 2000;
  constexpr double kPitch = 10.0, kJitter = 1.0, kClusterRadius = 2.5;
  PortableRandom rng(seed);
  const size_t clusters = std::max<size_t>(1, count / kPerCluster);
  const size_t g = size_t(std::ceil(std::cbrt(double(clusters)) - 1e-9));
  const double half = 0.5 * double(g) * kPitch;  // the grid spans [-half, half]^3
  SphereSet s;
  reserve(s, count);
  for (size_t k = 0; k < clusters; ++k) {
    const glm::dvec3 cell{double(k % g), double(k / g % g), double(k / (g * g))};
    const glm::dvec3 centre = (cell + 0.5) * kPitch - half +
                              glm::dvec3(rng.uniform(-kJitter, kJitter), rng.uniform(-kJitter, kJitter),
                                         rng.uniform(-kJitter, kJitter));
    const glm::vec4 tint = random_colour(rng, 1.f);
    const size_t n = count / clusters + (k < count % clusters ? 1 : 0);
    for (size_t i = 0; i < n; ++i) {
      // Uniform in the ball: a uniform direction (normalised Gaussian) and
      // radius ~ cbrt(u).
      glm::dvec3 d{rng.normal(), rng.normal(), rng.normal()};
      const double len = glm::length(d);
      d = len > 0 ? d / len : glm::dvec3(1, 0, 0);
      const glm::dvec3 c = centre + d * (kClusterRadius * std::cbrt(rng.uniform()));
      const double r = rng.uniform(0.08, 0.15);
      const double edge = std::max({std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)}) / half;  // 0 at the centre, ~1 at the border
      glm::vec4 rgba = tint * float(rng.uniform(0.8, 1.0));
      rgba.a = edge > 0.75 ? float(rng.uniform(0.1, 0.4)) : 1.f;
      if (edge <= 0.75) rng.bits();
      add(s, c, r, rgba);
    }
  }
  return s;
}

SphereSet generate_c4(size_t count, uint64_t seed) {
  PortableRandom rng(seed);
  const size_t n = std::max<size_t>(1, size_t(std::llround(std::cbrt(double(count)))));
  const size_t layers = (count + n * n - 1) / (n * n);
  const double extent = double(n);
  // Blobs of red and green spheres: centres well inside the block.
  struct Blob {
    glm::dvec3 c;
    bool red;
  };
  Blob blobs[8];
  const double blob_r = 0.12 * extent;
  for (int b = 0; b < 8; ++b)
    blobs[b] = {{rng.uniform(0.2, 0.8) * extent, rng.uniform(0.2, 0.8) * extent, rng.uniform(0.2, 0.8) * double(layers)},
                b % 2 == 0};
  SphereSet s;
  reserve(s, count);
  for (size_t i = 0; i < count; ++i) {
    const glm::dvec3 lattice{double(i % n), double(i / n % n), double(i / (n * n))};
    const glm::dvec3 c = lattice + 0.5 + glm::dvec3(rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2));
    const double r = rng.uniform(0.5, 0.7);
    const Blob* in = nullptr;
    for (const Blob& b : blobs)
      if (glm::dot(c - b.c, c - b.c) < blob_r * blob_r) {
        in = &b;
        break;
      }
    const double u = rng.uniform(), v = rng.uniform();
    glm::vec4 rgba;
    if (in) {
      const float shade = float(0.7 + 0.3 * u);
      rgba = in->red ? glm::vec4(shade, 0.1f, 0.1f, 0.f) : glm::vec4(0.1f, shade, 0.1f, 0.f);
      rgba.a = float(0.02 + 0.06 * v);
    } else {
      const float shade = float(0.5 + 0.3 * u);
      rgba = {0.6f * shade, 0.7f * shade, shade, v < 0.05 ? 1.f : float(0.1 + 0.2 * (v / 0.95 - 0.05 / 0.95))};
      if (rgba.a > 1.f) rgba.a = 1.f;
    }
    add(s, c, r, rgba);
  }
  return s;
}

}  // namespace zs
