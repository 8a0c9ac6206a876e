// Uniform body acceleration: a_i = g, a constant vector (any direction).
// The case key `gravity` gives it as D values; the scalar key `g` is the
// shorthand g = -g e_up, "up" the last axis (y in 2D, z in 3D).
#pragma once

#include "sph/terms/term_bits.hpp"

#include "sph/particles.hpp"

namespace sph {

template <int D>
struct UniformGravity {
  static constexpr unsigned bit = term_bits::kGravity;
  Vec<D> g;

  // -g e_up: the scalar shorthand.
  static UniformGravity down(Real g) {
    Vec<D> a = Vec<D>::Zero();
    a[verticalAxis<D>] = -g;
    return {a};
  }

  Vec<D> acceleration(std::size_t, const Particles<D>&) const { return g; }

  // The gravity vector.
  Vec<D> vector() const { return g; }

  // Potential energy of particle i: -m g . x (m g y for gravity along -y;
  // the zero components add nothing, so that product is formed as before).
  Real potential(std::size_t i, const Particles<D>& P) const {
    Real e = 0;
    for (int d = 0; d < D; ++d)
      if (g[d] != 0) e += P.m[i] * (-g[d]) * P.x[i][d];
    return e;
  }
};

}  // namespace sph
