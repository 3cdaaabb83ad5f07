// Random numbers that are the same on every platform and standard library:
// std::mt19937_64's output sequence is fixed by the standard, but the
// std::*_distribution classes are not, so the distributions are here.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace zs {

class PortableRandom {
 public:
  explicit PortableRandom(uint64_t seed) : g_(seed) {}

  uint64_t bits() { return g_(); }
  // Uniform in [0, 1): the top 53 bits of one draw.
  double uniform() { return double(g_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [0, n), n > 0: multiply-shift of one draw (bias below
  // n / 2^64, irrelevant here, and no rejection loop so every call costs one
  // draw).
  uint64_t below(uint64_t n) { return uint64_t((unsigned __int128)g_() * n >> 64); }
  // Standard normal, Box-Muller from two draws (the second value is dropped,
  // which keeps every call at a fixed two draws).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  std::mt19937_64 g_;
};

}  // namespace zs
