// Seed pressure force (averaged-pressure form of the seed 2D scheme):
//
//   F_p,i = - sum_{j != i} (m_j / rho_j) (p_i + p_j) / 2 * G(q) r_ij,
//   G(q) r_ij = -30/(pi h^3) r_ij (1 - q)^2 / q          (SeedKernels)
//
// Because m_i F_p,i / rho_i is symmetric in i and j, pair momenta cancel.
// Two particles at the same position give q = 0 and a non-finite force; the
// state check reports it (the seed scheme has no guard against it).
#pragma once

#include "sph/terms/term_bits.hpp"

#include "sph/kernels/seed_kernels.hpp"
#include "sph/pair_loop.hpp"

namespace sph {

struct SeedPressure {
  static constexpr unsigned bit = term_bits::kSeedPressure;
  SeedKernels kernels;

  static constexpr unsigned writes = rates::kForceDensity;

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    const Real pBar = (Real(P.p[c.i]) + P.p[c.j]) / 2;
    r.F += (-P.m[c.j] / P.rho[c.j] * pBar * kernels.pressureFactor(c.q)) * c.rij;
  }
};

}  // namespace sph
