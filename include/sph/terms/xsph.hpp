// XSPH velocity smoothing (Monaghan 1989, "On the problem of penetration in
// particle methods", J. Comput. Phys. 82):
//
//   dx_i/dt = v_i + eps sum_j (m_j / rhobar_ij) (v_j - v_i) W(r_ij, h)
//
// The pair sum goes to PairRates::xsph; the epilogue multiplies it by eps
// into vXsph, which the integrators add to the drift. It moves particles
// with a locally averaged velocity and keeps momentum. Fluid pairs only.
// Switched on and off at run time (eps = 0: one predictable branch per pair
// and nothing else), which halves the number of pair loops compiled.
#pragma once

#include "sph/pair_loop.hpp"

namespace sph {

template <class Kernel>
struct Xsph {
  static constexpr unsigned bit = term_bits::kXsph;
  static constexpr unsigned writes = rates::kXsph;
  Kernel kernel;
  Real epsilon = 0;

  bool active() const { return epsilon > 0; }

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    if (epsilon == 0) return;
    r.xsph += (2 * P.m[c.j] / (P.rho[c.i] + P.rho[c.j]) * kernel.W(c.r)) * (P.v[c.j] - P.v[c.i]);
  }
};

}  // namespace sph
