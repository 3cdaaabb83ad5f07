// Two lanes of a vector type side by side (light_kernel.h's lane interface):
// the same operations on twice the segments, written so the two halves'
// instructions interleave and each hides the other's latency (the kernel is
// a few long dependency chains: log, exp, the polynomials). Included only by
// the per-ISA kernel files, with a lane type local to that file.
#pragma once

#include <cstdint>

namespace zs::light {

template <class L>
struct LanePair {
  using Scalar = typename L::Scalar;
  static constexpr int kWidth = 2 * L::kWidth;
  struct Mask {
    typename L::Mask a, b;
  };
  L a, b;
  LanePair() = default;
  explicit LanePair(double x) : a(x), b(x) {}
  LanePair(L x, L y) : a(x), b(y) {}
  static LanePair load(const double* p) { return {L::load(p), L::load(p + L::kWidth)}; }
  void store(double* p) const {
    a.store(p);
    b.store(p + L::kWidth);
  }
  friend LanePair operator+(LanePair x, LanePair y) { return {x.a + y.a, x.b + y.b}; }
  friend LanePair operator-(LanePair x, LanePair y) { return {x.a - y.a, x.b - y.b}; }
  friend LanePair operator*(LanePair x, LanePair y) { return {x.a * y.a, x.b * y.b}; }
  friend LanePair operator/(LanePair x, LanePair y) { return {x.a / y.a, x.b / y.b}; }
  friend LanePair fmadd(LanePair x, LanePair y, LanePair z) { return {fmadd(x.a, y.a, z.a), fmadd(x.b, y.b, z.b)}; }
  friend LanePair fnmadd(LanePair x, LanePair y, LanePair z) { return {fnmadd(x.a, y.a, z.a), fnmadd(x.b, y.b, z.b)}; }
  friend Mask operator<(LanePair x, LanePair y) { return {x.a < y.a, x.b < y.b}; }
  friend Mask operator>(LanePair x, LanePair y) { return {x.a > y.a, x.b > y.b}; }
  friend Mask operator<=(LanePair x, LanePair y) { return {x.a <= y.a, x.b <= y.b}; }
  friend Mask operator>=(LanePair x, LanePair y) { return {x.a >= y.a, x.b >= y.b}; }
  friend Mask operator==(LanePair x, LanePair y) { return {x.a == y.a, x.b == y.b}; }
  friend Mask not_less(LanePair x, LanePair y) { return {not_less(x.a, y.a), not_less(x.b, y.b)}; }
  static Mask mask_and(Mask x, Mask y) { return {L::mask_and(x.a, y.a), L::mask_and(x.b, y.b)}; }
  static bool all(Mask m) { return L::all(m.a) && L::all(m.b); }
  static void store_mask(uint8_t* p, Mask m) {
    L::store_mask(p, m.a);
    L::store_mask(p + L::kWidth, m.b);
  }
  static LanePair lookup(const Scalar* table, LanePair n, int entries) {
    return {L::lookup(table, n.a, entries), L::lookup(table, n.b, entries)};
  }
  friend LanePair max(LanePair x, LanePair y) { return {max(x.a, y.a), max(x.b, y.b)}; }
  friend LanePair abs(LanePair x) { return {abs(x.a), abs(x.b)}; }
  friend LanePair select(Mask m, LanePair x, LanePair y) { return {select(m.a, x.a, y.a), select(m.b, x.b, y.b)}; }
  friend LanePair round_int(LanePair x) { return {round_int(x.a), round_int(x.b)}; }
  friend LanePair pow2_int(LanePair x) { return {pow2_int(x.a), pow2_int(x.b)}; }
  friend void split_exponent(LanePair w, LanePair* e, LanePair* m) {
    split_exponent(w.a, &e->a, &m->a);
    split_exponent(w.b, &e->b, &m->b);
  }
};

}  // namespace zs::light
