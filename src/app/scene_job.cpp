#include "app/scene_job.h"

#include "app/scene_jobs.h"
#include "raster/tile_sink.h"

namespace zs {

std::string left_out_note(const std::vector<LeftOut>& parts) {
  std::string s;
  for (const LeftOut& p : parts)
    if (p.count) s += (s.empty() ? "; left out: " : ", ") + std::to_string(p.count) + " " + (p.count == 1 ? p.one : p.many);
  return s;
}

std::unique_ptr<SceneJob> make_scene_job(SceneInput& in, bool no_culling) {
  if (in.scene.kind == SceneKind::Spheres) return make_sphere_job(in, no_culling);
  if (in.scene.kind == SceneKind::Surfaces) {
    if (no_culling) in.scene.surfaces.cull_back = in.scene.surfaces.cull_view = false;
    return make_surface_job(in);
  }
  if (in.scene.mixed()) {
    if (no_culling) in.scene.surfaces.cull_back = in.scene.surfaces.cull_view = false;
    return make_mixed_job(in, no_culling);
  }
  return make_volume_job(in);
}

std::unique_ptr<TiledRenderer> render_frames(SceneJob& job, int frames, TileSink& sink, uint64_t extra_bytes,
                                             bool progress, std::vector<double>* frame_ms, TileSink* warmup) {
  NullSink discard;
  std::unique_ptr<TiledRenderer> r;
  for (int f = 0; f < frames; ++f) {
    if (!job.overlap_frames()) r.reset();  // one frame's buffers at a time
    r = job.renderer(extra_bytes, progress);
    r->render_tiles(f + 1 < frames ? (warmup ? *warmup : static_cast<TileSink&>(discard)) : sink, nullptr);
    frame_ms->push_back(job.total_ms(*r));
  }
  return r;
}

}  // namespace zs
