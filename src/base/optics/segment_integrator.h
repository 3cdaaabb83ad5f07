// Light from one ray segment inside a cell, for the absorption-plus-emission
// model (B-Convert digest §1.3, Eq. 2.7; scene spec): extinction
// tau(s) = -ln(1 - a(s))/unit, emission c(s)·tau(s), with the scalar s linear
// along the segment.
// A segment returns its premultiplied colour I (as seen at its front end) and
// its transmittance T; front-to-back: acc += acc_T·I, acc_T *= T.
#pragma once

#include <vector>

#include "base/optics/transfer_function.h"

namespace zs {

enum class Integrator {
  Exact,          // split at TF breakpoints, closed-form optical depth, quadrature for colour
  Linear,         // the seed's Eq. 2.8: colour and opacity linear between the two ends
  Preintegrated,  // Moreland–Angel partial pre-integration: tau and colour linear, psi table
  Taylor2,        // original-ZSweep style: e^-x by its 2nd-order Taylor expansion, mean colour
};

const char* to_string(Integrator i);
bool parse_integrator(const std::string& s, Integrator* out);

struct SegmentLight {
  double rgb[3];
  double T;
};

// What the exact integrator needs of a segment's end besides its scalar:
// the transfer-function interval and ln(1 - a). Every fragment ends one
// segment and starts the next, so computing this once per fragment (the
// compositor keeps the previous one) halves the logs and searches.
struct SegmentEnd {
  int k = 0;       // interval of the scalar (TransferFunction::interval)
  double L = 0;    // ln(1 - a(s))
};

class SegmentIntegrator {
 public:
  SegmentIntegrator(const TransferFunction& tf, Integrator kind);

  // Scalar from s0 (front) to s1 (back) over world length L >= 0.
  SegmentLight integrate(double s0, double s1, double L) const {
    return integrate(s0, end(s0), s1, end(s1), L);
  }
  SegmentEnd end(double s) const;
  // The same with ends already prepared by end(); identical results.
  SegmentLight integrate(double s0, const SegmentEnd& e0, double s1, const SegmentEnd& e1, double L) const;

  Integrator kind() const { return kind_; }

 private:
  SegmentLight exact(double s0, const SegmentEnd& e0, double s1, const SegmentEnd& e1, double L) const;
  SegmentLight linear(double s0, double s1, double L) const;
  SegmentLight preintegrated(double s0, double s1, double L) const;
  SegmentLight taylor2(double s0, double s1, double L) const;

  const TransferFunction& tf_;
  Integrator kind_;
  std::vector<float> psi_;  // Moreland–Angel psi(gamma_f, gamma_b), kPsiN^2 entries
  std::vector<double> L_at_bs_;  // ln(1 - a) at each breakpoint
};

// One piece on which colour and opacity are both linear: exact optical depth
// (closed form for -ln(1 - a) with a linear) and colour by adaptive
// Gauss–Legendre quadrature of the transmittance. Exposed for tests.
SegmentLight integrate_linear_piece(const double c0[3], double a0, const double c1[3], double a1, double len,
                                    double unit_distance);
// The same with L0 = ln(1 - a0) and L1 = ln(1 - a1) given.
SegmentLight integrate_linear_piece(const double c0[3], double a0, double L0, const double c1[3], double a1,
                                    double L1, double len, double unit_distance);

}  // namespace zs
