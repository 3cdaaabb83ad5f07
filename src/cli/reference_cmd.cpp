// `zsweep reference SCENE.json|MESH -o OUT.exr [--stats S.json]`: the
// independent ray caster every error figure is measured against.
// Sphere scenes and files (.pdb/.sph/.sphb): the sphere renderers' Embree
// reference, on the scene's camera, colours and shading (RGBA and Z).
#include <algorithm>
#include <cstdio>
#include <memory>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/json_out.h"
#include "cli/render_file.h"
#include "app/reference_scene.h"
#include "app/option_checks.h"
#include "app/scene_args.h"
#include "output/image_io.h"
#include "output/tile_writer.h"
#include "base/util/atomic_file.h"

namespace zs {

namespace {

// Writes RGBA and, for EXR/TIFF, Z (and AO) through the tile writer, as
// `render` writes them.
void write_channels(const std::string& path, const ReferenceImage& ref) {
  const uint32_t C = uint32_t(ref.names.size());
  const TileGrid grid{ref.width, ref.height, 64, C};
  ImageTileWriter w(path, grid, "", C > 5 ? ref.names : std::vector<std::string>{});
  std::vector<float> buf;
  for (uint32_t t = 0; t < grid.count(); ++t) {
    const TileRect r = grid.rect(t);
    buf.resize(size_t(r.width()) * r.height() * C);
    for (uint32_t y = r.y0; y < r.y1; ++y)
      std::copy_n(&ref.pixels[(size_t(y) * ref.width + r.x0) * C], size_t(r.width()) * C,
                  &buf[size_t(y - r.y0) * r.width() * C]);
    w.tile(r, buf.data());
  }
  w.commit();
}

}  // namespace

void add_reference_command(CLI::App& app) {
  auto a = std::make_shared<SceneArgs>();
  auto out = std::make_shared<std::string>(), stats = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "reference", "Ground-truth image: an independent ray caster (tet walk, exact integration, no early termination; "
      "sphere scenes: Embree with exact hits; surface scenes: Embree shadow rays)");
  a->add_options(*cmd, false);
  cmd->add_option("-o,--output", *out, "Output image (.exr or .tif keep the float values)")->required();
  cmd->add_option("--stats", *stats, "Write ray-casting statistics as JSON");
  auto ao_samples = std::make_shared<uint32_t>(0);
  cmd->add_option("--ao-samples", *ao_samples,
                  "Sphere scenes with ao: 0 (default) traces the scene's directions exactly; N > 0 a cosine-weighted "
                  "Monte Carlo AO with N rays per pixel")
      ->check(number_check(whole_range(0, 1 << 20)));
  cmd->callback([a, out, stats, ao_samples] {
    SceneArgs args = *a;
    if (*ao_samples) args.also_given.push_back("--ao-samples");
    SceneInput in = args.load();
    if (*ao_samples && !in.scene.spheres.ao.directions)
      throw UsageError(args.input + ": --ao-samples needs a sphere scene with an 'ao' block");
    if (in.scene.kind == SceneKind::Surfaces) {
      // The surface renderer's ground truth is its exact mode: one Embree
      // shadow ray per visible pixel and light (docs/shadows.md).
      in.scene.surfaces.shadows.mode = ShadowMode::Exact;
      render_to_file(in, *out, *stats, 1, "", false);
      return;
    }
    AtomicFile(*out).check_writable();  // before minutes of ray casting
    if (!stats->empty()) AtomicFile(*stats).check_writable();
    const ReferenceImage ref = reference_image(in, *ao_samples);
    if (ref.names.size() == 4) {  // volumes: RGBA
      Image img(ref.width, ref.height);
      img.rgba = ref.pixels;
      write_image(*out, img);
    } else {
      write_channels(*out, ref);
    }
    if (!stats->empty()) write_json_file(*stats, ref.stats);
    std::printf("wrote %s: %s\n", out->c_str(), ref.summary.c_str());
  });
}

}  // namespace zs
