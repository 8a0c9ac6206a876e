// Pass: the equation of state p_i = p(rho_i) (and c_i = c(rho_i) when the
// particles carry a sound speed) over particles [begin, end): the fluid, or
// every particle when walls carry a density of their own (dynamic walls).
// Used when density is a state variable (continuity density); summation
// density applies the EOS itself. Dynamic wall particles never pull: their
// density is kept >= rho0 first (as DualSPHysics does), so their pressure
// is >= 0 and a free surface next to a wall does not stick to it.
#pragma once

#include "sph/boundaries/wall_sums.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/terms/term_bits.hpp"

#include <algorithm>

namespace sph {

template <int D>
struct EquationOfStatePass {
  static constexpr const char* name = "equation_of_state";
  EquationOfState eos;
  WallSums walls{};            // densityRates: the wall particles carry a density (dynamic walls)
  bool clampNegative = false;  // negative_pressure = clamp

  Real rho0 = 0;               // walls: the least density they may have

  unsigned run(Particles<D>& P, const NeighbourList<D>&, const StepContext&) const;
  // run() reads rho; writes p and c (and the dynamic walls' rho, clamped).
  FieldAccess fields(const StepContext&) const {
    return {fieldBit(kFieldRho), fieldBits(kFieldP, kFieldC) | (walls.densityRates ? fieldBit(kFieldRho) : 0u)};
  }
};

// Defined here, instantiated once (src/instantiate_*.cpp).
template <int D>
unsigned EquationOfStatePass<D>::run(Particles<D>& P, const NeighbourList<D>&, const StepContext&) const {
  const std::size_t n = walls.densityRates ? P.size() : P.fluidCount();
  if (walls.densityRates)
    for (std::size_t i = P.fluidCount(); i < n; ++i) P.rho[i] = std::max(P.rho[i], rho0);
  std::visit([&](const auto& e) { computePressure(P, e, n, clampNegative); }, eos);
  return term_bits::kEquationOfState;
}

extern template struct EquationOfStatePass<2>;
extern template struct EquationOfStatePass<3>;

}  // namespace sph
