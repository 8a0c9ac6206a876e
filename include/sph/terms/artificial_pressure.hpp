// Artificial pressure against the tensile instability (Monaghan 2000, "SPH
// without a tensile instability", J. Comput. Phys. 159, 290-311, eqs. 4.6 to
// 4.8 and sec. 5; the form for fluids as in Gray, Monaghan & Swift 2001):
//
//   a_i += - sum_j m_j R_ij f_ij^n grad_i W(r_ij),   f_ij = W(r_ij) / W(dx)
//
//   R_ij = R_i + R_j,   R_i = eps |p_i| / rho_i^2 if p_i < 0, else 0
//   R_ij = 0.01 (p_i / rho_i^2 + p_j / rho_j^2)  when p_i >= 0 and p_j >= 0
//
// dx is the initial particle spacing (`spacing`), eps and n are keys
// (`artificial_pressure`, usually 0.2; `artificial_pressure_n`, usually 4).
// The term is an extra repulsion between close pairs: f_ij^n is ~1 at
// r = dx and falls quickly beyond, so it acts where particles pair up and
// hardly changes the pressure gradient at the mean spacing. R_ij >= 0, and
// the term is antisymmetric in i and j, so momentum is conserved.
// Fluid-fluid pairs only (wall particles carry no tension of their own).
// Switched at run time like XSPH: eps = 0 is one predictable branch per
// pair, and the pair loop is not compiled twice.
// An optional term (optional_terms.hpp): ArtificialPressure is what the case
// declares (keys, checks); MonaghanArtificialPressure<Kernel> its pair
// evaluator, placed in the force pass's pack after the pressure term.
#pragma once

#include "sph/case_keys.hpp"
#include "sph/fields.hpp"
#include "sph/pair_loop.hpp"

#include <string>
#include <vector>

namespace sph {

template <class Kernel>
struct MonaghanArtificialPressure {
  static constexpr unsigned bit = term_bits::kArtificialPressure;
  static constexpr unsigned writes = rates::kAcceleration;
  Kernel kernel;
  Real epsilon = 0;        // 0: off
  int n = 4;               // exponent of f_ij
  Real invWdx = 0;         // 1 / W(dx)
  // R_ij when both pressures are positive, over (p_i/rho_i^2 + p_j/rho_j^2)
  static constexpr Real kPositive = 0.01;

  bool active() const { return epsilon > 0; }

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    if (epsilon == 0) return;
    const Real pi = P.p[c.i] / (P.rho[c.i] * P.rho[c.i]);
    const Real pj = P.p[c.j] / (P.rho[c.j] * P.rho[c.j]);
    const Real R = (pi >= 0 && pj >= 0) ? kPositive * (pi + pj)
                                        : epsilon * ((pi < 0 ? -pi : 0) + (pj < 0 ? -pj : 0));
    const Real f = kernel.W(c.r) * invWdx;
    Real fn = 1;
    for (int k = 0; k < n; ++k) fn *= f;
    r.a += (-P.m[c.j] * R * fn) * c.gradW;
  }
};

struct ArtificialPressure {
  static constexpr const char* name = "artificial_pressure_monaghan2000";
  static constexpr unsigned bit = term_bits::kArtificialPressure;
  static constexpr bool kPerPair = true;  // pairEvaluator()
  Real epsilon = 0;                       // 0: off
  int n = 4;
  Real spacing = 0;                       // dx

  static std::vector<KeySpec> keys() {
    using namespace key_range;
    return {termKey("artificial_pressure", KeyGroup::kPhysics, "",
                    "Monaghan (2000) artificial pressure epsilon against the tensile instability: R_ij (W_ij/W(dx))^n "
                    "added to the pressure term (0: off; 0.2 usual; needs spacing)",
                    within(0, 10), Real(0)),
            termKey("artificial_pressure_n", KeyGroup::kPhysics, "",
                    "Exponent n of (W_ij/W(dx))^n in the artificial pressure (4 usual)", count(1, 16), 4L)};
  }
  static ArtificialPressure fromCase(const CaseConfig& c) {
    return {termReal(c, "artificial_pressure"), static_cast<int>(termCount(c, "artificial_pressure_n")), c.spacing};
  }
  static void validate(const CaseConfig& c) {
    const Real epsilon = termReal(c, "artificial_pressure");
    if (epsilon > 0 && !(c.spacing > 0))
      throw CaseError("artificial_pressure = " + std::to_string(epsilon) +
                      " needs spacing (> 0): its f_ij = W(r_ij)/W(dx) is relative to the particle spacing dx");
  }
  template <class Note>
  static void noteUnused(const CaseConfig& c, Note&& note) {
    if (termReal(c, "artificial_pressure") == 0)
      note("artificial_pressure_n", "artificial_pressure is 0 (off); it applies to artificial_pressure > 0");
  }

  bool active() const { return epsilon > 0; }
  FieldSet reads() const { return 0; }  // x, m, rho, p: read by the pressure term already

  template <class Kernel>
  MonaghanArtificialPressure<Kernel> pairEvaluator(const Kernel& k) const {
    return {k, epsilon, n, epsilon > 0 ? 1 / k.W(spacing) : 0};
  }
};

}  // namespace sph
