// The body forces of a model, added to each particle's acceleration in the
// epilogue of the pair loop, in this order: gravity, the toy star's
// attraction (linear damping, an optional term, follows them:
// terms/linear_damping.hpp). Each is optional (a coefficient of 0 builds
// none); an absent one costs one predictable branch per particle, not per
// pair, and no instantiation of the pair loop.
#pragma once

#include "sph/terms/star_attraction.hpp"
#include "sph/terms/uniform_gravity.hpp"

#include <optional>

namespace sph {

template <int D>
struct BodyForces {
  std::optional<UniformGravity<D>> gravity;
  std::optional<StarAttraction<D>> star;

  void add(std::size_t i, const Particles<D>& P, Vec<D>& a) const {
    if (gravity) a += gravity->acceleration(i, P);
    if (star) a += star->acceleration(i, P);
  }

  // The fields add() reads: the star's x (gravity none).
  FieldSet reads() const { return star ? fieldBit(kFieldX) : 0u; }

  // The bits of the forces present (term_bits.hpp).
  unsigned bits() const {
    return (gravity ? UniformGravity<D>::bit : 0u) | (star ? StarAttraction<D>::bit : 0u);
  }

  // Potential energy of the conservative ones (gravity, star).
  Real potential(const Particles<D>& P) const {
    Real e = 0;
    for (std::size_t i = 0; i < P.fluidCount(); ++i) {
      if (gravity) e += gravity->potential(i, P);
      if (star) e += star->potential(i, P);
    }
    return e;
  }
};

}  // namespace sph
