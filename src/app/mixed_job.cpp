// Volume scenes with opaque geometry inside (docs/scene.md, "Volumes with
// geometry"): the scene's spheres or surfaces are drawn first, a batch of
// tiles at a time, with their own renderer (shading, shadow maps, AO as
// always) into a capture; the volume is then swept over the same tiles with
// the geometry's depth cutting every ray and its colour in place of the
// background (render/volume/opaque_layer.h).
#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "app/scene_jobs.h"
#include "raster/tile_capture.h"
#include "render/volume/zsweep_renderer.h"

namespace zs {

namespace {

class MixedRenderer : public TiledRenderer {
 public:
  MixedRenderer(std::unique_ptr<TiledRenderer> volume, std::unique_ptr<TiledRenderer> geometry)
      : volume_(std::move(volume)), geometry_(std::move(geometry)) {}
  const TileGrid& grid() const override { return volume_->grid(); }
  int threads() const override { return volume_->threads(); }
  void render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles) override {
    std::vector<uint32_t> all;
    if (!tiles) {
      for (uint32_t t = 0; t < grid().count(); ++t) all.push_back(t);
      tiles = &all;
    }
    // A batch at a time, so the capture holds a few tiles per thread, not the image.
    const size_t batch = size_t(std::max(1, threads())) * 8;
    TileCapture capture(geometry_->grid());
    const CapturedOpaqueLayer layer(capture);
    auto& volume = static_cast<ZSweepRenderer&>(*volume_);
    for (size_t k = 0; k < tiles->size(); k += batch) {
      const std::vector<uint32_t> part(tiles->begin() + long(k),
                                       tiles->begin() + long(std::min(tiles->size(), k + batch)));
      geometry_->render_tiles(capture, &part);
      volume.set_opaque_layer(&layer);
      volume.render_tiles(sink, &part);
      volume.set_opaque_layer(nullptr);
      capture.clear();
    }
  }
  // The two renderers' totals, one after the other (MPI sums each).
  std::vector<uint8_t> tile_totals() const override {
    std::vector<uint8_t> v = volume_->tile_totals(), g = geometry_->tile_totals();
    const uint64_t n = v.size();
    std::vector<uint8_t> out(8);
    std::memcpy(out.data(), &n, 8);
    out.insert(out.end(), v.begin(), v.end());
    out.insert(out.end(), g.begin(), g.end());
    return out;
  }
  void add_tile_totals(const std::vector<uint8_t>& other) override {
    uint64_t n = 0;
    if (other.size() < 8) throw std::runtime_error("mixed tile totals of the wrong size");
    std::memcpy(&n, other.data(), 8);
    if (other.size() - 8 < n) throw std::runtime_error("mixed tile totals of the wrong size");
    volume_->add_tile_totals(std::vector<uint8_t>(other.begin() + 8, other.begin() + 8 + long(n)));
    geometry_->add_tile_totals(std::vector<uint8_t>(other.begin() + 8 + long(n), other.end()));
  }
  const TiledRenderer& volume() const { return *volume_; }
  const TiledRenderer& geometry() const { return *geometry_; }

 private:
  std::unique_ptr<TiledRenderer> volume_, geometry_;
};

class MixedJob : public SceneJob {
 public:
  MixedJob(SceneInput& in, bool no_culling)
      : in_(in),
        geometry_(in.scene.with_spheres ? make_sphere_job(in, no_culling) : make_surface_job(in)),
        volume_(make_volume_job(in)) {
    grid_ = volume_->grid();
    const TileGrid& g = geometry_->grid();
    if (g.width != grid_.width || g.height != grid_.height || g.size != grid_.size || g.channels < 5)
      throw std::logic_error("the geometry's tiles differ from the volume's");
  }
  void check_budget(uint64_t extra_bytes) const override { volume_->check_budget(extra_bytes); }
  std::unique_ptr<TiledRenderer> renderer(uint64_t extra_bytes, bool progress) override {
    // The geometry's capture: a batch of tiles per thread (mixed_job.cpp).
    const uint64_t capture = uint64_t(std::max(1, in_.scene.settings.threads)) * 8 *
                             geometry_->grid().max_tile_pixels() * geometry_->grid().channels * 4;
    auto g = geometry_->renderer(extra_bytes + capture, progress);
    auto v = volume_->renderer(extra_bytes + capture, progress);
    return std::make_unique<MixedRenderer>(std::move(v), std::move(g));
  }
  double total_ms(const TiledRenderer& r) const override {
    return volume_->total_ms(of(r).volume()) + geometry_->total_ms(of(r).geometry());
  }
  nlohmann::json stats(const TiledRenderer& r, const FrameReport& f) const override {
    FrameReport vf = f;
    if (f.best_ms >= 0) vf.best_ms = -1;  // the total is set below, over both renderers
    nlohmann::json j = volume_->stats(of(r).volume(), vf);
    j["geometry"] = geometry_->stats(of(r).geometry(), FrameReport{});
    j["geometry"]["renderer"] = in_.scene.with_spheres ? "spheres" : "surfaces";
    if (in_.scene.clip_geometry)
      j["geometry"]["clip"] = {{"triangles_dropped", in_.surface_clip.dropped}, {"triangles_cut", in_.surface_clip.cut}};
    j["time_ms"]["total"] = f.best_ms >= 0 ? f.best_ms : total_ms(r);
    return j;
  }
  std::string summary(const TiledRenderer& r, double total_ms) const override {
    return volume_->summary(of(r).volume(), total_ms) + "; under it " + geometry_->summary(of(r).geometry(),
                                                                                         geometry_->total_ms(of(r).geometry()));
  }
  std::string empty_reason(const TiledRenderer& r) const override {
    const std::string v = volume_->empty_reason(of(r).volume()), g = geometry_->empty_reason(of(r).geometry());
    return !v.empty() && !g.empty() ? v + ", and " + g : "";
  }
  bool set_camera(const Camera& camera) override {
    in_.scene.settings.camera = camera;  // the geometry's settings are made from the scene's per renderer
    return volume_->set_camera(camera) && geometry_->set_camera(camera);
  }

 private:
  static const MixedRenderer& of(const TiledRenderer& r) { return static_cast<const MixedRenderer&>(r); }
  SceneInput& in_;
  std::unique_ptr<SceneJob> geometry_, volume_;
};

}  // namespace

std::unique_ptr<SceneJob> make_mixed_job(SceneInput& in, bool no_culling) {
  return std::make_unique<MixedJob>(in, no_culling);
}

}  // namespace zs
