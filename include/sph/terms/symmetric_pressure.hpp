// Symmetric pressure acceleration (Monaghan 1992, "Smoothed particle
// hydrodynamics", Annu. Rev. Astron. Astrophys. 30, eq. 3.3):
//
//   a_i = - sum_j m_j (p_i / rho_i^2 + p_j / rho_j^2) grad_i W(r_ij, h)
//
// Antisymmetric in i, j, so total momentum is conserved exactly.
//
// With CSPM (corrected = true) it is the same sum with the corrected gradient L_i grad_i W_ij
// (cspm_correction.hpp). Renormalised gradients kept in a form with p_i + p_j
// for stability, as Oger et al. 2007 (J. Comput. Phys. 225, 1472) do; here
// with Monaghan's p/rho^2 weights. For a uniform density it is
// a_i = -(1/rho)[grad p + 2 p_i L_i sum_j V_j grad_i W_ij] for a linear p:
// the (M_i - I) grad p part of the error of the uncorrected form (half the
// gradient on a free surface) is gone, and what is left vanishes where
// p_i = 0 (the free surface) or the support is full and ordered. The
// difference form sum_j V_j (p_j - p_i) L_i grad W, exact for any linear p,
// was tried and left out: it does not hold a free surface together (a surface
// particle at low pressure is pushed away from its neighbours, expands by the
// corrected continuity, and the hydrostatic tank blew up at its top corners
// within 0.02 s). Not antisymmetric in i, j: momentum is conserved only to
// the accuracy of the gradient.
#pragma once

#include "sph/terms/term_bits.hpp"

#include "sph/pair_loop.hpp"

namespace sph {

// The pair loop hands the pressure term c.gradWC: grad W itself, or L_i
// grad W when the case corrects gradients (a uniform branch in the loop,
// pair_loop.hpp), so one instantiation serves both; `corrected` only names
// which of the two ran (its term bit).
struct SymmetricPressure {
  bool corrected = false;
  static constexpr unsigned writes = rates::kAcceleration;
  unsigned bits() const { return corrected ? term_bits::kCspmPressure : term_bits::kSymmetricPressure; }

  // p/rho^2 of every particle, formed before the pairs (pair_loop.hpp's
  // ParticlePrologue), or null: formed at each pair.
  const Real* pOverRho2 = nullptr;

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    const Real pi = pOverRho2 ? pOverRho2[c.i] : P.p[c.i] / (P.rho[c.i] * P.rho[c.i]);
    const Real pj = pOverRho2 ? pOverRho2[c.j] : P.p[c.j] / (P.rho[c.j] * P.rho[c.j]);
    r.a += (-P.m[c.j] * (pi + pj)) * c.gradWC;
  }
};

}  // namespace sph
