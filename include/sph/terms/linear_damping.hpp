// Linear damping a_i = -nu v_i: drains kinetic energy so a scene relaxes to
// equilibrium (the toy star's relaxation).
#pragma once

#include "sph/terms/term_bits.hpp"

#include "sph/particles.hpp"

namespace sph {

template <int D>
struct LinearDamping {
  static constexpr unsigned bit = term_bits::kDamping;
  Real nu;

  Vec<D> acceleration(std::size_t i, const Particles<D>& P) const { return -nu * P.v[i]; }
};

}  // namespace sph
