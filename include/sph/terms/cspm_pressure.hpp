// Pressure acceleration with the CSPM-corrected gradient (Chen, Beraun &
// Carney 1999, eq. 14, the difference form of a first derivative):
//
//   a_i = -(1/rho_i) sum_j V_j (p_j - p_i) L_i grad_i W_ij,   V_j = m_j / rho_j
//
// With L_i from cspm_correction.hpp this is -grad p / rho_i exactly for a
// linear pressure field on any particle arrangement and near a free surface
// or a wall, where the symmetric form (symmetric_pressure.hpp) is off by
// -(2 p_i / rho_i) sum_j V_j grad W_ij. The price: it is not antisymmetric
// in i, j, so momentum is conserved only to the accuracy of the gradient,
// and it does not push particles apart at uniform pressure (no remedy for
// clumping of its own).
#pragma once

#include "sph/pair_loop.hpp"
#include "sph/terms/term_bits.hpp"

namespace sph {

struct CspmPressure {
  static constexpr unsigned bit = term_bits::kCspmPressure;
  static constexpr unsigned writes = rates::kAcceleration;
  bool differenceForm = true;

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    if (differenceForm) {
      r.a += (-P.m[c.j] / P.rho[c.j] * (P.p[c.j] - P.p[c.i]) / P.rho[c.i]) * c.gradWC;
    } else {
      const Real pi = P.p[c.i] / (P.rho[c.i] * P.rho[c.i]);
      const Real pj = P.p[c.j] / (P.rho[c.j] * P.rho[c.j]);
      r.a += (-P.m[c.j] * (pi + pj)) * c.gradWC;
    }
  }
};

}  // namespace sph
