// `zsweep render SCENE.json -o OUT` or `zsweep render MESH -o OUT` (automatic
// camera and transfer function), or `zsweep render -o OUT` for the embedded
// default scene.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/option_checks.h"
#include "app/scene_job.h"
#include "cli/commands.h"
#include "cli/json_out.h"
#include "cli/render_file.h"
#include "cli/render_mpi.h"
#include "app/scene_args.h"
#include "output/tile_writer.h"
#include "geometry/tets/validate.h"
#include "base/util/atomic_file.h"

namespace zs {

namespace {

// Input that renders, but not as the user likely meant: one warning line
// each on stderr; the image is still written and the exit code is 0.
void warn_nonfinite(const SceneInput& in) {
  const size_t n = count_nonfinite_tets(in.mesh);
  if (n == 0) return;
  const std::string name = in.scene.mesh_path.empty() ? "default mesh" : in.scene.mesh_path;
  std::fprintf(stderr, "zsweep: warning: %s: %zu of %zu tets have a non-finite coordinate or scalar; they are left out\n",
               name.c_str(), n, in.mesh.num_tets());
}

// A scalar with one value everywhere maps every point to one colour and
// opacity: the image is a flat silhouette (the oxygen post's density).
void warn_constant_scalar(const SceneInput& in) {
  const TetMesh& m = in.mesh;
  if (m.scalar_values().empty()) return;
  double lo = INFINITY, hi = -INFINITY;
  for (double s : m.scalar_values())
    if (std::isfinite(s)) lo = std::min(lo, s), hi = std::max(hi, s);
  if (lo < hi || !(lo <= hi)) return;
  const std::string name = in.scene.mesh_path.empty() ? "default mesh" : in.scene.mesh_path;
  const std::string scalar = m.scalar_name.empty() ? "scalar" : m.scalar_name;
  std::fprintf(stderr,
               "zsweep: warning: %s: scalar '%s' is constant (%.9g)%s; every point gets the same colour and opacity\n",
               name.c_str(), scalar.c_str(), lo,
               in.scene.mesh_options.scalar.empty() ? ", as is every other array" : "");
}

}  // namespace

void render_to_file(SceneInput& in, const std::string& out_path, const std::string& stats_path, int frames,
                    const std::string& compression, bool no_culling) {
  if (!stats_path.empty()) AtomicFile(stats_path).check_writable();  // not after the render
  const bool volume = in.scene.kind == SceneKind::Volume;
  if (volume) {
    if (!render_mpi_enabled() || render_mpi_rank() == 0) {
      warn_nonfinite(in);
      warn_constant_scalar(in);
    }
    in.scene.settings.face_area_stats = !stats_path.empty();
  }
  std::unique_ptr<SceneJob> job = make_scene_job(in, no_culling);
  if (!ImageTileWriter::keeps_extra_channels(out_path)) job->keep_rgba_only();
  const TileGrid& grid = job->grid();
  // The budget before the output opens: the file library allocates its tile
  // tables then (2 GiB for a 1048576² EXR), and an image the format cannot
  // hold is refused here too.
  job->check_budget(ImageTileWriter::buffer_bytes_estimate(out_path, grid));
  FrameReport report;
  std::unique_ptr<TiledRenderer> r;
  std::unique_ptr<ImageTileWriter> writer;
  if (render_mpi_enabled()) {
    // `render --mpi` (src/cli/render_mpi.h): every rank renders a share of
    // the tiles into rank 0's writer; rank 0 alone writes and prints.
    if (render_mpi_rank() == 0) writer = std::make_unique<ImageTileWriter>(out_path, grid, compression, job->channel_names());
    r = job->renderer(
        (writer ? writer->buffer_bytes_estimate() : 0) + render_mpi_message_bytes(grid, in.scene.settings.threads), false);
    MpiReport mpi;
    render_mpi(*r, writer.get(), &mpi);
    if (!writer) return;
    writer->commit();
    report.mpi_wall_ms = mpi.wall_ms;
    for (uint64_t p : mpi.peak_rss) report.peak_rss = std::max(report.peak_rss, p);
  } else {
    // Tiles stream from the renderer into the file as they finish, so no
    // format needs the whole image in memory (EXR/TIFF tiled, PNG in row
    // bands) and stills larger than memory work. The writer opens first, so
    // an unwritable path fails before the render, and its buffers count
    // against the budget; nothing appears under out_path unless commit() succeeds.
    writer = std::make_unique<ImageTileWriter>(out_path, grid, compression, job->channel_names());
    r = render_frames(*job, frames, *writer, writer->buffer_bytes_estimate(), true, &report.frame_ms);
    writer->commit();
    if (frames > 1) report.best_ms = *std::min_element(report.frame_ms.begin(), report.frame_ms.end());
  }
  const nlohmann::json st = job->stats(*r, report);
  const std::string why = job->empty_reason(*r);
  if (!why.empty()) std::fprintf(stderr, "zsweep: warning: %s: the image is empty: %s\n", out_path.c_str(), why.c_str());
  if (!stats_path.empty()) write_json_file(stats_path, st);
  std::printf("wrote %s: %s\n", out_path.c_str(), job->summary(*r, st["time_ms"]["total"].get<double>()).c_str());
}

namespace {

void run(SceneArgs a, const std::string& out_path, const std::string& stats_path, int frames,
         const std::string& compression, bool no_culling) {
  if (no_culling) a.also_given.push_back("--no-culling");
  SceneInput in = a.load();
  render_to_file(in, out_path, stats_path, frames, compression, no_culling);
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto a = std::make_shared<SceneArgs>();
  auto out = std::make_shared<std::string>(), stats = std::make_shared<std::string>();
  auto frames = std::make_shared<int>(1);
  auto compression = std::make_shared<std::string>();
  auto no_culling = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("render", "Render a scene (.json), a mesh, or the embedded default scene");
  a->add_options(*cmd, true);
  cmd->add_option("-o,--output", *out, "Output image: .png (8-bit), .exr or .tif (float)")->required();
  cmd->add_option("--stats", *stats, "Write render statistics as JSON");
  cmd->add_option("--frames", *frames,
                  "Render N whole frames (setup included) in one process and write the last; --stats reports "
                  "the best frame's time (steady-state benchmarks)")
      ->check(number_check(whole_range(1, 100000)));
  cmd->add_option("--compression", *compression,
                  "EXR/TIFF compression. EXR lossless: rle (default: fast), zip (smaller files, ~4x slower to "
                  "write), zips, piz, none; EXR lossy: pxr24, b44, b44a, dwaa, dwab. TIFF (lossless): zip "
                  "(default), lzw, packbits, none");
  cmd->add_flag("--no-culling", *no_culling,
                 "Sphere scenes: draw every sphere, without the (lossless) visibility culling; surface scenes: no "
                 "back-face or view-volume culling");
  add_render_mpi_options(*cmd);  // --mpi, --mpi-schedule (src/cli/render_mpi.h)
  cmd->callback([a, out, stats, frames, compression, no_culling] { run(*a, *out, *stats, *frames, *compression, *no_culling); });
}

}  // namespace zs
