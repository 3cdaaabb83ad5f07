// One loaded scene (scene/scene_input.h) made ready to render: the renderer
// its kind needs (volume, spheres or surfaces), what it owns for them
// (topology, colours, grids, AO maps), its output channels and its --stats.
// `zsweep render` sends the frames into a file or across MPI ranks, the
// Python module into arrays; both through this interface only.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster/tile_grid.h"
#include "raster/tiled_renderer.h"
#include "scene/scene_input.h"

namespace zs {

// What the caller measured around a frame, for the stats.
struct FrameReport {
  std::vector<double> frame_ms;  // every frame's total (several with --frames)
  double best_ms = -1;           // >= 0: the total reported (the best of several frames)
  double mpi_wall_ms = -1;       // >= 0: the total is the setup plus this (MPI: every rank's tiles)
  uint64_t peak_rss = 0;         // > 0: the peak over MPI ranks
};

// The total a frame reports: the renderer's, the best frame's or MPI's.
inline double frame_total(double renderer_ms, double setup_ms, const FrameReport& f) {
  return f.mpi_wall_ms >= 0 ? setup_ms + f.mpi_wall_ms : f.best_ms >= 0 ? f.best_ms : renderer_ms;
}

class SceneJob {
 public:
  virtual ~SceneJob() = default;
  // The tiles and channels of every frame, and the channels' names for the
  // image writers (empty: R, G, B, A, then Z when there are five).
  const TileGrid& grid() const { return grid_; }
  const std::vector<std::string>& channel_names() const { return names_; }
  // Throws when the scene cannot fit the memory budget beside `extra_bytes`
  // of the caller's own (an output's buffers): called before output opens.
  virtual void check_budget(uint64_t extra_bytes) const {}
  // A renderer for one frame (its setup is part of the frame).
  virtual std::unique_ptr<TiledRenderer> renderer(uint64_t extra_bytes, bool progress) = 0;
  // A finished frame's total time, its --stats JSON and its one-line summary
  // ("WxH, ... ms"); `empty_reason` is "" unless nothing was drawn.
  virtual double total_ms(const TiledRenderer& r) const = 0;
  virtual nlohmann::json stats(const TiledRenderer& r, const FrameReport& f) const = 0;
  virtual std::string summary(const TiledRenderer& r, double total_ms) const = 0;
  virtual std::string empty_reason(const TiledRenderer& r) const = 0;
  // The output keeps R, G, B and A only (an 8-bit file): a job may leave its
  // other channels out of the frames (surfaces: Z and lit, whose stores are a
  // good part of a frame); the others' writers drop them.
  virtual void keep_rgba_only() {}
  // Points the next frames' camera at `camera`, keeping what does not depend
  // on the view (a volume's topology); false when this job cannot, and the
  // caller makes a new job for the new camera instead.
  virtual bool set_camera(const Camera&) { return false; }
  // Whether render_frames makes the next frame's renderer before it frees
  // the previous one (more memory for a moment; the allocator then hands the
  // same pages back instead of faulting fresh ones in).
  virtual bool overlap_frames() const { return false; }

 protected:
  TileGrid grid_{};
  std::vector<std::string> names_;
};

// What a render left out of its input, for the summary line: each part a
// count and its noun, singular and plural ("tet with a non-finite
// coordinate or scalar"). Returns "; left out: 1 tet ..., 2 ..." or "" when
// every count is 0, so every renderer's summary says what it skipped.
struct LeftOut {
  uint64_t count;
  const char* one;
  const char* many;
};
std::string left_out_note(const std::vector<LeftOut>& parts);

// Throws std::runtime_error naming the file on bad input (sphere colours).
// `in` must outlive the job. `no_culling`: as `render --no-culling`.
std::unique_ptr<SceneJob> make_scene_job(SceneInput& in, bool no_culling);

// Renders `frames` whole frames (setup included) and sends the last one to
// `sink`, the ones before it to `warmup` (null: nowhere): the steady-state
// frames benchmarks time. Returns the last frame's renderer; `frame_ms` gets
// each frame's time.
std::unique_ptr<TiledRenderer> render_frames(SceneJob& job, int frames, TileSink& sink, uint64_t extra_bytes,
                                             bool progress, std::vector<double>* frame_ms, TileSink* warmup = nullptr);

}  // namespace zs
