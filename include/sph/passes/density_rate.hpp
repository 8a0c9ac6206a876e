// Pass: the density rate alone,
//   d rho_i/dt = sum_j m_j (v_i - v_j) . grad_i W_ij  + density diffusion
// (continuity_density.hpp, density_diffusion.hpp), and the dynamic wall
// particles' own rate from their fluid neighbours, at the particles'
// current x and v. The leap-frog and symplectic Euler integrators advance
// rho like a position, with a rate at a state of its own (half-step
// positions and velocities; the new velocity): they run this pass apart
// (Model::densityRate, the model's density-rate list) and the force pass
// then leaves d rho/dt alone (StepContext::densityRateApart). The
// continuity sum takes the plain grad W, CSPM or not
// (continuity_density.hpp), so no correction is formed here. One pair loop
// per kernel. The optional terms that write the density rate only
// (terms/optional_terms.hpp) follow the diffusion, in their list order.
// With Wendland C2 or the cubic spline and no such term, on a build for
// AVX2 or AVX-512,
// the fluid particles' pairs, fluid and wall, go in SIMD blocks instead
// (density_rate_blocks.hpp: the same rates up to the order of the sum).
#pragma once

#include "sph/boundaries/wall_sums.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/pair_loop.hpp"
#include "sph/passes/seed_forces.hpp"
#include "sph/passes/density_rate_blocks.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/terms/continuity_density.hpp"
#include "sph/terms/density_diffusion.hpp"
#include "sph/terms/optional_terms.hpp"

#include <tuple>
#include <type_traits>
#include <variant>

namespace sph {

template <int D>
struct DensityRatePass {
  static constexpr const char* name = "density_rate";
  Kernel<D> kernel;
  DensityDiffusion<D> diffusion;  // coefficient 0: off
  WallSums walls{};               // wall pairs (inSums), the walls' own rates (densityRates)
  OptionalTerms terms{};          // its density-rate-only ones run here

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const;
  // run() reads x, m and v (rho for the diffusion, what the optional
  // density-rate terms read); writes d rho/dt.
  FieldAccess fields(const StepContext&) const {
    return {fieldBits(kFieldX, kFieldM, kFieldV) | (diffusion.active() ? fieldBit(kFieldRho) : 0u) |
                rateTermReads(terms),
            fieldBit(kFieldDrho)};
  }
};

// Defined here, instantiated once (src/instantiate_forces_*.cpp).
template <int D>
unsigned DensityRatePass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const {
  const bool blocks = kPairBlocksPay && pairBlocksAllowed() && !anyRateTermActive(terms) &&
                     isRowKernel(kernel);  // (the rows' kernels, below)
  const ParticlePrologue<D> prologue = pairArrays(P, false, diffusion.active(), blocks);
  DensityDiffusion<D> diffusionHere = diffusion;
  diffusionHere.volume = prologue.volume;
  const unsigned bits = std::visit(
      [&](const auto& k) {
        const ContinuityDensity rate{true};
        auto loop = [&](const auto& fluidRow, const auto& wallRow) {
          return runPairLoop(P, neighbours, k, k.support(),
                             std::tuple_cat(std::make_tuple(rate, diffusionHere), densityRateTermEvaluators(terms, k)),
                             std::make_tuple(rate), std::make_tuple(ContinuityDensity{walls.densityRates}),
                             DensityRateEpilogue<D>{}, DensityRateEpilogue<D>{},
                             PairLoopParts{walls.inSums, walls.densityRates}, NoGradientCorrection{}, prologue,
                             fluidRow, wallRow);
        };
        using K = std::decay_t<decltype(k)>;
        if constexpr (kPairBlocksPay && kRowKernel<K>) {
          const Real* m = realMasses(P, prologue);
          if (blocks && m && (diffusionHere.coefficient == 0 || diffusionHere.volume)) {
            // The wall neighbours: continuity alone (the diffusion is
            // between fluid particles), the wall pack's one term.
            return loop(DensityRateRow<D, K>{P, k, diffusionHere, m},
                        DensityRateRow<D, K, false>{P, k, diffusionHere, m});
          }
        }
        return loop(PairByPair{}, PairByPair{});
      },
      kernel);
  return bits | (walls.densityRates && P.hasWalls() ? term_bits::kDynamicWalls : 0u);
}

extern template struct DensityRatePass<2>;
extern template struct DensityRatePass<3>;

}  // namespace sph
