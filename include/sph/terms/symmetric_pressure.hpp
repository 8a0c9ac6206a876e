// Symmetric pressure acceleration (Monaghan 1992, "Smoothed particle
// hydrodynamics", Annu. Rev. Astron. Astrophys. 30, eq. 3.3):
//
//   a_i = - sum_j m_j (p_i / rho_i^2 + p_j / rho_j^2) grad_i W(r_ij, h)
//
// Antisymmetric in i, j, so total momentum is conserved exactly.
#pragma once

#include "sph/terms/term_bits.hpp"

#include "sph/pair_loop.hpp"

namespace sph {

struct SymmetricPressure {
  static constexpr unsigned bit = term_bits::kSymmetricPressure;
  static constexpr unsigned writes = rates::kAcceleration;

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    const Real pi = P.p[c.i] / (P.rho[c.i] * P.rho[c.i]);
    const Real pj = P.p[c.j] / (P.rho[c.j] * P.rho[c.j]);
    r.a += (-P.m[c.j] * (pi + pj)) * c.gradW;
  }
};

}  // namespace sph
