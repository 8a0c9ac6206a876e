// Linear attraction of the toy star: a_i = -lambda x_i (a fixed external
// potential Phi = lambda |x|^2 / 2 standing in for self-gravity; Monaghan &
// Price 2004, "Toy stars in one dimension", and Mocz's toy-star tutorial).
// The potential is centred at the origin, whatever star_center says.
// lambda follows from the star's mass, radius, k, n and the dimension (toy_star.hpp).
#pragma once

#include "sph/terms/term_bits.hpp"

#include "sph/particles.hpp"

namespace sph {

template <int D>
struct StarAttraction {
  static constexpr unsigned bit = term_bits::kStarAttraction;
  Real lambda;

  Vec<D> acceleration(std::size_t i, const Particles<D>& P) const { return -lambda * P.x[i]; }
  Real potential(std::size_t i, const Particles<D>& P) const {
    return 0.5 * lambda * P.m[i] * P.x[i].squaredNorm();
  }
};

}  // namespace sph
