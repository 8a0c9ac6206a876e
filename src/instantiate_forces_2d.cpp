// The wcsph force pass in 2D, compiled once for the program: its pair loop is
// instantiated per kernel x viscosity x separation x gradient correction, and
// every other translation unit sees only the declaration of run()
// (extern template in wcsph_forces.hpp).
#include "sph/passes/wcsph_forces.hpp"

namespace sph {
template struct WcsphForcePass<2>;
}  // namespace sph
