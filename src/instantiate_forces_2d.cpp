// The wcsph force pass and the density-rate pass in 2D, compiled once for
// the program: their pair loops are instantiated per kernel (x viscosity
// for the forces), and every other translation unit sees only the
// declarations of run() (extern template in wcsph_forces.hpp and
// density_rate.hpp).
#include "sph/passes/density_rate.hpp"
#include "sph/passes/wcsph_forces.hpp"

namespace sph {
template struct WcsphForcePass<2>;
template struct DensityRatePass<2>;
}  // namespace sph
