// Seed viscous force (Laplacian form, Mueller et al. 2003):
//
//   F_v,i = - mu sum_{j != i} (m_j / rho_j) v_ij L(q),   v_ij = v_i - v_j,
//   L(q) = 40/(pi h^4) (1 - q)                          (SeedKernels)
//
// mu is the dynamic viscosity; a case with mu = 0 does not construct this term.
#pragma once

#include "sph/terms/term_bits.hpp"

#include "sph/kernels/seed_kernels.hpp"
#include "sph/pair_loop.hpp"

namespace sph {

struct SeedViscosity {
  static constexpr unsigned bit = term_bits::kSeedViscosity;
  SeedKernels kernels;
  Real mu;

  static constexpr unsigned writes = rates::kForceDensity;

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    r.F += (-mu * P.m[c.j] / P.rho[c.j] * kernels.viscosityLaplacian(c.q)) * (P.v[c.i] - P.v[c.j]);
  }
};

}  // namespace sph
