// CSPM gradient correction: the corrective smoothed particle method of
// Chen, Beraun & Carney 1999 (Int. J. Numer. Meth. Engng 46, 231-252) in the
// matrix form of Bonet & Lok 1999 (Comput. Methods Appl. Mech. Engrg. 180,
// 97-115, eq. 29) and Randles & Libersky 1996:
//
//   M_i = sum_k V_k (x_k - x_i) (x) grad_i W_ik,   V_k = m_k / rho_k
//   L_i = M_i^-1,                grad_i W^C_ij = L_i grad_i W_ij
//
// so that sum_j V_j (f_j - f_i) grad_i W^C_ij = grad f exactly for every
// linear f, on any particle arrangement. For a radial kernel grad_i W_ik =
// (W'/r) (x_i - x_k), so M_i = -sum_k V_k (W'/r) r_ik r_ik^T is symmetric
// (no question of which side L_i multiplies) and ~ identity inside a full
// support. This pass computes L_i into the field cspmL before the forces;
// the pair loop hands each fluid pair gradWC = L_i grad_i W (GradientCorrection
// in pair_loop.hpp), which the pressure term (symmetric_pressure.hpp) uses; the continuity
// term, viscosity and density diffusion keep grad W. (The continuity term
// used L_i grad W until 2026-12: the density then stopped following the
// particles' packing and the dam break's surge tongue crowded until a
// particle went through the floor; continuity_density.hpp.)
//
// Neighbours: fluid and, when the walls are in the SPH sums (dummy,
// dynamic), the wall particles with their own m and rho: the same
// neighbours as the pressure sum. Only fluid particles are corrected.
//
// Guard: near a free surface M_i loses rank (half a support: its smallest
// eigenvalue ~ 0.5; a particle with a few neighbours: ~ 0). When the
// smallest eigenvalue of M_i is below kCspmMinEigenvalue (L_i would amplify
// a gradient more than 5 times) L_i = I, the uncorrected gradient; each
// such particle-evaluation is counted and the run summary prints the count.
#pragma once

#include "sph/boundaries/wall_sums.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/neighbour_walk.hpp"
#include "sph/particles.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/terms/term_bits.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <optional>

namespace sph {

constexpr Real kCspmMinEigenvalue = 0.2;

// M_i of fluid particle i, from its row (r_ij = x_i - x_j; a neighbour
// across a periodic face is a ghost).
template <int D, class K>
inline Mat<D> cspmMoment(const NeighbourRow<D>& row, const Particles<D>& P, const K& kernel, bool wallsInSums) {
  Mat<D> M = Mat<D>::Zero();
  row.forEachSummed(wallsInSums, [&](std::uint32_t j, const Vec<D>& rij) {
    const Real r = rij.norm();
    if (!(r > 0)) return;
    // (x_j - x_i) (x) grad_i W_ij = -(W'/r) rij rij^T
    M.noalias() -= (P.m[j] / P.rho[j] * kernel.dWdr_r(r)) * (rij * rij.transpose());
  });
  return M;
}

// L_i = M_i^-1, or nothing when M_i is ill-conditioned.
template <int D>
inline std::optional<Mat<D>> cspmCorrection(const Mat<D>& M) {
  Eigen::SelfAdjointEigenSolver<Mat<D>> eig;
  eig.computeDirect(M, Eigen::EigenvaluesOnly);
  if (!(eig.eigenvalues()[0] >= kCspmMinEigenvalue)) return std::nullopt;
  return Mat<D>(M.inverse());
}

template <int D>
struct CspmCorrectionPass {
  static constexpr const char* name = "cspm_correction";
  Kernel<D> kernel;
  WallSums walls{};  // what the walls add (not repulsive walls)

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const;
  // run() reads the neighbours' x, m and rho; writes the fluid's cspmL.
  FieldAccess fields(const StepContext&) const {
    return {fieldBits(kFieldX, kFieldM, kFieldRho), fieldBit(kFieldCspmL)};
  }
};

// Defined here, instantiated once (src/instantiate_*.cpp).
template <int D>
unsigned CspmCorrectionPass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const {
  const std::size_t n = P.fluidCount();
  const long fallbacks = walkNeighbours<long>(
      P, neighbours, P.range(ParticleRange::kFluid), kernel,
      [&](std::size_t i, const NeighbourRow<D>& row, long& fallback, const auto& k) {
        const std::optional<Mat<D>> L = cspmCorrection<D>(cspmMoment(row, P, k, walls.inSums));
        if (L) {
          P.cspmL[i] = *L;
        } else {
          P.cspmL[i] = Mat<D>::Identity();
          ++fallback;
        }
      });
  if (ctx.counts) {
    ctx.counts->cspmParticles += static_cast<long>(n);
    ctx.counts->cspmFallbacks += fallbacks;
  }
  return term_bits::kCspmCorrection;
}

extern template struct CspmCorrectionPass<2>;
extern template struct CspmCorrectionPass<3>;

}  // namespace sph
