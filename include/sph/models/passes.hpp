// The passes a model is made of (one value type each, in passes/), as one
// variant: a model holds an ordered list of them.
#pragma once

#include "sph/passes/cspm_correction.hpp"
#include "sph/passes/colour_field.hpp"
#include "sph/passes/density_rate.hpp"
#include "sph/passes/equation_of_state.hpp"
#include "sph/passes/mls_density.hpp"
#include "sph/passes/shepard_density.hpp"
#include "sph/passes/seed_forces.hpp"
#include "sph/passes/summation_density.hpp"
#include "sph/passes/wall_passes.hpp"
#include "sph/passes/wcsph_forces.hpp"

#include <variant>

namespace sph {

template <int D>
using Pass = std::variant<SummationDensityPass<D>, EquationOfStatePass<D>, AdamiWallsPass<D>, SeedForcePass<D>,
                          WcsphForcePass<D>, RepulsiveWallsPass<D>, CspmCorrectionPass<D>, ShepardDensityPass<D>,
                          MlsDensityPass<D>, ColourFieldPass<D>, DensityRatePass<D>>;

// The fields a pass reads and writes at this step (its fields(), declared
// next to its run(); fields.hpp: FieldAccess).
template <int D>
FieldAccess passFields(const Pass<D>& pass, const StepContext& ctx) {
  return std::visit([&](const auto& p) { return p.fields(ctx); }, pass);
}

}  // namespace sph
