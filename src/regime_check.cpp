// The regime check's measurement (regime_check.hpp): one walk over the
// fluid particles' neighbours, its maxima and counts reduced over the
// threads and the ranks. Instantiated here for 2D and 3D.
#include "sph/regime_check.hpp"

#include "sph/neighbour_walk.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace sph {

template <int D>
RegimeState measureRegime(const Particles<D>& P, const NeighbourList<D>& neighbours, Real cRef, Real dx, Real rho0,
                          Real support, const mpi::Communicator& comm) {
  // (A list with a Verlet skin holds pairs beyond the support: not counted.)
  const Real support2 = support * support;
  const std::size_t nFluid = P.fluidCount();
  const Real close2 = dx > 0 ? 0.04 * dx * dx : 0;
  // This thread's maxima and counts; merged: the largest, the sums.
  struct Tally {
    Real v2 = 0, rhoMax = 0, rhoMin = std::numeric_limits<Real>::infinity();
    std::size_t isolated = 0, paired = 0, pairs = 0;
    void operator+=(const Tally& o) {
      v2 = std::max(v2, o.v2);
      rhoMax = std::max(rhoMax, o.rhoMax);
      rhoMin = std::min(rhoMin, o.rhoMin);
      isolated += o.isolated, paired += o.paired, pairs += o.pairs;
    }
  };
  const Tally t = walkNeighbours<Tally>(
      P, neighbours, P.range(ParticleRange::kFluid), [&](std::size_t i, const NeighbourRow<D>& row, Tally& mine) {
        mine.v2 = std::max(mine.v2, P.v[i].squaredNorm());
        mine.rhoMax = std::max(mine.rhoMax, P.rho[i]);
        mine.rhoMin = std::min(mine.rhoMin, P.rho[i]);
        std::size_t count = 0;
        bool close = false;
        row.forEach([&](std::uint32_t, const Vec<D>& rij) {
          const Real r2 = rij.squaredNorm();
          count += r2 < support2;
          close |= r2 < close2;
        });
        mine.pairs += count;
        mine.isolated += count == 0;
        mine.paired += close;
      });
  Real v2 = t.v2, rhoMax = t.rhoMax, rhoMin = t.rhoMin;
  std::size_t isolated = t.isolated, paired = t.paired, pairs = t.pairs;
  // Over every rank's fluid (no MPI call on one rank); the least as minus
  // the largest of its negative.
  double highest[3] = {v2, rhoMax, -rhoMin};
  mpi::allMax(comm, highest, 3);
  v2 = highest[0], rhoMax = highest[1], rhoMin = -highest[2];
  std::int64_t counts[4] = {static_cast<std::int64_t>(nFluid), static_cast<std::int64_t>(isolated),
                            static_cast<std::int64_t>(paired), static_cast<std::int64_t>(pairs)};
  mpi::allSum(comm, counts, 4);
  const auto fluidAll = static_cast<std::size_t>(counts[0]);
  isolated = static_cast<std::size_t>(counts[1]), paired = static_cast<std::size_t>(counts[2]),
  pairs = static_cast<std::size_t>(counts[3]);
  RegimeState s;
  s.maxSpeed = std::sqrt(v2);
  s.mach = cRef > 0 ? s.maxSpeed / cRef : 0;
  s.densityMax = rho0 > 0 ? rhoMax / rho0 : 0;
  s.densityMin = rhoMin;
  if (fluidAll > 0) {
    const Real n = static_cast<Real>(fluidAll);
    s.isolatedFraction = static_cast<Real>(isolated) / n;
    s.meanNeighbours = static_cast<Real>(pairs) / n;
    s.pairedFraction = static_cast<Real>(paired) / n;
  }
  return s;
}

template RegimeState measureRegime<2>(const Particles<2>&, const NeighbourList<2>&, Real, Real, Real, Real,
                                      const mpi::Communicator&);
template RegimeState measureRegime<3>(const Particles<3>&, const NeighbourList<3>&, Real, Real, Real, Real,
                                      const mpi::Communicator&);

}  // namespace sph
