#include "lighting/shadow_rays.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <tbb/task_arena.h>

namespace zs {

struct ShadowRays::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  glm::dvec3 centre{0.0};
  double offset = 0;  // off the surface, world units
  double ms_build = 0;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
  void check(const char* what) const {
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("shadow rays: Embree failed in ") + what);
  }
};

ShadowRays::ShadowRays(const TriangleMesh& m, int threads) : impl_(std::make_unique<Impl>()) {
  const auto t0 = std::chrono::steady_clock::now();
  Impl& I = *impl_;
  const Bounds b = triangle_bounds(m);
  I.centre = b.centre();
  I.offset = 1e-6 * std::max(b.empty ? 1.0 : b.diagonal(), 1e-300);
  const std::string config = threads > 0 ? "threads=" + std::to_string(threads) : std::string();
  I.device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (!I.device) throw std::runtime_error("shadow rays: cannot create the Embree device");
  I.scene = rtcNewScene(I.device);
  RTCGeometry g = rtcNewGeometry(I.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  float* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.num_points()));
  unsigned* ix = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m.num_tris()));
  I.check("rtcSetNewGeometryBuffer");
  for (size_t i = 0; i < m.num_points(); ++i) {
    const glm::dvec3 p = m.points[i] - I.centre;
    v[3 * i] = float(p.x);
    v[3 * i + 1] = float(p.y);
    v[3 * i + 2] = float(p.z);
  }
  for (size_t t = 0; t < m.num_tris(); ++t)
    for (int k = 0; k < 3; ++k) ix[3 * t + k] = m.tris[t][k];
  rtcCommitGeometry(g);
  rtcAttachGeometry(I.scene, g);
  rtcReleaseGeometry(g);
  if (threads > 0) {
    tbb::task_arena arena(threads);
    arena.execute([&] { rtcCommitScene(I.scene); });
  } else {
    rtcCommitScene(I.scene);
  }
  I.check("rtcCommitScene");
  I.ms_build = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

ShadowRays::~ShadowRays() = default;

double ShadowRays::ms_build() const { return impl_->ms_build; }

bool ShadowRays::lit(const Light& l, const glm::dvec3& p, const glm::dvec3& n) const {
  const glm::dvec3 L = to_light(l, p);
  if (!in_light_cone(l, p) || !(glm::dot(n, L) > 0)) return false;
  const Impl& I = *impl_;
  const glm::dvec3 o = p + n * I.offset - I.centre;
  double tfar = std::numeric_limits<float>::infinity();
  if (l.type == LightType::Spot) tfar = glm::length(l.position - I.centre - o);
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay ray{};
  ray.org_x = float(o.x);
  ray.org_y = float(o.y);
  ray.org_z = float(o.z);
  ray.dir_x = float(L.x);
  ray.dir_y = float(L.y);
  ray.dir_z = float(L.z);
  ray.tnear = 0.f;
  ray.tfar = float(tfar);
  ray.mask = ~0u;
  ray.flags = 0;
  rtcOccluded1(I.scene, &ctx, &ray);
  return ray.tfar >= 0;  // Embree sets tfar to -inf when occluded
}

}  // namespace zs
