#include "lighting/multi_depth.h"

#include <algorithm>
#include <cmath>

namespace zs {

std::vector<std::pair<int, int>> depth_pattern(uint32_t n) {
  // The 8 neighbours counter-clockwise from +x; n − 1 of them, spread evenly.
  static const std::pair<int, int> ring[8] = {{1, 0},  {1, 1},   {0, 1},  {-1, 1},
                                               {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  std::vector<std::pair<int, int>> p;
  const uint32_t m = n - 1;
  for (uint32_t i = 0; i < m; ++i) p.push_back(ring[std::lround(8.0 * i / m) % 8]);
  return p;
}

void build_multi_depth(const float* z, uint32_t size, uint32_t n, DepthSelect select, float* out) {
  const int D = int(size);
  auto at = [&](int x, int y) { return z[size_t(std::clamp(y, 0, D - 1)) * size + size_t(std::clamp(x, 0, D - 1))]; };
  if (n == 1) {
    std::copy(z, z + size_t(size) * size, out);
    return;
  }
  const std::vector<std::pair<int, int>> pat = n >= 4 ? depth_pattern(n) : std::vector<std::pair<int, int>>{};
  for (int y = 0; y < D; ++y)
    for (int x = 0; x < D; ++x) {
      float* o = out + (size_t(y) * size + size_t(x)) * n;
      const float c = z[size_t(y) * size + size_t(x)];
      o[0] = c;
      if (n >= 4) {
        for (uint32_t i = 0; i + 1 < n; ++i) o[i + 1] = at(x + pat[i].first, y + pat[i].second);
        continue;
      }
      float mx = c, mn = c;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const float s = at(x + dx, y + dy);
          mx = std::max(mx, s);
          mn = std::min(mn, s);
        }
      if (n == 2) {
        o[1] = select == DepthSelect::Max ? mx : mn;
      } else {
        o[1] = mx;
        o[2] = mn;
      }
    }
}

}  // namespace zs
