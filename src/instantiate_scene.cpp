// Scene<D> in 2D and 3D, compiled once for the program: its step (the
// integrators' advance, the state check's loop, shifting and wall motion),
// sort and evaluate are instantiated here, and every other translation unit
// sees only their declarations (extern template in scene.hpp).
#include "sph/scene.hpp"

namespace sph {
template class Scene<2>;
template class Scene<3>;
}  // namespace sph
