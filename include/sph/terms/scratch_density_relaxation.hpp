// SCRATCH (not physics to keep): a density relaxation rate towards the
// kernel-weighted mean of the neighbours,
//   d rho_i/dt += kappa sum_j (m_j / rho_j) (rho_j - rho_i) W_ij,
// key scratch_density_relaxation (kappa, 1/s; 0: off); fluid pairs only,
// continuity density only. A demonstration of terms/optional_terms.hpp.
#pragma once

#include "sph/case_keys.hpp"
#include "sph/fields.hpp"
#include "sph/pair_loop.hpp"

#include <vector>

namespace sph {

template <class Kernel>
struct ScratchDensityRelaxationPairs {
  static constexpr unsigned writes = rates::kDensityRate;
  Kernel kernel;
  Real kappa = 0;
  bool active() const { return kappa > 0; }
  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    if (kappa == 0) return;
    r.drho += kappa * P.m[c.j] / P.rho[c.j] * (P.rho[c.j] - P.rho[c.i]) * kernel.W(c.r);
  }
};

struct ScratchDensityRelaxation {
  static constexpr const char* name = "scratch_density_relaxation";
  static constexpr bool kPerPair = true;
  Real kappa = 0;

  static std::vector<KeySpec> keys() {
    return {termKey("scratch_density_relaxation", KeyGroup::kPhysics, "1/s",
                    "Scratch: d rho_i/dt += kappa sum_j V_j (rho_j - rho_i) W_ij (continuity density; 0: off)",
                    key_range::within(0, 1e6), Real(0))};
  }
  static ScratchDensityRelaxation fromCase(const CaseConfig& c) { return {termReal(c, "scratch_density_relaxation")}; }
  static void validate(const CaseConfig& c) {
    if (termReal(c, "scratch_density_relaxation") > 0 && c.density != "continuity")
      throw CaseError("scratch_density_relaxation needs density = \"continuity\"");
  }
  template <class Note>
  static void noteUnused(const CaseConfig&, Note&&) {}
  bool active() const { return kappa > 0; }
  FieldSet reads() const { return fieldBit(kFieldRho); }
  template <class K>
  ScratchDensityRelaxationPairs<K> pairEvaluator(const K& k) const { return {k, kappa}; }
};

}  // namespace sph
