// Continuity density (Monaghan 1992, eq. 2.17; Monaghan 2005):
//
//   d rho_i / dt = sum_j m_j (v_i - v_j) . grad_i W(r_ij)
//
// over fluid and wall neighbours alike (a wall's v is its own, prescribed,
// velocity: 0 for a fixed wall). It also gives dynamic boundary particles
// their density rate from their fluid neighbours (Crespo et al. 2007).
// With a gradient correction (CSPM) the corrected gradient L_i grad_i W
// is used (gradWC; it is grad W otherwise).
// Switched on at run time (density = continuity): off, it is one
// predictable branch per pair.
#pragma once

#include "sph/pair_loop.hpp"

namespace sph {

struct ContinuityDensity {
  static constexpr unsigned bit = term_bits::kContinuityDensity;
  static constexpr unsigned writes = rates::kDensityRate;
  bool on = false;

  bool active() const { return on; }

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    if (!on) return;
    r.drho += P.m[c.j] * (P.v[c.i] - P.v[c.j]).dot(c.gradWC);
  }
};

}  // namespace sph
