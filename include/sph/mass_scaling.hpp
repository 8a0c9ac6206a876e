// Mass scaling to the rest density (seed scheme): with unit masses compute
// rho_i by summation, then give every particle m = N rho0 / sum_i rho_i, so
// that the mean summation density equals rho0 exactly.
#pragma once

#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"

#include <algorithm>

namespace sph {

// The neighbour list must be built on P.x. Returns the mass.
template <int D, class Model>
Real scaleMassToRestDensity(Particles<D>& P, const NeighbourList<D>& neighbours,
                            const Model& model) {
  std::fill(P.m.begin(), P.m.end(), Real(1));
  model.computeDensity(P, neighbours);
  Real sum = 0;
  for (std::size_t i = 0; i < P.size(); ++i) sum += P.rho[i];  // owned: no ghosts
  const Real m = static_cast<Real>(P.size()) * model.restDensity() / sum;
  std::fill(P.m.begin(), P.m.end(), m);
  return m;
}

}  // namespace sph
