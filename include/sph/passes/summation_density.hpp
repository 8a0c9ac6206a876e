// Pass: summation density, with the equation of state fused into it.
//
//   rho_i = sum_j m_j W(|x_i - x_j|)   (self term included), then p_i = p(rho_i)
//   and c_i = c(rho_i) when the particles carry a sound speed.
//
// Over the fluid particles, with every neighbour (fluid and wall) in the
// sum. The kernel is seen as a function of r^2 (density(r2) and
// densityAtZero()); the seed scheme's density kernel has that form itself.
#pragma once

#include "sph/boundaries/wall_sums.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/kernels/seed_kernels.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/terms/summation_density.hpp"
#include "sph/terms/term_bits.hpp"

#include <cmath>
#include <variant>

namespace sph {

template <int D>
using DensityKernelChoice =
    std::variant<SeedKernels, DensityKernel<CubicSpline<D>>, DensityKernel<WendlandC2<D>>,
                 DensityKernel<Gaussian<D>>, DensityKernel<Muller<D>>>;

template <int D>
struct SummationDensityPass {
  static constexpr const char* name = "summation_density";
  DensityKernelChoice<D> kernel;
  EquationOfState eos;
  WallSums walls{};            // what the walls add (not repulsive walls)
  bool clampNegative = false;  // negative_pressure = clamp

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const;
  // run() reads the neighbours' x and m; writes the fluid's rho, p and c
  // (fields.hpp: FieldAccess).
  FieldAccess fields(const StepContext&) const {
    return {fieldBits(kFieldX, kFieldM), fieldBits(kFieldRho, kFieldP, kFieldC)};
  }
};

// Defined here, instantiated once (src/instantiate_*.cpp).
template <int D>
unsigned SummationDensityPass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const {
  computeSummationDensity(P, neighbours, kernel, eos, walls.inSums, clampNegative);
  return term_bits::kSummationDensity | term_bits::kEquationOfState;
}

extern template struct SummationDensityPass<2>;
extern template struct SummationDensityPass<3>;

}  // namespace sph
