// Uniform gravity: F_g,i = -rho_i g e_up, i.e. a_i = -g e_up, where "up" is
// the last axis (y in 2D, z in 3D).
#pragma once

#include "sph/terms/term_bits.hpp"

#include "sph/particles.hpp"

namespace sph {

template <int D>
struct UniformGravity {
  static constexpr unsigned bit = term_bits::kGravity;
  Real g;

  Vec<D> acceleration(std::size_t, const Particles<D>&) const { return vector(); }

  // The gravity vector, -g e_up.
  Vec<D> vector() const {
    Vec<D> a = Vec<D>::Zero();
    a[verticalAxis<D>] = -g;
    return a;
  }

  // Potential energy of particle i: m g y.
  Real potential(std::size_t i, const Particles<D>& P) const {
    return P.m[i] * g * P.x[i][verticalAxis<D>];
  }
};

}  // namespace sph
