// Volume scenes with opaque geometry inside (docs/scene.md, "Volumes with
// geometry"): the scene's spheres and/or surfaces are drawn first, a batch of
// tiles at a time, each with its own renderer (shading, shadow maps, AO as
// always) into a capture; with both, each pixel keeps the nearer of the two.
// The volume is then swept over the same tiles with the geometry's depth
// cutting every ray and its colour in place of the background
// (render/volume/opaque_layer.h).
#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "app/scene_jobs.h"
#include "raster/tile_capture.h"
#include "render/volume/zsweep_renderer.h"

namespace zs {

namespace {

// Byte blocks, each behind its uint64 length: the renderers' totals for MPI.
void put_block(std::vector<uint8_t>& out, const std::vector<uint8_t>& b) {
  const uint64_t n = b.size();
  const size_t at = out.size();
  out.resize(at + 8);
  std::memcpy(out.data() + at, &n, 8);
  out.insert(out.end(), b.begin(), b.end());
}
std::vector<uint8_t> take_block(const std::vector<uint8_t>& in, size_t* at) {
  uint64_t n = 0;
  if (in.size() - *at < 8) throw std::runtime_error("mixed tile totals of the wrong size");
  std::memcpy(&n, in.data() + *at, 8);
  *at += 8;
  if (in.size() - *at < n) throw std::runtime_error("mixed tile totals of the wrong size");
  std::vector<uint8_t> b(in.begin() + long(*at), in.begin() + long(*at + n));
  *at += n;
  return b;
}

class MixedRenderer : public TiledRenderer {
 public:
  MixedRenderer(std::unique_ptr<TiledRenderer> volume, std::vector<std::unique_ptr<TiledRenderer>> geometry)
      : volume_(std::move(volume)), geometry_(std::move(geometry)) {}
  const TileGrid& grid() const override { return volume_->grid(); }
  int threads() const override { return volume_->threads(); }
  void render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles) override {
    std::vector<uint32_t> all;
    if (!tiles) {
      for (uint32_t t = 0; t < grid().count(); ++t) all.push_back(t);
      tiles = &all;
    }
    // A batch at a time, so the captures hold a few tiles per thread, not the image.
    const size_t batch = size_t(std::max(1, threads())) * 8;
    std::vector<TileCapture> captures;
    for (const auto& g : geometry_) captures.emplace_back(g->grid());
    TileGrid g5 = grid();
    g5.channels = 5;
    TileCapture nearest(g5);  // two geometries: the nearer of the two per pixel
    const bool merge = captures.size() > 1;
    const CapturedOpaqueLayer layer(merge ? nearest : captures[0]);
    auto& volume = static_cast<ZSweepRenderer&>(*volume_);
    for (size_t k = 0; k < tiles->size(); k += batch) {
      const std::vector<uint32_t> part(tiles->begin() + long(k),
                                       tiles->begin() + long(std::min(tiles->size(), k + batch)));
      for (size_t i = 0; i < geometry_.size(); ++i) geometry_[i]->render_tiles(captures[i], &part);
      if (merge) keep_nearest(part, captures, nearest);
      volume.set_opaque_layer(&layer);
      volume.render_tiles(sink, &part);
      volume.set_opaque_layer(nullptr);
      for (TileCapture& c : captures) c.clear();
      nearest.clear();
    }
  }
  // The renderers' totals, one block each (MPI sums each).
  std::vector<uint8_t> tile_totals() const override {
    std::vector<uint8_t> out;
    put_block(out, volume_->tile_totals());
    for (const auto& g : geometry_) put_block(out, g->tile_totals());
    return out;
  }
  void add_tile_totals(const std::vector<uint8_t>& other) override {
    size_t at = 0;
    volume_->add_tile_totals(take_block(other, &at));
    for (const auto& g : geometry_) g->add_tile_totals(take_block(other, &at));
  }
  const TiledRenderer& volume() const { return *volume_; }
  const TiledRenderer& geometry(size_t i) const { return *geometry_[i]; }

 private:
  // Per pixel of each tile, RGBA and Z of whichever geometry is nearer (the
  // first on a tie): what a z-buffer over both would keep.
  static void keep_nearest(const std::vector<uint32_t>& tiles, const std::vector<TileCapture>& in, TileCapture& out) {
    std::vector<float> px;
    for (uint32_t t : tiles) {
      const TileRect r = out.grid().rect(t);
      const size_t n = size_t(r.width()) * r.height();
      px.assign(n * 5, 0.f);
      for (size_t p = 0; p < n; ++p) {
        const float* best = nullptr;
        for (const TileCapture& c : in) {
          const float* q = c.pixels(t) + p * c.grid().channels;
          if (!best || q[4] < best[4]) best = q;
        }
        std::copy(best, best + 5, px.data() + p * 5);
      }
      out.tile(r, px.data());
    }
  }

  std::unique_ptr<TiledRenderer> volume_;
  std::vector<std::unique_ptr<TiledRenderer>> geometry_;
};

class MixedJob : public SceneJob {
 public:
  MixedJob(SceneInput& in, bool no_culling) : in_(in) {
    if (in.scene.with_spheres) geometry_.push_back({"spheres", make_sphere_job(in, no_culling)});
    if (in.scene.with_surfaces) geometry_.push_back({"surfaces", make_surface_job(in)});
    volume_ = make_volume_job(in);
    grid_ = volume_->grid();
    for (const Part& p : geometry_) {
      const TileGrid& g = p.job->grid();
      if (g.width != grid_.width || g.height != grid_.height || g.size != grid_.size || g.channels < 5)
        throw std::logic_error("the geometry's tiles differ from the volume's");
    }
  }
  void check_budget(uint64_t extra_bytes) const override { volume_->check_budget(extra_bytes); }
  std::unique_ptr<TiledRenderer> renderer(uint64_t extra_bytes, bool progress) override {
    // The captures: a batch of tiles per thread each (and their merge).
    uint64_t capture = 0;
    for (const Part& p : geometry_) capture += p.job->grid().channels;
    if (geometry_.size() > 1) capture += 5;
    capture *= uint64_t(std::max(1, in_.scene.settings.threads)) * 8 * grid_.max_tile_pixels() * 4;
    std::vector<std::unique_ptr<TiledRenderer>> g;
    for (const Part& p : geometry_) g.push_back(p.job->renderer(extra_bytes + capture, progress));
    auto v = volume_->renderer(extra_bytes + capture, progress);
    return std::make_unique<MixedRenderer>(std::move(v), std::move(g));
  }
  double total_ms(const TiledRenderer& r) const override {
    double ms = volume_->total_ms(of(r).volume());
    for (size_t i = 0; i < geometry_.size(); ++i) ms += geometry_[i].job->total_ms(of(r).geometry(i));
    return ms;
  }
  nlohmann::json stats(const TiledRenderer& r, const FrameReport& f) const override {
    FrameReport vf = f;
    if (f.best_ms >= 0) vf.best_ms = -1;  // the total is set below, over every renderer
    nlohmann::json j = volume_->stats(of(r).volume(), vf);
    for (size_t i = 0; i < geometry_.size(); ++i) {
      nlohmann::json g = geometry_[i].job->stats(of(r).geometry(i), FrameReport{});
      g["renderer"] = geometry_[i].name;
      if (geometry_[i].name == std::string("surfaces") && in_.scene.clip_geometry)
        g["clip"] = {{"triangles_dropped", in_.surface_clip.dropped}, {"triangles_cut", in_.surface_clip.cut}};
      // One geometry: its stats; two: both, by name.
      if (geometry_.size() == 1) j["geometry"] = g;
      else j["geometry"][geometry_[i].name] = g;
    }
    if (geometry_.size() > 1) j["geometry"]["renderer"] = "spheres and surfaces";
    j["time_ms"]["total"] = f.best_ms >= 0 ? f.best_ms : total_ms(r);
    return j;
  }
  std::string summary(const TiledRenderer& r, double total_ms) const override {
    std::string s = volume_->summary(of(r).volume(), total_ms);
    for (size_t i = 0; i < geometry_.size(); ++i)
      s += (i ? "; and " : "; under it ") +
           geometry_[i].job->summary(of(r).geometry(i), geometry_[i].job->total_ms(of(r).geometry(i)));
    return s;
  }
  std::string empty_reason(const TiledRenderer& r) const override {
    std::string why = volume_->empty_reason(of(r).volume());
    for (size_t i = 0; i < geometry_.size() && !why.empty(); ++i) {
      const std::string g = geometry_[i].job->empty_reason(of(r).geometry(i));
      why = g.empty() ? "" : why + ", and " + g;
    }
    return why;
  }
  bool set_camera(const Camera& camera) override {
    in_.scene.settings.camera = camera;  // the geometry's settings are made from the scene's per renderer
    bool all = volume_->set_camera(camera);
    for (Part& p : geometry_) all = p.job->set_camera(camera) && all;
    return all;
  }

 private:
  struct Part {
    const char* name;
    std::unique_ptr<SceneJob> job;
  };
  static const MixedRenderer& of(const TiledRenderer& r) { return static_cast<const MixedRenderer&>(r); }
  SceneInput& in_;
  std::vector<Part> geometry_;
  std::unique_ptr<SceneJob> volume_;
};

}  // namespace

std::unique_ptr<SceneJob> make_mixed_job(SceneInput& in, bool no_culling) {
  return std::make_unique<MixedJob>(in, no_culling);
}

}  // namespace zs
