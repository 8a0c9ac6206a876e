// Shepard density re-initialisation: the zeroth-order corrected kernel
// W~_ij = W_ij / sum_k V_k W_ik (Shepard 1968; in SPH as the density filter
// of Colagrossi & Landrieu 2003, J. Comput. Phys. 191, 448, sec. 3.2 and
// Randles & Libersky 1996), applied to the density every N steps:
//
//   rho_i <- sum_j m_j W_ij / sum_j (m_j / rho_j) W_ij      (self term included)
//
// A constant density is kept exactly, whatever the particle arrangement and
// however truncated the support (free surface, wall); a linear one is not
// (zeroth order: the error is grad rho . (x_i - centroid of the weights)).
// The new densities are written to rhoReinit first (gather form: rho_j is
// read while other threads compute), then replace rho, and p (and c) follow
// from the equation of state.
//
// Over the fluid particles, and in the wcsph model over their fluid
// neighbours only (wallsInSums = false): walls contribute nothing, the
// normalisation makes up for the missing part of the support. Between steps
// a dummy wall's density is not the extrapolated one it has inside an
// evaluation, a dynamic wall's is clamped at rho0, a repulsive wall has
// none; with them in the sums the tank's bottom layer was pulled towards
// rho0 and leaked through the floor. (wallsInSums = true takes the walls'
// rho as they stand, for the tests.) Walls are never re-initialised. It runs after a step
// (Model::afterStep) on the finished state, so every integrator sees the
// corrected density as its state; its neighbour list is the step's last,
// built at x^{n+1} for leap-frog and the Euler schemes (RK4: at its fourth
// stage, a pair leaving the support is then counted with W ~ 0).
#pragma once

#include "sph/boundaries/wall_sums.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/neighbour_walk.hpp"
#include "sph/particles.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/terms/term_bits.hpp"

#include <variant>

namespace sph {

// Whether a re-initialisation runs after step `step`: every `every` steps.
inline bool reinitDue(const StepContext& ctx, long every) { return every > 0 && ctx.step > 0 && ctx.step % every == 0; }

// The Shepard density of fluid particle i: sum m_j W_ij / sum V_j W_ij,
// from its row (r_ij = x_i - x_j; a neighbour across a periodic face is a
// ghost).
template <int D, class K>
inline Real shepardDensity(const NeighbourRow<D>& row, const Particles<D>& P, const K& kernel, bool wallsInSums) {
  const std::size_t i = row.index();
  const Real W0 = kernel.W(0);
  Real sumMW = P.m[i] * W0, sumVW = P.m[i] / P.rho[i] * W0;
  row.forEachSummed(wallsInSums, [&](std::uint32_t j, const Vec<D>& rij) {
    const Real W = kernel.W(rij.norm());
    sumMW += P.m[j] * W;
    sumVW += P.m[j] / P.rho[j] * W;
  });
  return sumMW / sumVW;
}

// rho <- rhoReinit over the fluid, then the equation of state.
template <int D>
inline void applyReinitialisedDensity(Particles<D>& P, const EquationOfState& eos, bool clampNegative) {
  const std::size_t n = P.fluidCount();
  for (std::size_t i = 0; i < n; ++i) P.rho[i] = P.rhoReinit[i];
  std::visit([&](const auto& e) { computePressure(P, e, n, clampNegative); }, eos);
}

// What a density re-initialisation (Shepard's, MLS) reads and writes: on
// the steps it is due, x, m and rho of the neighbours; rhoReinit and, by
// applyReinitialisedDensity(), the fluid's rho, p and c. Else nothing.
inline FieldAccess reinitFields(const StepContext& ctx, long every) {
  if (!reinitDue(ctx, every)) return {};
  return {fieldBits(kFieldX, kFieldM, kFieldRho), fieldBits(kFieldRhoReinit, kFieldRho, kFieldP, kFieldC)};
}

template <int D>
struct ShepardDensityPass {
  static constexpr const char* name = "shepard_density";
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
unsigned ShepardDensityPass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const {
  if (!reinitDue(ctx, every)) return 0;
  const std::size_t n = P.fluidCount();
  walkNeighbours(P, neighbours, P.range(ParticleRange::kFluid), kernel,
                 [&](std::size_t i, const NeighbourRow<D>& row, const auto& k) {
                   P.rhoReinit[i] = shepardDensity(row, P, k, walls.inSums);
                 });
  applyReinitialisedDensity(P, eos, clampNegative);
  if (ctx.counts) {
    ++ctx.counts->reinitSteps;
    ctx.counts->reinitParticles += static_cast<long>(n);
  }
  return term_bits::kShepardDensity;
}

extern template struct ShepardDensityPass<2>;
extern template struct ShepardDensityPass<3>;

}  // namespace sph
