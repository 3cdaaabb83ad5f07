// What every sphere set a reader accepts must satisfy (sphere_set.h and the
// readers' contracts), and what rendering it must: a small image in both
// projections, with culling on and off, bit-identical (culling is lossless).
// A violation aborts, which libFuzzer reports.
#pragma once

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <glm/common.hpp>

#include "raster/image_sink.h"
#include "scene/scene_defaults.h"
#include "geometry/spheres/sphere_colors.h"
#include "geometry/spheres/sphere_set.h"
#include "render/spheres/sphere_renderer.h"

namespace zs::fuzz {

inline void check_spheres(const SphereSet& s) {
  if (s.size() == 0 || s.radii.size() != s.size()) std::abort();
  if (s.has_scalars() && s.scalars.size() != s.size()) std::abort();
  if (s.has_rgba() && s.rgba.size() != s.size()) std::abort();
  if (s.has_elements() && s.element.size() != s.size()) std::abort();
  for (size_t i = 0; i < s.size(); ++i) {
    const glm::dvec3& c = s.centres[i];
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) std::abort();
    if (!(s.radii[i] > 0.0) || !std::isfinite(s.radii[i])) std::abort();  // invalid ones are skipped
    if (s.has_rgba())
      for (int k = 0; k < 4; ++k)
        if (!(s.rgba[i][k] >= 0.f && s.rgba[i][k] <= 1.f)) std::abort();
  }
  if (s.degenerate > s.size()) std::abort();
  if (s.is_molecule()) {  // the molecule reader's per-atom fields and counts
    if (s.chain.size() != s.size() || s.residue_class.size() != s.size() || s.molecule.atoms != s.size()) std::abort();
    for (uint16_t c : s.chain)
      if (c >= s.chain_names.size()) std::abort();
    for (ResidueClass rc : s.residue_class)
      if (static_cast<int>(rc) >= kResidueClasses) std::abort();
    size_t counted = 0;
    for (const auto& e : s.molecule.elements) counted += e.second;
    if (counted != s.size() || s.molecule.chains != s.chain_names.size()) std::abort();
  }
}

// Sets larger than this are checked but not rendered (milliseconds per input).
constexpr size_t kMaxRenderSpheres = 2000;

inline void render_spheres_small(const SphereSet& s) {
  if (s.size() > kMaxRenderSpheres) return;
  Bounds b;
  for (size_t i = 0; i < s.size(); ++i) {
    const glm::dvec3 r(s.radii[i]);
    b.lo = b.empty ? s.centres[i] - r : glm::min(b.lo, s.centres[i] - r);
    b.hi = b.empty ? s.centres[i] + r : glm::max(b.hi, s.centres[i] + r);
    b.empty = false;
  }
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    SphereRenderSettings rs;
    rs.width = 16, rs.height = 12, rs.tile_size = 8, rs.grid = 3;
    try {
      rs.camera = frame_bounds(b, p, rs.width, rs.height);  // refuses extents it cannot frame
    } catch (const std::runtime_error&) {
      return;
    }
    const std::vector<glm::vec4> colors = sphere_colors(s, SphereColorMode::Element, TransferFunction());
    const SphereGrid g = build_sphere_grid(s, rs.grid);
    ImageSink on_sink(TileGrid{rs.width, rs.height, rs.tile_size, 5}), off_sink = on_sink;
    SphereRenderer on(s, colors, g, rs);
    on.render_tiles(on_sink, nullptr);
    rs.culling = false;
    SphereRenderer off(s, colors, g, rs);
    off.render_tiles(off_sink, nullptr);
    if (std::memcmp(on_sink.image.rgba.data(), off_sink.image.rgba.data(), on_sink.image.rgba.size() * 4) != 0 ||
        std::memcmp(on_sink.z.data(), off_sink.z.data(), on_sink.z.size() * 4) != 0)
      std::abort();  // culling changed a pixel
  }
}

}  // namespace zs::fuzz
