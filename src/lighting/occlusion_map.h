// The conservative depth map of occlusion culling (spheres digest §2.2.3–2.2.4): each
// occluding sphere is drawn as the disc through its centre, perpendicular to
// the view axis, at its centre's depth. That disc lies inside the sphere, so
// along any ray through it the sphere's front surface is nearer than the
// disc: the map is never nearer than the exact depth map at any pixel, and
// whatever lies behind it everywhere is hidden. A plane parallel to the image
// projects to a circle in both projections, so the disc is exact there too.
//
// Depths are stored as floats rounded up (never nearer than the double they
// stand for), which halves the map's memory traffic and keeps it
// conservative.
//
// For large images the map is coarser than the image: one texel per s×s
// pixel block (s chosen so the map is at most 1024 texels a side), written
// only where a disc covers every pixel centre of the block. A one-level
// max-depth pyramid over it answers "is this screen box hidden behind z?"
// with at most 2×2 reads (the per-sphere test of the spheres digest §2.2.4).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace zs {

// A margin for depths compared across two computations of a surface (the
// disc's centre depth here, the exact hit in the renderer): hidden only when
// nearer by more than rounding could explain.
inline double occlusion_margin(double z) { return z + 1e-9 * (z < 0 ? -z : z) + 1e-300; }

class OcclusionMap {
 public:
  OcclusionMap(uint32_t width, uint32_t height, uint32_t max_side = 1024);

  // Disc of radius rho pixels centred at (X, Y) (pixel coordinates), depth
  // z > 0. With `shared`, threads may draw discs at once: a texel takes the
  // minimum by an atomic compare-and-swap (so the map does not depend on the
  // order); without, plain stores (a row's loop vectorizes).
  void write_disc(double X, double Y, double rho, double z, bool shared = false);
  // The same for n ≤ kBatch discs (rho ≤ 0: none); returns how many were
  // drawn. The small discs' texels are found in one vectorized loop.
  static constexpr size_t kBatch = 512;
  uint64_t write_discs(const double* X, const double* Y, const double* rho, const double* z, size_t n,
                       bool shared = false);
  // True when every texel over pixel-centre range [i0, i1] x [j0, j1] holds a
  // depth strictly nearer than z: anything whose surface lies at depth ≥ z
  // inside that box is hidden. Reads the map itself (used while it grows).
  bool hidden(int i0, int i1, int j0, int j1, double z) const;
  // True when the texel over pixel centre (i, j), inside the image, is
  // strictly nearer than z.
  bool hidden_at(int i, int j, double z) const {
    return occlusion_margin(level_[0][size_t(uint32_t(j) / s_) * tw_ + uint32_t(i) / s_]) < z;
  }
  // Builds the max pyramid; call once the map is complete.
  void build_pyramid();
  // The same question on the pyramid: one level, at most 2×2 elements.
  bool hidden_pyramid(int i0, int i1, int j0, int j1, double z) const;

  uint32_t block() const { return s_; }
  // Texels per side of the summary blocks (below).
  static constexpr uint32_t kSummary = 16;
  uint32_t texels_x() const { return tw_; }
  uint32_t texels_y() const { return th_; }
  double texel(uint32_t tx, uint32_t ty) const { return level_[0][size_t(ty) * tw_ + tx]; }
  // The float a depth is stored as: the nearest float not below z.
  static float round_up(double z);
  uint64_t bytes() const;

 private:
  // A disc of radius rho < kSmall pixels (most discs of a large set):
  // small_texel gives the one texel it can cover (the nearest pixel centre,
  // when inside the disc and texels are pixels) or -1, and write_texel
  // draws depth z there.
  static constexpr double kSmall = 0.5;
  static bool small_disc(double rho) { return rho * kShrink < kSmall; }
  // The column of the texel (its row in *ty), or -1.
  int32_t small_texel(double X, double Y, double rho, int32_t* ty) const {
    const double r = rho * kShrink;
    const double px = std::floor(X + 0.5), py = std::floor(Y + 0.5);
    // Bitwise &: no branches.
    const bool in = (s_ == 1) & (px >= 0) & (py >= 0) & (px < double(tw_)) & (py < double(th_)) &
                    ((px - X) * (px - X) + (py - Y) * (py - Y) <= r * r);
    *ty = in ? int32_t(py) : 0;
    return in ? int32_t(px) : -1;
  }
  void write_texel(uint32_t tx, uint32_t ty, double z, bool shared);
  // Discs are shrunk a little so a pixel centre on the rim (where the exact
  // surface meets the disc's depth) is never claimed.
  static constexpr double kShrink = 1 - 1e-6;
  uint32_t w_, h_, s_, tw_, th_;
  std::vector<std::vector<float>> level_;  // level_[0]: the map; then max levels
  std::vector<uint32_t> lw_, lh_;
  // While the map grows: the max over each kSummary² block of texels, kept
  // lazily (a block written since is recomputed when a test needs it), so
  // testing a large box reads blocks, not texels.
  uint32_t bw_, bh_;
  mutable std::vector<float> bmax_;
  mutable std::vector<uint8_t> bdirty_;
  float block_max(uint32_t bx, uint32_t by) const;
  void write_min(size_t texel, float z);  // atomic
  void mark(size_t block);                // atomic
};


}  // namespace zs
