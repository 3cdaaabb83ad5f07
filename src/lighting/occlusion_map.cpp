#include "lighting/occlusion_map.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cfloat>
#include <cmath>

namespace zs {

OcclusionMap::OcclusionMap(uint32_t width, uint32_t height, uint32_t max_side) : w_(width), h_(height) {
  const uint32_t side = std::max(width, height);
  s_ = std::max<uint32_t>(1, (side + max_side - 1) / max_side);
  tw_ = (width + s_ - 1) / s_;
  th_ = (height + s_ - 1) / s_;
  level_.emplace_back(size_t(tw_) * th_, INFINITY);
  lw_.push_back(tw_);
  lh_.push_back(th_);
  bw_ = (tw_ + kSummary - 1) / kSummary;
  bh_ = (th_ + kSummary - 1) / kSummary;
  bmax_.assign(size_t(bw_) * bh_, INFINITY);
  bdirty_.assign(size_t(bw_) * bh_, 0);
}

float OcclusionMap::round_up(double z) {
  float f = float(z);
  // The next float up; for z > 0 that is the next bit pattern.
  if (double(f) < z) f = z > 0 && f < FLT_MAX ? std::bit_cast<float>(std::bit_cast<uint32_t>(f) + 1) : std::nextafter(f, INFINITY);
  return f;
}

// Depths are > 0 (or +inf), so the minimum is a compare-and-swap that only
// ever lowers a texel; a plain load first keeps the common case (a texel
// already nearer) free of atomics' cost.
void OcclusionMap::write_min(size_t texel, float z) {
  std::atomic_ref<float> a(level_[0][texel]);
  float cur = a.load(std::memory_order_relaxed);
  while (z < cur && !a.compare_exchange_weak(cur, z, std::memory_order_relaxed)) {
  }
}

void OcclusionMap::mark(size_t block) {
  std::atomic_ref<uint8_t> d(bdirty_[block]);
  if (!d.load(std::memory_order_relaxed)) d.store(1, std::memory_order_relaxed);
}

float OcclusionMap::block_max(uint32_t bx, uint32_t by) const {
  const size_t b = size_t(by) * bw_ + bx;
  if (bdirty_[b]) {
    float v = -INFINITY;
    const uint32_t x1 = std::min(tw_, (bx + 1) * kSummary), y1 = std::min(th_, (by + 1) * kSummary);
    for (uint32_t y = by * kSummary; y < y1; ++y)
      for (uint32_t x = bx * kSummary; x < x1; ++x) v = std::max(v, level_[0][size_t(y) * tw_ + x]);
    bmax_[b] = v;
    bdirty_[b] = 0;
  }
  return bmax_[b];
}

uint64_t OcclusionMap::bytes() const {
  uint64_t b = 0;
  for (const auto& l : level_) b += l.size() * sizeof(float);
  return b;
}

void OcclusionMap::write_texel(uint32_t x, uint32_t y, double z, bool shared) {
  const size_t t = size_t(y) * tw_ + x, b = size_t(y / kSummary) * bw_ + size_t(x / kSummary);
  if (shared) {
    write_min(size_t(t), round_up(z));
    mark(b);
  } else {
    level_[0][size_t(t)] = std::min(level_[0][size_t(t)], round_up(z));
    bdirty_[b] = 1;
  }
}

void OcclusionMap::write_disc(double X, double Y, double rho, double z, bool shared) {
  const double r = rho * kShrink;
  if (!(r > 0) || !std::isfinite(X) || !std::isfinite(Y) || !(z > 0)) return;
  const double r2 = r * r;
  if (small_disc(rho)) {
    // At most the nearest pixel centre is inside, and only a one-pixel
    // texel can be covered (skipped when texels are larger: conservative).
    // floor(X + 0.5) differs from round(X) only at a half, where the centre
    // is 0.5 > r away anyway.
    int32_t ty;
    const int32_t tx = small_texel(X, Y, rho, &ty);
    if (tx >= 0) write_texel(uint32_t(tx), uint32_t(ty), z, shared);
    return;
  }
  const double ylo = std::floor((Y - r) / s_), yhi = std::ceil((Y + r) / s_);
  if (!(yhi >= 0 && ylo <= double(th_) - 1)) return;
  const int ty0 = std::max(0, int(std::max(ylo, -1.0)));
  const int ty1 = std::min(int(th_) - 1, int(std::min(yhi, 2e9)));
  const float zf = round_up(z);
  for (int ty = ty0; ty <= ty1; ++ty) {
    // The block's first and last pixel-centre rows; both must be inside.
    const double y0 = double(ty) * s_, y1 = double(std::min<uint32_t>((ty + 1) * s_, h_) - 1);
    const double dy = std::max(std::abs(y0 - Y), std::abs(y1 - Y));
    const double hw2 = r2 - dy * dy;
    if (!(hw2 >= 0)) continue;
    const double hw = std::sqrt(hw2), xl = X - hw, xr = X + hw;
    // Texels whose first pixel column is ≥ xl and whose last is ≤ xr (the
    // last texel of a row ends at the image's last column).
    const double lo = std::ceil(xl / s_);
    double hi = std::floor((xr + 1) / s_) - 1;
    if (double(w_) - 1 <= xr) hi = double(tw_) - 1;
    const int tx0 = int(std::max(lo, 0.0)), tx1 = int(std::min(hi, double(tw_) - 1));
    if (tx0 > tx1) continue;
    const size_t row = size_t(ty) * tw_, brow = size_t(ty / int(kSummary)) * bw_;
    if (shared) {
      for (int tx = tx0; tx <= tx1; ++tx) write_min(row + size_t(tx), zf);
      for (int bx = tx0 / int(kSummary); bx <= tx1 / int(kSummary); ++bx) mark(brow + bx);
    } else {
      float* m = level_[0].data() + row;
      for (int tx = tx0; tx <= tx1; ++tx) m[tx] = std::min(m[tx], zf);
      for (int bx = tx0 / int(kSummary); bx <= tx1 / int(kSummary); ++bx) bdirty_[brow + bx] = 1;
    }
  }
}

uint64_t OcclusionMap::write_discs(const double* X, const double* Y, const double* rho, const double* z, size_t n,
                                   bool shared) {
  // Per small disc, the pixel centre it covers ((-1, -1): none), as
  // small_texel, in a branch-free loop; the rest go through write_disc.
  double px[kBatch], py[kBatch];
  const double tw = tw_, th = th_, one = s_ == 1 ? 1.0 : 0.0;
  for (size_t q = 0; q < n; ++q) {
    const double r = rho[q] * kShrink;
    const double x = std::floor(X[q] + 0.5), y = std::floor(Y[q] + 0.5);
    const bool in = (one == 1.0) & (r > 0) & (x >= 0) & (y >= 0) & (x < tw) & (y < th) &
                    ((x - X[q]) * (x - X[q]) + (y - Y[q]) * (y - Y[q]) <= r * r);
    px[q] = in ? x : -1.0;
    py[q] = in ? y : -1.0;
  }
  uint64_t drawn = 0;
  for (size_t q = 0; q < n; ++q) {
    if (!(rho[q] > 0)) continue;
    ++drawn;
    if (!small_disc(rho[q]))
      write_disc(X[q], Y[q], rho[q], z[q], shared);
    else if (px[q] >= 0 && z[q] > 0)
      write_texel(uint32_t(px[q]), uint32_t(py[q]), z[q], shared);
  }
  return drawn;
}

bool OcclusionMap::hidden(int i0, int i1, int j0, int j1, double z) const {
  i0 = std::max(i0, 0), j0 = std::max(j0, 0);
  i1 = std::min(i1, int(w_) - 1), j1 = std::min(j1, int(h_) - 1);
  if (i0 > i1 || j0 > j1) return true;  // no pixel centre: nothing to see
  const int tx0 = i0 / int(s_), tx1 = i1 / int(s_), ty0 = j0 / int(s_), ty1 = j1 / int(s_);
  const std::vector<float>& m = level_[0];
  const int K = int(kSummary);
  for (int by = ty0 / K; by <= ty1 / K; ++by)
    for (int bx = tx0 / K; bx <= tx1 / K; ++bx) {
      // A summary block hidden as a whole settles all its texels.
      if (occlusion_margin(block_max(uint32_t(bx), uint32_t(by))) < z) continue;
      const int ya = std::max(ty0, by * K), yb = std::min(ty1, by * K + K - 1);
      const int xa = std::max(tx0, bx * K), xb = std::min(tx1, bx * K + K - 1);
      for (int ty = ya; ty <= yb; ++ty)
        for (int tx = xa; tx <= xb; ++tx)
          if (!(occlusion_margin(m[size_t(ty) * tw_ + tx]) < z)) return false;
    }
  return true;
}

void OcclusionMap::build_pyramid() {
  level_.resize(1);
  lw_.resize(1);
  lh_.resize(1);
  while (lw_.back() > 1 || lh_.back() > 1) {
    const uint32_t pw = lw_.back(), ph = lh_.back(), nw = (pw + 1) / 2, nh = (ph + 1) / 2;
    const std::vector<float>& p = level_.back();
    std::vector<float> n(size_t(nw) * nh);
    for (uint32_t y = 0; y < nh; ++y)
      for (uint32_t x = 0; x < nw; ++x) {
        float v = -INFINITY;
        for (uint32_t dy = 0; dy < 2; ++dy)
          for (uint32_t dx = 0; dx < 2; ++dx) {
            const uint32_t sx = std::min(2 * x + dx, pw - 1), sy = std::min(2 * y + dy, ph - 1);
            v = std::max(v, p[size_t(sy) * pw + sx]);
          }
        n[size_t(y) * nw + x] = v;
      }
    level_.push_back(std::move(n));
    lw_.push_back(nw);
    lh_.push_back(nh);
  }
}

bool OcclusionMap::hidden_pyramid(int i0, int i1, int j0, int j1, double z) const {
  i0 = std::max(i0, 0), j0 = std::max(j0, 0);
  i1 = std::min(i1, int(w_) - 1), j1 = std::min(j1, int(h_) - 1);
  if (i0 > i1 || j0 > j1) return true;
  int tx0 = i0 / int(s_), tx1 = i1 / int(s_), ty0 = j0 / int(s_), ty1 = j1 / int(s_);
  // The finest level where the box spans at most 2×2 elements.
  size_t k = 0;
  while (k + 1 < level_.size() && (tx1 - tx0 > 1 || ty1 - ty0 > 1)) {
    tx0 >>= 1, tx1 >>= 1, ty0 >>= 1, ty1 >>= 1;
    ++k;
  }
  const std::vector<float>& m = level_[k];
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx)
      if (!(occlusion_margin(m[size_t(ty) * lw_[k] + tx]) < z)) return false;
  return true;
}

}  // namespace zs
