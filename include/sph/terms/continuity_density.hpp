// Continuity density (Monaghan 1992, eq. 2.17; Monaghan 2005):
//
//   d rho_i / dt = sum_j m_j (v_i - v_j) . grad_i W(r_ij)
//
// over fluid and wall neighbours alike (a wall's v is its own, prescribed,
// velocity: 0 for a fixed wall). It also gives dynamic boundary particles
// their density rate from their fluid neighbours (Crespo et al. 2007).
// Always the plain grad_i W, also with the CSPM gradient correction on: this
// rate is then exactly d/dt sum_j m_j W_ij, so the density (and the
// pressure) follows how closely the particles are packed. With L_i grad W
// it did not: where the particles crowd (the dam break's surge tongue)
// M_i grows past I, L_i shrinks the rate, the crowding raises no pressure
// and feeds itself (kernel sums 1.6-2.2 rho0 at rho = rho0, M_i's largest
// eigenvalue ~2) until a particle is pressed through the floor (t = 0.47 s;
// cspm_correction.hpp). As in delta-SPH (Antuono et al. 2010, Marrone et
// al. 2011), the renormalised gradient is not used in the continuity sum.
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
    r.drho += P.m[c.j] * (P.v[c.i] - P.v[c.j]).dot(c.gradW);
  }
};

}  // namespace sph
