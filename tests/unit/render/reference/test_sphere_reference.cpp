// The Embree sphere reference (src/render/reference/sphere_reference.h) against
// closed forms computed here independently, in long double, for both
// projections.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "render/reference/sphere_reference.h"

namespace zs {
namespace {

using LD = long double;

Camera camera(Projection p, glm::dvec3 eye = {0, 0, 5}) {
  Camera c;
  c.projection = p;
  c.eye = eye;
  c.target = {0, 0, 0};
  c.up = {0, 1, 0};
  c.height = 4.0;
  c.fov_y = 40.0;
  return c;
}

SphereSet make_set(const std::vector<glm::dvec3>& c, const std::vector<double>& r) {
  SphereSet s;
  s.centres = c;
  s.radii = r;
  return s;
}

// The visible ray parameter of sphere (c, r) along o + t·u, in long double
// from the textbook quadratic; -1 when nothing at t > 0 is hit.
// *half_chord (if given) gets the half-chord h: near grazing (h -> 0) the
// root's condition number in the perpendicular distance is r/h.
LD closed_form_t(const glm::dvec3& o, const glm::dvec3& u, const glm::dvec3& c, double r, LD* half_chord = nullptr) {
  const LD wx = LD(c.x) - o.x, wy = LD(c.y) - o.y, wz = LD(c.z) - o.z;
  const LD tc = wx * u.x + wy * u.y + wz * u.z;
  const LD disc = LD(r) * r - (wx * wx + wy * wy + wz * wz - tc * tc);
  if (disc < 0) return -1;
  const LD h = std::sqrt(disc);
  if (half_chord) *half_chord = h;
  if (tc - h > 0) return tc - h;
  if (tc + h > 0) return tc + h;
  return -1;
}

LD closed_form_depth(const View& v, double X, double Y, const glm::dvec3& c, double r, LD* half_chord = nullptr) {
  glm::dvec3 o, u;
  v.ray(X, Y, &o, &u);
  const LD t = closed_form_t(o, u, c, r, half_chord);
  if (t < 0) return -1;
  const glm::dvec3 f = v.forward();
  return t * (LD(u.x) * f.x + LD(u.y) * f.y + LD(u.z) * f.z);
}

const Projection kBoth[] = {Projection::Orthographic, Projection::Perspective};

TEST(SphereReference, HeadOnDepthAndNormal) {
  for (Projection p : kBoth) {
    const View v(camera(p), 63, 63);  // odd: pixel 31 is the image centre
    const double r = 0.8;
    const SphereReference ref(make_set({{0, 0, 0}}, {r}), v);
    double depth;
    uint32_t id;
    glm::dvec3 n;
    ASSERT_TRUE(ref.nearest(31, 31, &depth, &id, &n));
    EXPECT_NEAR(depth, 5.0 - r, 1e-14);  // |eye − c| − r = dot(c − eye, f) − r on the axis
    EXPECT_EQ(id, 0u);
    EXPECT_NEAR(n.x, 0, 1e-14);
    EXPECT_NEAR(n.y, 0, 1e-14);
    EXPECT_NEAR(n.z, 1, 1e-14);
  }
}

TEST(SphereReference, OffAxisCentreRay) {
  // The ray through the projected centre passes through c: it hits at
  // distance |eye − c| − r along the ray (perspective), at view depth
  // dot(c − eye, f) − r (orthographic).
  const glm::dvec3 c(0.37, -0.21, 0.4);
  const double r = 0.3;
  for (Projection p : kBoth) {
    const View v(camera(p), 64, 48);
    const SphereReference ref(make_set({c}, {r}), v);
    const ViewPoint q = v.project(c);
    double depth;
    uint32_t id;
    glm::dvec3 n;
    ASSERT_TRUE(ref.nearest(q.x, q.y, &depth, &id, &n));
    const glm::dvec3 d = c - v.eye();
    const double expect = p == Projection::Orthographic
                              ? glm::dot(d, v.forward()) - r
                              : (glm::length(d) - r) * glm::dot(d, v.forward()) / glm::length(d);
    EXPECT_NEAR(depth, expect, 1e-13);
  }
}

TEST(SphereReference, OrthoCoverageMatchesAnalyticCircle) {
  const uint32_t W = 96, H = 80;
  const Camera cam = camera(Projection::Orthographic);
  const View v(cam, W, H);
  const glm::dvec3 c(0.4133, -0.2711, -1.0);
  const double r = 0.9173;
  const SphereSet set = make_set({c}, {r});
  const double bg[4] = {0.1, 0.2, 0.3, 0.5};
  const SphereReferenceImage img = render_sphere_reference(set, {glm::vec4(1, 0.5, 0.25, 1)}, Shading{}, v, bg, 1);
  // Pixel centres from the spec's formula (camera.h), not from View; the
  // camera looks down −z with right = +x and up = +y.
  uint64_t inside = 0;
  for (uint32_t j = 0; j < H; ++j)
    for (uint32_t i = 0; i < W; ++i) {
      const double a = ((i + 0.5) / W - 0.5) * cam.height * W / H, b = (0.5 - (j + 0.5) / H) * cam.height;
      const bool in = (a - c.x) * (a - c.x) + (b - c.y) * (b - c.y) <= r * r;
      inside += in;
      const float z = img.z[size_t(j) * W + i];
      const float* px = img.rgba.at(i, j);
      if (in) {
        EXPECT_TRUE(std::isfinite(z)) << i << "," << j;
        EXPECT_EQ(px[3], 1.f);
      } else {
        EXPECT_EQ(z, std::numeric_limits<float>::infinity()) << i << "," << j;
        for (int k = 0; k < 4; ++k) EXPECT_EQ(px[k], float(bg[k]));
      }
    }
  EXPECT_GT(inside, 100u);
  EXPECT_EQ(img.hits, inside);
}

TEST(SphereReference, EyeInsideSeesExit) {
  // Perspective eye inside the sphere, centre 0.2 behind it: straight ahead
  // the exit is at r − 0.2, and every ray hits.
  {
    const View v(camera(Projection::Perspective), 31, 31);
    const double r = 1.0;
    const SphereReference ref(make_set({{0, 0, 5.2}}, {r}), v);
    double depth;
    uint32_t id;
    glm::dvec3 n;
    ASSERT_TRUE(ref.nearest(15, 15, &depth, &id, &n));
    EXPECT_NEAR(depth, r - 0.2, 1e-14);
    EXPECT_NEAR(n.z, 1, 1e-14);  // the inside surface, turned to face the viewer
    std::vector<SphereCrossing> cr;
    ref.crossings(15, 15, &cr);
    ASSERT_EQ(cr.size(), 1u);
    EXPECT_FALSE(cr[0].entering);
    EXPECT_NEAR(cr[0].depth, r - 0.2, 1e-14);
    for (uint32_t j = 0; j < 31; j += 5)
      for (uint32_t i = 0; i < 31; i += 5) {
        ASSERT_TRUE(ref.nearest(i, j, &depth, &id, nullptr));
        EXPECT_NEAR(depth, closed_form_depth(v, i, j, {0, 0, 5.2}, r), 1e-13);
      }
  }
  // Orthographic eye plane through the centre: the exit, at depth r.
  {
    const View v(camera(Projection::Orthographic), 31, 31);
    const SphereReference ref(make_set({{0, 0, 5}}, {1.0}), v);
    double depth;
    uint32_t id;
    ASSERT_TRUE(ref.nearest(15, 15, &depth, &id, nullptr));
    EXPECT_NEAR(depth, 1.0, 1e-14);
  }
}

TEST(SphereReference, BehindTheCameraIsNotSeen) {
  for (Projection p : kBoth) {
    const View v(camera(p), 32, 32);
    const SphereSet set = make_set({{0, 0, 7.5}}, {2.0});  // wholly behind the eye (and its plane)
    const double bg[4] = {0, 0, 0, 0};
    const SphereReferenceImage img = render_sphere_reference(set, {glm::vec4(1)}, Shading{}, v, bg, 2);
    EXPECT_EQ(img.hits, 0u);
    for (float z : img.z) EXPECT_EQ(z, std::numeric_limits<float>::infinity());
  }
}

TEST(SphereReference, InterpenetratingSpheresSeamIsExact) {
  const glm::dvec3 ca(-0.3, 0.05, 0.0), cb(0.35, 0.1, 0.25);
  const double ra = 0.8, rb = 0.7;
  for (Projection p : kBoth) {
    const View v(camera(p), 96, 96);
    const SphereReference ref(make_set({ca, cb}, {ra, rb}), v);
    int seam = 0;
    for (uint32_t j = 0; j < 96; ++j)
      for (uint32_t i = 0; i < 96; ++i) {
        LD ha = 0, hb = 0;
        const LD da = closed_form_depth(v, i, j, ca, ra, &ha), db = closed_form_depth(v, i, j, cb, rb, &hb);
        double depth;
        uint32_t id;
        const bool hit = ref.nearest(i, j, &depth, &id, nullptr);
        ASSERT_EQ(hit, da >= 0 || db >= 0) << i << "," << j;
        if (!hit) continue;
        const bool a_wins = db < 0 || (da >= 0 && da <= db);
        const LD best = a_wins ? da : db;
        // Double rounding of the perpendicular distance (~1e-16·|c − o|) is
        // amplified by r/h near the silhouette; 1e-13 elsewhere.
        const LD tol = 1e-13L * std::max(1.0L, (a_wins ? ra / ha : rb / hb));
        EXPECT_NEAR(LD(depth), best, tol) << i << "," << j;
        if (da >= 0 && db >= 0) {
          ++seam;
          if (std::fabs(da - db) > 1e-12L) EXPECT_EQ(id, da < db ? 0u : 1u) << i << "," << j;
        }
      }
    EXPECT_GT(seam, 200);
  }
}

TEST(SphereReference, FloatTiesResolvedExactly) {
  // Sphere 1 is sphere 0 moved 1e-9 towards the eye: identical in float, so
  // only the exact test can tell that sphere 1's front is nearer.
  // Sphere 2 duplicates sphere 3 exactly: the smaller id wins the tie.
  const std::vector<glm::dvec3> c = {{-0.5, 0, 0}, {-0.5, 0, 1e-9}, {0.6, 0.1, 0}, {0.6, 0.1, 0}};
  const std::vector<double> r = {0.45, 0.45, 0.4, 0.4};
  for (Projection p : kBoth) {
    const View v(camera(p), 64, 64);
    const SphereReference ref(make_set(c, r), v);
    int left = 0, right = 0;
    for (uint32_t j = 0; j < 64; ++j)
      for (uint32_t i = 0; i < 64; ++i) {
        double depth;
        uint32_t id;
        if (!ref.nearest(i, j, &depth, &id, nullptr)) continue;
        const LD d0 = closed_form_depth(v, i, j, c[0], r[0]), d1 = closed_form_depth(v, i, j, c[1], r[1]);
        if (id <= 1) {
          ++left;
          if (d1 >= 0 && (d0 < 0 || d1 < d0)) EXPECT_EQ(id, 1u) << i << "," << j;
        } else {
          ++right;
          EXPECT_EQ(id, 2u);
        }
      }
    EXPECT_GT(left, 50);
    EXPECT_GT(right, 50);
  }
}

TEST(SphereReference, FloatOrderDisagreesWithExact) {
  // Pairs of spheres differing by less than float resolution in centre and
  // radius: where their fronts are within rounding, Embree's float order
  // often disagrees with the exact one, and only the exact band finds the
  // truly nearest. Every pixel is checked against the closed forms.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-1.6, 1.6), rad(0.08, 0.2), tiny(-3e-8, 3e-8);
  std::vector<glm::dvec3> c;
  std::vector<double> r;
  for (int k = 0; k < 150; ++k) {
    const glm::dvec3 a(pos(rng), pos(rng), pos(rng) * 0.3);
    const double ra = rad(rng);
    c.push_back(a);
    r.push_back(ra);
    c.push_back(a + glm::dvec3(tiny(rng), tiny(rng), tiny(rng)));
    r.push_back(ra + tiny(rng));
  }
  for (Projection p : kBoth) {
    const View v(camera(p), 128, 128);
    const SphereReference ref(make_set(c, r), v);
    int checked = 0;
    for (uint32_t j = 0; j < 128; ++j)
      for (uint32_t i = 0; i < 128; ++i) {
        double depth;
        uint32_t id;
        const bool hit = ref.nearest(i, j, &depth, &id, nullptr);
        LD best = -1, second = -1;
        uint32_t best_id = 0;
        for (uint32_t k = 0; k < c.size(); ++k) {
          const LD d = closed_form_depth(v, i, j, c[k], r[k]);
          if (d < 0) continue;
          if (best < 0 || d < best) {
            second = best;
            best = d, best_id = k;
          } else if (second < 0 || d < second) {
            second = d;
          }
        }
        // Pixels within double rounding of a silhouette or of a tie are left out.
        if (best < 0) continue;
        if (second >= 0 && second - best < 1e-12L) continue;
        ++checked;
        ASSERT_TRUE(hit) << i << "," << j;
        EXPECT_EQ(id, best_id) << i << "," << j;
      }
    EXPECT_GT(checked, 1000);
  }
}

TEST(SphereReference, CrossingsSortedTwoPerSphere) {
  const glm::dvec3 ca(-0.3, 0.05, 0.0), cb(0.35, 0.1, 0.25), cc(0, 0, -2);
  const std::vector<double> r = {0.8, 0.7, 0.5};
  for (Projection p : kBoth) {
    const View v(camera(p), 48, 48);
    const SphereReference ref(make_set({ca, cb, cc}, r), v);
    std::vector<SphereCrossing> cr;
    for (uint32_t j = 0; j < 48; j += 3)
      for (uint32_t i = 0; i < 48; i += 3) {
        ref.crossings(i, j, &cr);
        size_t crossed = 0;
        const glm::dvec3 cs[3] = {ca, cb, cc};
        for (int k = 0; k < 3; ++k) crossed += closed_form_depth(v, i, j, cs[k], r[k]) >= 0;
        ASSERT_EQ(cr.size(), 2 * crossed) << i << "," << j;
        for (size_t k = 1; k < cr.size(); ++k) {
          EXPECT_LE(cr[k - 1].depth, cr[k].depth);
          if (cr[k - 1].depth == cr[k].depth) EXPECT_LE(cr[k - 1].id, cr[k].id);
        }
        // Each sphere is entered before it is left; the first crossing is the nearest hit.
        for (uint32_t s = 0; s < 3; ++s) {
          int state = 0;
          for (const SphereCrossing& x : cr)
            if (x.id == s) {
              EXPECT_EQ(x.entering, state == 0);
              ++state;
            }
        }
        double depth;
        uint32_t id;
        if (ref.nearest(i, j, &depth, &id, nullptr)) {
          ASSERT_FALSE(cr.empty());
          EXPECT_EQ(cr[0].depth, depth);
          EXPECT_EQ(cr[0].id, id);
        }
      }
  }
}

// The any-hit query the AO reference uses agrees with the full crossing
// list, from points on (and just inside) the spheres of a dense random set,
// where rays start inside neighbours and graze them.
TEST(SphereReference, RayBlockedAgreesWithCrossings) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<glm::dvec3> c;
  std::vector<double> r;
  for (int k = 0; k < 300; ++k) {
    c.push_back({2 * U(rng), 2 * U(rng), 2 * U(rng)});
    r.push_back(0.15 + 0.1 * (U(rng) + 1));
  }
  const View v(camera(Projection::Orthographic), 8, 8);
  const SphereReference ref(make_set(c, r), v);
  std::vector<SphereCrossing> cr;
  int blocked = 0, open = 0;
  for (int q = 0; q < 4000; ++q) {
    const uint32_t id = uint32_t(q % c.size());
    glm::dvec3 n = glm::normalize(glm::dvec3(U(rng), U(rng), U(rng)));
    glm::dvec3 w = glm::normalize(glm::dvec3(U(rng), U(rng), U(rng)));
    if (glm::dot(n, w) < 0) w = -w;
    const glm::dvec3 P = c[id] + r[id] * (q % 2 ? 1.0 : 0.999) * n;
    ref.ray_crossings(P, w, &cr);
    bool expect = false;
    for (const SphereCrossing& x : cr) expect |= x.id != id && x.depth > 0;
    ASSERT_EQ(ref.ray_blocked(P, w, id), expect) << q;
    (expect ? blocked : open) += 1;
  }
  EXPECT_GT(blocked, 400);  // both answers are exercised
  EXPECT_GT(open, 400);
}

TEST(SphereReference, EqualDepthCrossingsOrderedById) {
  const View v(camera(Projection::Orthographic), 16, 16);
  const SphereReference ref(make_set({{0, 0, 0}, {0, 0, 0}}, {1.0, 1.0}), v);
  std::vector<SphereCrossing> cr;
  ref.crossings(8, 8, &cr);
  ASSERT_EQ(cr.size(), 4u);
  EXPECT_EQ(cr[0].id, 0u);
  EXPECT_EQ(cr[1].id, 1u);
  EXPECT_TRUE(cr[0].entering && cr[1].entering);
  EXPECT_EQ(cr[2].id, 0u);
  EXPECT_FALSE(cr[2].entering);
}

TEST(SphereReference, ShadedCentrePixel) {
  for (Projection p : kBoth) {
    const View v(camera(p), 33, 33);
    const glm::vec4 col(0.8f, 0.3f, 0.1f, 1.f);
    Shading sh;
    sh.light_direction = {0.3, -0.2, -1};  // not a headlight, so N·L and N·H matter
    const double bg[4] = {0, 0, 0, 0};
    const SphereReferenceImage img = render_sphere_reference(make_set({{0, 0, 0}}, {1.0}), {col}, sh, v, bg, 0);
    const glm::dvec3 expect = shade(sh, glm::dvec3(col.r, col.g, col.b), {0, 0, 1}, {0, 0, 1});
    const float* px = img.rgba.at(16, 16);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(px[k], expect[k], 1e-6);
    EXPECT_EQ(px[3], 1.f);
    EXPECT_NEAR(img.z[16 * 33 + 16], 4.0, 1e-6);
  }
}

TEST(SphereReference, InvalidSpheresSkipped) {
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  const SphereSet set =
      make_set({{0, 0, 0}, {1, 0, 0}, {nan, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {1.0, 0.0, 1.0, -1.0, inf});
  const View v(camera(Projection::Orthographic), 31, 31);
  const SphereReference ref(set, v);
  EXPECT_EQ(ref.invalid(), 4u);
  double depth;
  uint32_t id;
  ASSERT_TRUE(ref.nearest(15, 15, &depth, &id, nullptr));
  EXPECT_EQ(id, 0u);
  EXPECT_NEAR(depth, 4.0, 1e-14);
  // And an empty set hits nothing.
  const SphereReference none(SphereSet{}, v);
  EXPECT_FALSE(none.nearest(15, 15, &depth, &id, nullptr));
}

}  // namespace
}  // namespace zs
