// Model<D>'s members that evaluate its equation of state and body forces
// (models/model.hpp holds them by pointer, declared only), and the model
// compiled once for D = 2 and 3.
#include "sph/models/model.hpp"

#include "sph/terms/body_forces.hpp"
#include "sph/terms/equation_of_state.hpp"

#include <algorithm>
#include <variant>

namespace sph {

template <int D>
Real Model<D>::potentialEnergy(const Particles<D>& P) const {
  return info_.bodies ? info_.bodies->potential(P) : Real(0);
}

template <int D>
Real Model<D>::regimeSoundSpeed() const {
  if (std::holds_alternative<PolytropicEos>(*info_.eos)) return 0;
  return std::visit([&](const auto& eos) { return eos.soundSpeed(info_.restDensity); }, *info_.eos);
}

template <int D>
Real Model<D>::regimeDensity() const {
  return std::holds_alternative<TaitEos>(*info_.eos) ? info_.restDensity : 0;
}

template <int D>
Real Model<D>::maxSoundSpeed(Real rhoMin, Real rhoMax) const {
  return std::visit([&](const auto& eos) { return std::max(eos.soundSpeed(rhoMin), eos.soundSpeed(rhoMax)); },
                    *info_.eos);
}

template class Model<2>;
template class Model<3>;

}  // namespace sph
