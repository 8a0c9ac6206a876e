// Mass scaling to the rest density (seed scheme): with unit masses compute
// rho_i by summation, then give every particle m = N rho0 / sum_i rho_i, so
// that the mean summation density equals rho0 exactly. On several MPI ranks
// N and the sum are every rank's (the halos, filled with unit masses too,
// give each owned particle its whole sum), the sum added in the order of the
// ids, so that the mass is the same double on any number of ranks > 1.
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
  if (comm.size > 1) {
    std::vector<mpi::ById<Real>> mine(P.size());
    for (std::size_t i = 0; i < P.size(); ++i) mine[i] = {P.id[i], P.rho[i]};
    for (const auto& r : mpi::allGatherById(comm, mine)) sum += r.value;
  } else {
    for (std::size_t i = 0; i < P.size(); ++i) sum += P.rho[i];  // owned: no ghosts (the seed's order)
  }
  const auto n = mpi::allSum(comm, static_cast<std::int64_t>(P.size()));
  const Real m = static_cast<Real>(n) * model.restDensity() / sum;
  std::fill(P.m.begin(), P.m.end(), m);
  return m;
}

}  // namespace sph
