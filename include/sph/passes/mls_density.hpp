// MLS density re-initialisation: the first-order moving-least-squares
// kernel of Colagrossi & Landrieu 2003 (J. Comput. Phys. 191, 448-475,
// sec. 3.2, eqs. 23-25; after Dilts 1999), applied to the density every N
// steps:
//
//   rho_i <- sum_j m_j W^MLS_ij,   W^MLS_ij = [beta_0 + beta . (x_i - x_j)] W_ij
//   [beta_0, beta]^T = A_i^-1 (1, 0, ..., 0)^T,   A_i = sum_j V_j W_ij p p^T,
//   p = [1, x_i - x_j],  V_j = m_j / rho_j                (self term included)
//
// A_i is (D+1) x (D+1), in 2D and 3D alike (the seed document asks whether
// MLS is 2D only: nothing in it is). By construction sum_j V_j f_j W^MLS_ij
// = f(x_i) for every linear f, so a density that varies linearly (the
// hydrostatic column) is kept exactly, also where the support is truncated.
// Here p = [1, (x_i - x_j)/h]: the same kernel, with a dimensionless A_i
// whose condition number does not depend on h.
//
// Guard: A_i is singular when the neighbours do not span the space (a
// particle with one or two neighbours, or all of them on a line); when the
// ratio of its smallest to its largest eigenvalue (the 2-norm reciprocal
// condition number of the symmetric A_i, from its eigenvalues, not the LDL^T
// estimate, which missed an isolated pair: rank 2 of 3 came out >= 1e-3) is
// below kMlsMinRcond the particle gets the Shepard density instead (counted:
// the run summary prints how many). A full 2D support has a ratio of
// ~ 0.1-0.3 and a particle on a flat free surface ~ 0.05; 1e-3 only catches
// the degenerate, whose ratio is round-off (~1e-16).
//
// Neighbours, walls, scratch field and timing as for Shepard
// (shepard_density.hpp): fluid particles only, after a step.
#pragma once

#include "sph/boundaries/wall_sums.hpp"
#include "sph/passes/shepard_density.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <optional>

namespace sph {

constexpr Real kMlsMinRcond = 1e-3;

// The MLS density of fluid particle i, or nothing when A_i is singular;
// from its row (r_ij = x_i - x_j; a neighbour across a periodic face is a
// ghost).
template <int D, class K>
inline std::optional<Real> mlsDensity(const NeighbourRow<D>& row, const Particles<D>& P, const K& kernel,
                                      bool wallsInSums) {
  using Vp = Eigen::Matrix<Real, D + 1, 1>;
  using Mp = Eigen::Matrix<Real, D + 1, D + 1>;
  const std::size_t i = row.index();
  const Real invH = 1 / kernel.h();
  Mp A = Mp::Zero();
  const Real W0 = kernel.W(0);
  A(0, 0) = P.m[i] / P.rho[i] * W0;
  row.forEachSummed(wallsInSums, [&](std::uint32_t j, const Vec<D>& rij) {
    Vp p;
    p[0] = 1;
    p.template tail<D>() = rij * invH;
    A.noalias() += (P.m[j] / P.rho[j] * kernel.W(rij.norm())) * (p * p.transpose());
  });
  Eigen::SelfAdjointEigenSolver<Mp> eig;
  if constexpr (D + 1 <= 3) eig.computeDirect(A, Eigen::EigenvaluesOnly);
  else eig.compute(A, Eigen::EigenvaluesOnly);
  const auto& lambda = eig.eigenvalues();  // ascending
  if (!(lambda[0] >= kMlsMinRcond * lambda[D])) return std::nullopt;
  const Eigen::LDLT<Mp> ldlt(A);
  if (ldlt.info() != Eigen::Success) return std::nullopt;
  const Vp beta = ldlt.solve(Vp::Unit(0));
  Real rho = P.m[i] * beta[0] * W0;
  row.forEachSummed(wallsInSums, [&](std::uint32_t j, const Vec<D>& rij) {
    rho += P.m[j] * (beta[0] + beta.template tail<D>().dot(rij * invH)) * kernel.W(rij.norm());
  });
  return rho;
}

template <int D>
struct MlsDensityPass {
  static constexpr const char* name = "mls_density";
  Kernel<D> kernel;
  long every = 20;             // steps between two re-initialisations
  WallSums walls{};            // what the walls add (not repulsive walls)
  EquationOfState eos = LinearEos{1, 1};
  bool clampNegative = false;  // negative_pressure = clamp

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const;
  FieldAccess fields(const StepContext& ctx) const { return reinitFields(ctx, every); }
};

// Defined here, instantiated once (src/instantiate_*.cpp).
template <int D>
unsigned MlsDensityPass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const {
  if (!reinitDue(ctx, every)) return 0;
  const std::size_t n = P.fluidCount();
  const long fallbacks = walkNeighbours<long>(
      P, neighbours, P.range(ParticleRange::kFluid), kernel,
      [&](std::size_t i, const NeighbourRow<D>& row, long& fallback, const auto& k) {
        const std::optional<Real> rho = mlsDensity(row, P, k, walls.inSums);
        if (rho) {
          P.rhoReinit[i] = *rho;
        } else {
          P.rhoReinit[i] = shepardDensity(row, P, k, walls.inSums);
          ++fallback;
        }
      });
  applyReinitialisedDensity(P, eos, clampNegative);
  if (ctx.counts) {
    ++ctx.counts->reinitSteps;
    ctx.counts->reinitParticles += static_cast<long>(n);
    ctx.counts->mlsFallbacks += fallbacks;
  }
  return term_bits::kMlsDensity;
}

extern template struct MlsDensityPass<2>;
extern template struct MlsDensityPass<3>;

}  // namespace sph
