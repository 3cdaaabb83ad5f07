// libFuzzer target: the scene / transfer-function JSON parser (parse_scene),
// then a small render with the parsed camera, transfer function and render
// settings (image clamped to a few pixels): of the embedded default mesh for
// volume scenes, of a small fixed sphere set for sphere scenes.
// Rejections (std::runtime_error naming the input) are expected outcomes;
// anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_render.h"
#include "geometry/tets/default_mesh.h"
#include "scene/scene_defaults.h"
#include "geometry/spheres/sphere_colors.h"
#include "render/spheres/sphere_renderer.h"

namespace {

// Spheres overlapping, nested, one around the default camera's eye.
zs::SphereSet fuzz_spheres() {
  zs::SphereSet s;
  for (int i = 0; i < 27; ++i) {
    s.centres.push_back({(i % 3) * 0.6 - 0.6, (i / 3 % 3) * 0.6 - 0.6, (i / 9) * 0.6 - 0.6});
    s.radii.push_back(0.2 + 0.05 * (i % 4));
    s.scalars.push_back(i / 27.0);
  }
  s.centres.push_back({0, 0, 5});
  s.radii.push_back(1.0);
  s.scalars.push_back(0.5);
  return s;
}

void render_spheres(const zs::Scene& scene) {
  using namespace zs;
  static const SphereSet set = fuzz_spheres();
  SphereRenderSettings rs = sphere_render_settings(scene.settings, scene.spheres);
  rs.width = std::min(rs.width, fuzz::kMaxImage);
  rs.height = std::min(rs.height, fuzz::kMaxImage);
  rs.threads = 1;
  rs.progress = false;
  rs.tile_size = 8;
  // AO as parsed, its maps kept small (their cost is not what is fuzzed here).
  rs.ao.map_size = std::min(rs.ao.map_size, 64u);
  if (rs.ao.directions > 66) rs.ao.directions = 66;
  // rs.mode, surfaces, tolerance and max_layers as the scene says: every
  // translucent mode runs too (the transfer function gives mixed alphas).
  struct Discard : TileSink {
    void tile(const TileRect&, const float*) override {}
  } sink;
  try {
    // As the CLI does (scene_input): no transfer_function means the default
    // ramp over the set's scalars.
    const TransferFunction tf =
        scene.has_transfer_function ? scene.settings.tf : default_transfer_function(set.scalars, 1.0);
    const std::vector<glm::vec4> colors = sphere_colors(set, SphereColorMode::Scalar, tf);
    const SphereGrid g = build_sphere_grid(set, rs.grid);
    SphereRenderer r(set, colors, g, rs);
    r.render_tiles(sink, nullptr);
  } catch (const std::runtime_error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace zs;
  static const TetMesh mesh = default_mesh(2);  // a few dozen tets
  Scene scene;
  try {
    // Preset paths resolve against a directory that does not exist, so a
    // fuzzed scene cannot read the machine's files.
    scene = parse_scene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json",
                        "/nonexistent-zsweep-fuzz");
  } catch (const std::runtime_error&) {
    return 0;
  }
  if (scene.kind == SceneKind::Spheres) render_spheres(scene);
  else fuzz::render_small(mesh, scene.settings, !scene.has_camera, !scene.has_transfer_function);
  return 0;
}
