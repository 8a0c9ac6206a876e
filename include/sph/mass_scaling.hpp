// Mass scaling to the rest density (seed scheme): with unit masses compute
// rho_i by summation, then give every particle m = N rho0 / sum_i rho_i, so
// that the mean summation density equals rho0 exactly. On several MPI ranks
// N and the sum are every rank's (the halos, filled with unit masses too,
// give each owned particle its whole sum).
#pragma once

#include "sph/mpi/collectives.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"

#include <algorithm>

namespace sph {

// The neighbour list must be built on P.x. Returns the mass.
template <int D, class Model>
Real scaleMassToRestDensity(Particles<D>& P, const NeighbourList<D>& neighbours,
                            const Model& model, const mpi::Communicator& comm = {}) {
  std::fill(P.m.begin(), P.m.end(), Real(1));
  model.computeDensity(P, neighbours);
  Real sum = 0;
  for (std::size_t i = 0; i < P.size(); ++i) sum += P.rho[i];  // owned: no ghosts
  const auto n = mpi::allSum(comm, static_cast<std::int64_t>(P.size()));
  const Real m = static_cast<Real>(n) * model.restDensity() / mpi::allSum(comm, sum);
  std::fill(P.m.begin(), P.m.end(), m);
  return m;
}

}  // namespace sph
