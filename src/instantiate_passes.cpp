// The model passes other than the wcsph force pass, the density-rate pass
// and the wall passes, in 2D and 3D, compiled once for the program; every
// other translation unit sees only the declarations of their run() (extern
// template in each pass's header).
#include "sph/passes/colour_field.hpp"
#include "sph/passes/cspm_correction.hpp"
#include "sph/passes/equation_of_state.hpp"
#include "sph/passes/mls_density.hpp"
#include "sph/passes/seed_forces.hpp"
#include "sph/passes/shepard_density.hpp"
#include "sph/passes/summation_density.hpp"

namespace sph {
template struct SummationDensityPass<2>;
template struct SummationDensityPass<3>;
template struct EquationOfStatePass<2>;
template struct EquationOfStatePass<3>;
template struct SeedForcePass<2>;
template struct SeedForcePass<3>;
template struct CspmCorrectionPass<2>;
template struct CspmCorrectionPass<3>;
template struct ShepardDensityPass<2>;
template struct ShepardDensityPass<3>;
template struct MlsDensityPass<2>;
template struct MlsDensityPass<3>;
template struct ColourFieldPass<2>;
template struct ColourFieldPass<3>;
}  // namespace sph
