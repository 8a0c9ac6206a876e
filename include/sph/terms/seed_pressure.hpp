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
#include "sph/terms/pair_accelerations.hpp"

namespace sph {

struct SeedPressure {
  static constexpr unsigned bit = term_bits::kSeedPressure;
  SeedKernels kernels;

  static constexpr bool isForceDensity = true;

  template <int D>
  Vec<D> pair(const PairContext<D>& c, const Particles<D>& P) const {
    const Real pBar = (P.p[c.i] + P.p[c.j]) / 2;
    return (-P.m[c.j] / P.rho[c.j] * pBar * kernels.pressureFactor(c.q)) * c.rij;
  }
};

}  // namespace sph
