#include "lighting/ao_directions.h"

#include <array>
#include <map>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace zs {

bool valid_direction_count(uint64_t n) {
  for (uint64_t v = 6; v <= n; v = 2 + 4 * (v - 2))  // 2 + 4^(s+1) → 2 + 4^(s+2)
    if (v == n) return true;
  return false;
}

std::vector<glm::dvec3> ao_directions(uint32_t n) {
  if (!valid_direction_count(n))
    throw std::runtime_error("ao.directions must be 6, 18, 66, 258, 1026, ... (2 + 4^(s+1)); got " +
                             std::to_string(n));
  // Vertices in output order, each one's opposite, and the current triangles.
  std::vector<glm::dvec3> v = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<uint32_t> opp = {1, 0, 3, 2, 5, 4};
  // The octahedron's faces: one per octant, (±x, ±y, ±z).
  std::vector<std::array<uint32_t, 3>> tris;
  for (uint32_t sx : {0u, 1u})
    for (uint32_t sy : {2u, 3u})
      for (uint32_t sz : {4u, 5u}) tris.push_back({sx, sy, sz});
  while (v.size() < n) {
    // Edge (a < b) → its midpoint's id; a new midpoint is emitted with its
    // opposite (the midpoint of the opposite edge), so pairs stay adjacent.
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto key = [](uint32_t a, uint32_t b) { return a < b ? std::make_pair(a, b) : std::make_pair(b, a); };
    auto midpoint = [&](uint32_t a, uint32_t b) -> uint32_t {
      auto it = mid.find(key(a, b));
      if (it != mid.end()) return it->second;
      const uint32_t m = uint32_t(v.size());
      // normalize(a + b): the opposite edge's sum is exactly the negation, so
      // its midpoint is exactly −this one.
      const glm::dvec3 d = glm::normalize(v[a] + v[b]);
      v.push_back(d);
      v.push_back(-d);
      opp.push_back(m + 1);
      opp.push_back(m);
      mid[key(a, b)] = m;
      mid[key(opp[a], opp[b])] = m + 1;
      return m;
    };
    std::vector<std::array<uint32_t, 3>> next;
    for (const auto& t : tris) {
      const uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    tris.swap(next);
  }
  return v;
}

}  // namespace zs
