#include "render/reference/sphere_reference.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace zs {

namespace {

// The exact line–sphere roots t0 <= t1 along o + t·u (u unit), in double.
// The half-chord comes from the perpendicular distance d = |(c − o) × u|
// (no cancellation of |c − o|² − tc²), and the root nearer zero from the
// product of the roots, t0·t1 = |c − o|² − r², so neither root suffers the
// cancellation of tc ∓ h. False when the line misses (d > r).
inline bool exact_roots(const glm::dvec3& o, const glm::dvec3& u, const glm::dvec3& c, double r, double* t0,
                        double* t1) {
  const glm::dvec3 w = c - o;
  const double tc = glm::dot(w, u);
  const glm::dvec3 x = glm::cross(w, u);
  const double d = std::sqrt(glm::dot(x, x));
  if (d > r) return false;
  const double h = std::sqrt((r - d) * (r + d));
  const double wl = std::sqrt(glm::dot(w, w));
  const double prod = (wl - r) * (wl + r);
  if (tc >= 0) {
    *t1 = tc + h;
    *t0 = *t1 > 0 ? prod / *t1 : 0.0;  // t1 == 0 only when tc = h = 0: a tangent at the origin
  } else {
    *t0 = tc - h;
    *t1 = prod / *t0;
  }
  return true;
}

struct ExactSphere {
  glm::dvec3 c;
  double r;
  uint32_t id;  // index in the SphereSet
};

enum class Query { Nearest, Band, Crossings, Blocked };

// Our state rides behind Embree's context (the documented way to reach it
// from a filter callback).
struct Ctx {
  RTCIntersectContext rc;
  const std::vector<ExactSphere>* spheres;
  glm::dvec3 o, u;  // the exact (double) ray
  Query query;
  double best_t;    // nearest exact visible hit so far (ray parameter)
  uint32_t best_prim;
  std::vector<SphereCrossing>* out;  // Crossings: ray parameters for now, depths later
  uint32_t skip_id;                   // Blocked: the sphere (set index) that never blocks
  bool blocked;                       // Blocked: a crossing at t > 0 of another sphere was seen
};

inline bool better(double t, uint32_t id, double best_t, uint32_t best_id) {
  return t < best_t || (t == best_t && id < best_id);
}

void filter(const RTCFilterFunctionNArguments* args) {
  Ctx* ctx = reinterpret_cast<Ctx*>(args->context);
  const auto& sph = *ctx->spheres;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    const ExactSphere& s = sph[prim];
    double t0, t1;
    const bool line_hits = exact_roots(ctx->o, ctx->u, s.c, s.r, &t0, &t1);
    if (ctx->query == Query::Crossings) {
      // Record both surfaces and keep going; the same sphere may be reported
      // twice (its near and far float hits), duplicates go after sorting.
      if (line_hits) {
        if (t0 > 0) ctx->out->push_back({t0, s.id, true});
        if (t1 > 0) ctx->out->push_back({t1, s.id, false});
      }
      args->valid[i] = 0;
      continue;
    }
    if (ctx->query == Query::Blocked) {
      // Any surface ahead of the origin (entry, or exit when the origin is
      // inside) of another sphere blocks: accept it, and rtcOccluded1 stops.
      if (line_hits && s.id != ctx->skip_id && (t0 > 0 || t1 > 0)) {
        ctx->blocked = true;
      } else {
        args->valid[i] = 0;
      }
      continue;
    }
    const double t = !line_hits ? -1.0 : t0 > 0 ? t0 : t1;
    if (t <= 0) {
      args->valid[i] = 0;  // the exact sphere is missed, or only behind the origin
      continue;
    }
    const uint32_t best_id = ctx->best_prim == RTC_INVALID_GEOMETRY_ID ? UINT32_MAX : sph[ctx->best_prim].id;
    if (better(t, s.id, ctx->best_t, best_id)) {
      ctx->best_t = t;
      ctx->best_prim = prim;
    }
    // Nearest: accept, so Embree culls what lies beyond this float hit.
    // Band: reject, so every candidate in the band is seen.
    if (ctx->query == Query::Band) args->valid[i] = 0;
  }
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

struct SphereReference::Impl {
  View view;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<ExactSphere> spheres;  // by Embree primitive index
  glm::dvec3 centre{0};              // the float BVH's coordinates are relative to it
  double bound_r = 0;                // every enlarged sphere lies within this of `centre`
  double slack = 0;                  // G below: how far a float hit may stray from the exact one

  explicit Impl(const View& v) : view(v) {}
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
  void check(const char* what) const {
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE)
      throw std::runtime_error(std::string("sphere reference: Embree error ") + std::to_string(int(e)) + " in " +
                               what);
  }

  // The Embree ray for the exact ray o + t·u: it starts at parameter *t_shift
  // (shortly before the scene's bounding sphere, or before the origin when
  // that is inside it) so Embree's float coordinates stay local to the
  // scene. False when the ray misses the bounding sphere or lies behind.
  bool setup(const glm::dvec3& o, const glm::dvec3& u, RTCRayHit* rh, double* t_shift) const {
    double b0, b1;
    if (!exact_roots(o, u, centre, bound_r, &b0, &b1) || b1 <= 0) return false;
    *t_shift = std::max(b0, 0.0) - slack;
    const glm::dvec3 start = o + *t_shift * u - centre;
    RTCRay& ray = rh->ray;
    ray.org_x = float(start.x), ray.org_y = float(start.y), ray.org_z = float(start.z);
    ray.dir_x = float(u.x), ray.dir_y = float(u.y), ray.dir_z = float(u.z);
    ray.tnear = 0.f;
    ray.tfar = std::numeric_limits<float>::infinity();
    ray.time = 0.f;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.primID = RTC_INVALID_GEOMETRY_ID;
    return true;
  }
  // A query `q` along o + t·u: the context (no best hit, no output, no
  // sphere skipped) and the Embree ray; false when there is nothing to ask.
  bool begin(Ctx* ctx, const glm::dvec3& o, const glm::dvec3& u, Query q, RTCRayHit* rh, double* t_shift) const {
    if (!scene) return false;
    rtcInitIntersectContext(&ctx->rc);
    ctx->spheres = &spheres;
    ctx->o = o;
    ctx->u = u;
    ctx->query = q;
    ctx->best_t = std::numeric_limits<double>::infinity();
    ctx->best_prim = RTC_INVALID_GEOMETRY_ID;
    ctx->out = nullptr;
    ctx->skip_id = UINT32_MAX;
    ctx->blocked = false;
    return setup(o, u, rh, t_shift);
  }

};

SphereReference::SphereReference(const SphereSet& set, const View& view, int threads)
    : impl_(std::make_unique<Impl>(view)) {
  Impl& m = *impl_;
  // Only drawable spheres go into the BVH.
  m.spheres.reserve(set.size());
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  double r_max = 0;
  for (size_t i = 0; i < set.size(); ++i) {
    const glm::dvec3& c = set.centres[i];
    const double r = i < set.radii.size() ? set.radii[i] : std::nan("");
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) || !std::isfinite(r) || !(r > 0)) {
      ++invalid_;
      continue;
    }
    m.spheres.push_back({c, r, uint32_t(i)});
    lo = glm::min(lo, c - r);
    hi = glm::max(hi, c + r);
    r_max = std::max(r_max, r);
  }
  if (m.spheres.empty()) return;  // nothing is ever hit; no Embree needed
  m.centre = 0.5 * (lo + hi);
  double R = 0;
  for (const ExactSphere& s : m.spheres) R = std::max(R, glm::length(s.c - m.centre) + s.r);
  if (!(R < 1e30)) throw std::runtime_error("sphere reference: sphere coordinates out of float range");

  // Radius margin. Embree intersects in float, in coordinates relative to
  // `centre` (|x| <= R + slack) along a float ray that starts near the
  // scene, so every hit parameter is O(R). Rounding the centre, the radius,
  // the ray's origin and direction to float and Embree's own arithmetic
  // (c − o, its projection on the direction, the perpendicular offset, each
  // a few roundings) move the float perpendicular distance by at most a few
  // tens of float ulps of R (ulp = 2^-23·R ≈ 1.2e-7·R). A margin of 1e-5·R
  // (≈ 80 ulps) plus a tiny absolute term therefore makes every exact sphere
  // lie inside its float stand-in with room to spare: no exact hit is lost,
  // and the float entry lies before the exact entry. The cost is a few more
  // candidates that the exact test rejects.
  margin_ = 1e-5 * R + 1e-30;
  // How much earlier than the exact entry (or later than the exact exit) an
  // enlarged sphere's float hit may be: at grazing incidence the enlarged
  // half-chord exceeds the exact one by up to sqrt(2·r·m + m²); plus m.
  m.slack = std::sqrt(2 * r_max * margin_ + margin_ * margin_) + 2 * margin_;
  m.bound_r = R + 2 * margin_;

  const std::string config = threads > 0 ? "threads=" + std::to_string(threads) : std::string();
  m.device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (!m.device) throw std::runtime_error("sphere reference: cannot create the Embree device");
  m.scene = rtcNewScene(m.device);
  RTCGeometry geom = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  m.check("rtcNewGeometry");
  float* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                         4 * sizeof(float), m.spheres.size()));
  m.check("rtcSetNewGeometryBuffer");
  for (size_t k = 0; k < m.spheres.size(); ++k) {
    const glm::dvec3 c = m.spheres[k].c - m.centre;
    v[4 * k + 0] = float(c.x);
    v[4 * k + 1] = float(c.y);
    v[4 * k + 2] = float(c.z);
    // Rounded up, so the float radius is never below r + margin.
    v[4 * k + 3] = std::nextafter(float(m.spheres[k].r + margin_), std::numeric_limits<float>::infinity());
  }
  rtcSetGeometryIntersectFilterFunction(geom, filter);
  rtcSetGeometryOccludedFilterFunction(geom, filter);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(m.scene, geom);
  rtcReleaseGeometry(geom);
  m.check("building the geometry");
  if (threads > 0) {
    tbb::task_arena arena(threads);
    arena.execute([&] { rtcCommitScene(m.scene); });
  } else {
    rtcCommitScene(m.scene);
  }
  m.check("rtcCommitScene");
}

SphereReference::~SphereReference() = default;

bool SphereReference::nearest(double X, double Y, double* depth, uint32_t* id, glm::dvec3* normal_view) const {
  const Impl& m = *impl_;
  glm::dvec3 o, u;
  m.view.ray(X, Y, &o, &u);
  Ctx ctx;
  alignas(16) RTCRayHit rh;
  double shift;
  if (!m.begin(&ctx, o, u, Query::Nearest, &rh, &shift)) return false;
  rtcIntersect1(m.scene, &ctx.rc, &rh);
  if (ctx.best_prim == RTC_INVALID_GEOMETRY_ID) return false;
  // Embree's float order may disagree with the exact one: a sphere whose
  // exact hit is nearer than the best so far can have its float hit beyond
  // Embree's nearest float hit (it was culled). Its float hit cannot lie
  // beyond the best exact hit plus the slack, so one more query over that
  // band, rejecting every hit, sees all such spheres. Hits with float
  // parameter below Embree's nearest were all offered to the filter already.
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
    const float t_float = rh.ray.tfar;
    const double upper = ctx.best_t - shift + m.slack + margin_;
    // One float step below, in case Embree culled equal float parameters.
    rh.ray.tnear = t_float > 0 ? std::nextafter(t_float, 0.f) : 0.f;
    rh.ray.tfar = std::nextafter(float(upper), std::numeric_limits<float>::infinity());
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    if (rh.ray.tfar >= rh.ray.tnear) {
      ctx.query = Query::Band;
      rtcIntersect1(m.scene, &ctx.rc, &rh);
    }
  }
  const ExactSphere& s = m.spheres[ctx.best_prim];
  const double t = ctx.best_t;
  // View depth = dot(o + t·u − eye, f) = t·dot(u, f): the ray origin is the
  // eye (perspective) or on the eye plane (orthographic, o − eye ⟂ f, and
  // u = f exactly), so the origin's own depth is 0.
  *depth = m.view.perspective() ? t * glm::dot(ctx.u, m.view.forward()) : t;
  *id = s.id;
  if (normal_view) {
    glm::dvec3 n = (ctx.o + t * ctx.u - s.c) / s.r;
    if (glm::dot(n, ctx.u) > 0) n = -n;  // the inside surface (exit) faces the viewer reversed
    *normal_view = {glm::dot(n, m.view.right()), glm::dot(n, m.view.up()), -glm::dot(n, m.view.forward())};
  }
  return true;
}

void SphereReference::crossings(double X, double Y, std::vector<SphereCrossing>* out) const {
  glm::dvec3 o, u;
  impl_->view.ray(X, Y, &o, &u);
  ray_crossings(o, u, out);
  const double k = impl_->view.perspective() ? glm::dot(u, impl_->view.forward()) : 1.0;
  for (SphereCrossing& c : *out) c.depth *= k;
}

void SphereReference::ray_crossings(const glm::dvec3& o, const glm::dvec3& u, std::vector<SphereCrossing>* out) const {
  out->clear();
  const Impl& m = *impl_;
  Ctx ctx;
  alignas(16) RTCRayHit rh;
  double shift;
  if (!m.begin(&ctx, o, u, Query::Crossings, &rh, &shift)) return;
  ctx.out = out;
  rtcIntersect1(m.scene, &ctx.rc, &rh);
  auto key = [](const SphereCrossing& a) { return std::tuple(a.depth, a.id, !a.entering); };
  std::sort(out->begin(), out->end(), [&](const SphereCrossing& a, const SphereCrossing& b) { return key(a) < key(b); });
  out->erase(std::unique(out->begin(), out->end(),
                         [&](const SphereCrossing& a, const SphereCrossing& b) { return key(a) == key(b); }),
             out->end());
}

bool SphereReference::ray_blocked(const glm::dvec3& o, const glm::dvec3& u, uint32_t skip) const {
  const Impl& m = *impl_;
  Ctx ctx;
  alignas(16) RTCRayHit rh;
  double shift;
  if (!m.begin(&ctx, o, u, Query::Blocked, &rh, &shift)) return false;
  ctx.skip_id = skip;
  rtcOccluded1(m.scene, &ctx.rc, &rh.ray);
  return ctx.blocked;
}

namespace {

// The shared frame of both reference images: checks, the BVH, then
// pixel(ref, i, j, px, &depth) -> hit at every pixel on `threads` threads.
template <class Pixel>
SphereReferenceImage trace_image(const SphereSet& spheres, const std::vector<glm::vec4>& colors, const View& view,
                                 int threads, Pixel&& pixel) {
  if (colors.size() != spheres.size())
    throw std::runtime_error("sphere reference: " + std::to_string(colors.size()) + " colours for " +
                             std::to_string(spheres.size()) + " spheres");
  SphereReferenceImage res;
  const uint32_t W = view.width(), H = view.height();
  res.rgba = Image(W, H);
  res.z.assign(size_t(W) * H, std::numeric_limits<float>::infinity());
  auto t0 = std::chrono::steady_clock::now();
  const SphereReference ref(spheres, view, threads);
  res.ms_build = ms_since(t0);
  res.invalid = ref.invalid();
  std::atomic<uint64_t> hits{0};
  auto rows = [&](const tbb::blocked_range<uint32_t>& r) {
    uint64_t h = 0;
    for (uint32_t j = r.begin(); j != r.end(); ++j)
      for (uint32_t i = 0; i < W; ++i) {
        double depth = std::numeric_limits<double>::infinity();
        if (!pixel(ref, i, j, res.rgba.at(i, j), &depth)) continue;
        res.z[size_t(j) * W + i] = float(depth);
        ++h;
      }
    hits += h;
  };
  t0 = std::chrono::steady_clock::now();
  if (threads == 1) {
    rows(tbb::blocked_range<uint32_t>(0, H));
  } else {
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<uint32_t>(0, H, 1), rows); });
  }
  res.ms_trace = ms_since(t0);
  res.hits = hits;
  return res;
}

}  // namespace

SphereReferenceImage render_sphere_reference(const SphereSet& spheres, const std::vector<glm::vec4>& colors,
                                             const Shading& shading, const View& view, const double background[4],
                                             int threads) {
  // v = −u in view space: the ray's direction (r, u, −f components) negated.
  auto to_eye = [&](double X, double Y) {
    glm::dvec3 o, u;
    view.ray(X, Y, &o, &u);
    return glm::dvec3(-glm::dot(u, view.right()), -glm::dot(u, view.up()), glm::dot(u, view.forward()));
  };
  return trace_image(spheres, colors, view, threads,
                     [&](const SphereReference& ref, uint32_t i, uint32_t j, float* px, double* depth) {
                       uint32_t id;
                       glm::dvec3 n;
                       if (!ref.nearest(i, j, depth, &id, &n)) {
                         for (int k = 0; k < 4; ++k) px[k] = float(background[k]);
                         return false;
                       }
                       const glm::vec4& c = colors[id];
                       const glm::dvec3 rgb = shade(shading, glm::dvec3(c.r, c.g, c.b), n, to_eye(i, j));
                       px[0] = float(rgb.r), px[1] = float(rgb.g), px[2] = float(rgb.b), px[3] = 1.f;
                       return true;
                     });
}

namespace {

// AO at P (world) with unit outward normal N on sphere `id`, by exact rays:
// over spec.dirs with the renderer's weights (samples 0), else a
// cosine-weighted Monte Carlo estimate (Malley) from a fixed stream `seed`.
double traced_ao(const SphereReference& ref, const std::vector<glm::vec4>& colors, const SphereAoSpec& spec,
                 const glm::dvec3& P, const glm::dvec3& N, uint32_t id, uint64_t seed) {
  thread_local std::vector<SphereCrossing> xs;
  // V(P, w): no other sphere crosses the ray from P towards w (P's own
  // sphere is left behind: it is convex and N·w > 0). Alpha occluders:
  // Π(1 − α) over the spheres it crosses, each once (entered ahead of P, or
  // left ahead of P when P is inside it).
  auto open = [&](const glm::dvec3& w) {
    if (!spec.alpha_occluders) return ref.ray_blocked(P, w, id) ? 0.0 : 1.0;  // any hit ends the ray
    ref.ray_crossings(P, w, &xs);
    double pass = 1;
    for (size_t q = 0; q < xs.size(); ++q) {
      const SphereCrossing& x = xs[q];
      if (x.id == id || !(x.depth > 0)) continue;
      bool seen = false;
      for (size_t e = 0; e < q && !seen; ++e) seen = xs[e].id == x.id && xs[e].depth > 0;
      if (seen) continue;
      const float a = colors[x.id].a;
      pass *= a >= 1.f ? 0.0 : a > 0.f ? 1.0 - double(a) : 1.0;
    }
    return pass;
  };
  if (spec.samples == 0) {  // the renderer's directions, traced exactly
    double num = 0, den = 0;
    for (const glm::dvec3& w : spec.dirs) {
      const double c = glm::dot(N, w);
      if (!(c > 0)) continue;
      den += c;
      num += c * open(w);
    }
    return den > 0 ? num / den : 1.0;
  }
  uint64_t st = seed * 0x9E3779B97F4A7C15ull + 1;
  auto next = [&] {
    st ^= st << 13, st ^= st >> 7, st ^= st << 17;
    return double(st >> 11) * 0x1p-53;
  };
  const glm::dvec3 t = glm::normalize(glm::cross(N, std::abs(N.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  const glm::dvec3 b = glm::cross(N, t);
  double hits = 0;
  for (uint32_t q = 0; q < spec.samples; ++q) {
    const double r = std::sqrt(next()), phi = 2 * M_PI * next();
    const double x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.0, 1 - r * r));
    hits += open(glm::normalize(x * t + y * b + z * N));
  }
  return hits / spec.samples;
}

}  // namespace

SphereReferenceImage render_sphere_reference_translucent(const SphereSet& spheres,
                                                         const std::vector<glm::vec4>& colors, const Shading& shading,
                                                         const View& view, const double background[4], int threads,
                                                         bool front_only, const SphereAoSpec* ao,
                                                         std::vector<float>* ao_out) {
  const glm::dvec3 F = view.forward();
  const uint32_t W = view.width();
  if (ao) ao_out->assign(size_t(W) * view.height(), std::numeric_limits<float>::infinity());
  return trace_image(spheres, colors, view, threads,
                     [&](const SphereReference& ref, uint32_t i, uint32_t j, float* px, double* depth) {
                       thread_local std::vector<SphereCrossing> xs;
                       thread_local std::vector<uint32_t> seen;
                       ref.crossings(i, j, &xs);
                       glm::dvec3 o, u;
                       view.ray(i, j, &o, &u);
                       const double k = view.perspective() ? glm::dot(u, F) : 1.0;  // view depth per unit of ray
                       const glm::dvec3 v(-glm::dot(u, view.right()), -glm::dot(u, view.up()), glm::dot(u, F));
                       double acc[4] = {0, 0, 0, 0};
                       seen.clear();
                       for (const SphereCrossing& x : xs) {
                         const glm::vec4& col = colors[x.id];
                         const double a = col.a >= 1.f ? 1.0 : col.a > 0.f ? double(col.a) : 0.0;
                         if (a == 0) continue;
                         const bool opaque = a == 1;
                         if (front_only || opaque) {  // only the sphere's first (visible) crossing
                           if (std::find(seen.begin(), seen.end(), x.id) != seen.end()) continue;
                           seen.push_back(x.id);
                         }
                         glm::dvec3 n = (o + (x.depth / k) * u - spheres.centres[x.id]) / spheres.radii[x.id];
                         if (glm::dot(n, u) > 0) n = -n;  // facing the viewer
                         const glm::dvec3 nv = glm::normalize(
                             glm::dvec3(glm::dot(n, view.right()), glm::dot(n, view.up()), -glm::dot(n, F)));
                         glm::dvec3 rgb = shade(shading, glm::dvec3(col.r, col.g, col.b), nv, v);
                         if (ao) {  // at the crossing, with the sphere's outward normal
                           const glm::dvec3 P = o + (x.depth / k) * u;
                           const glm::dvec3 out = glm::normalize(P - spheres.centres[x.id]);
                           const double a_o = traced_ao(ref, colors, *ao, P, out, x.id,
                                                        (uint64_t(j) * W + i) * 1024 + (&x - xs.data()));
                           rgb *= a_o;
                           if (*depth == std::numeric_limits<double>::infinity())
                             (*ao_out)[size_t(j) * W + i] = float(a_o);  // the nearest crossing's, as the Z
                         }
                         const double c[4] = {rgb.r * a, rgb.g * a, rgb.b * a, a};
                         const double m = 1.0 - acc[3];
                         for (int q = 0; q < 4; ++q) acc[q] += c[q] * m;
                         if (*depth == std::numeric_limits<double>::infinity()) *depth = x.depth;
                         if (opaque) break;
                       }
                       const double m = 1.0 - acc[3];
                       for (int q = 0; q < 4; ++q) px[q] = float(acc[q] + background[q] * m);
                       return *depth < std::numeric_limits<double>::infinity();
                     });
}

}  // namespace zs

namespace zs {


SphereReferenceImage render_sphere_reference_ao(const SphereSet& spheres, const std::vector<glm::vec4>& colors,
                                                const Shading& shading, const View& view, const double background[4],
                                                int threads, const SphereAoSpec& spec, std::vector<float>* ao_out) {
  const uint32_t W = view.width();
  ao_out->assign(size_t(W) * view.height(), std::numeric_limits<float>::infinity());
  auto to_eye = [&](const glm::dvec3& u) {
    return glm::dvec3(-glm::dot(u, view.right()), -glm::dot(u, view.up()), glm::dot(u, view.forward()));
  };
  return trace_image(spheres, colors, view, threads,
                     [&](const SphereReference& ref, uint32_t i, uint32_t j, float* px, double* depth) {
                       uint32_t id;
                       glm::dvec3 n;
                       if (!ref.nearest(i, j, depth, &id, &n)) {
                         for (int k = 0; k < 4; ++k) px[k] = float(background[k]);
                         return false;
                       }
                       glm::dvec3 o, u;
                       view.ray(i, j, &o, &u);
                       const double k = view.perspective() ? glm::dot(u, view.forward()) : 1.0;
                       const glm::dvec3 P = o + (*depth / k) * u;
                       const glm::dvec3 N =
                           glm::normalize(n.x * view.right() + n.y * view.up() - n.z * view.forward());
                       const double ao = traced_ao(ref, colors, spec, P, N, id, uint64_t(j) * W + i);
                       const glm::vec4& c = colors[id];
                       const glm::dvec3 rgb = ao * shade(shading, glm::dvec3(c.r, c.g, c.b), n, to_eye(u));
                       px[0] = float(rgb.r), px[1] = float(rgb.g), px[2] = float(rgb.b), px[3] = 1.f;
                       (*ao_out)[size_t(j) * W + i] = float(ao);
                       return true;
                     });
}

}  // namespace zs
