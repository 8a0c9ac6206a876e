// The run() of the wall-particle boundaries' passes (passes/wall_passes.hpp),
// compiled for D = 2 and 3.
#include "sph/passes/wall_passes.hpp"

#include "sph/boundaries/dummy_adami2012.hpp"
#include "sph/neighbour_walk.hpp"
#include "sph/terms/term_bits.hpp"

#include <algorithm>

namespace sph {

template <int D>
unsigned AdamiWallsPass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const {
  const WallAcceleration<D> moving =
      motion ? WallAcceleration<D>{motion->firstId, motion->endId, motion->acceleration(ctx.time)}
             : WallAcceleration<D>{};
  extrapolateToWalls(P, neighbours, kernel, *eos, bodyAcceleration, noSlip, rho0, moving);
  return term_bits::kAdamiWalls;
}

// A dynamic wall shows the viscous term its own velocity (a paddle's
// moves; a fixed wall's is 0).
template <int D>
unsigned DynamicWallVelocityPass<D>::run(Particles<D>& P, const NeighbourList<D>&, const StepContext&) const {
  const IndexRange walls = P.range(ParticleRange::kWalls);
  std::copy(P.v.begin() + static_cast<std::ptrdiff_t>(walls.begin), P.v.begin() + static_cast<std::ptrdiff_t>(walls.end),
            P.vWall.begin() + static_cast<std::ptrdiff_t>(walls.begin));
  return 0;
}

// The walls' force on each fluid particle from its wall neighbours
// (repulsive_liu2012.hpp).
template <int D>
unsigned RepulsiveWallsPass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const {
  walkNeighbours(P, neighbours, P.range(ParticleRange::kFluid), [&](std::size_t i, const NeighbourRow<D>& row) {
    Vec<D> a = Vec<D>::Zero();
    row.forEachWall([&](std::uint32_t, const Vec<D>& rij) { a += force.factor(rij.norm()) * rij; });
    P.a[i] += a;
  });
  return term_bits::kRepulsiveWalls;
}

template struct AdamiWallsPass<2>;
template struct AdamiWallsPass<3>;
template struct DynamicWallVelocityPass<2>;
template struct DynamicWallVelocityPass<3>;
template struct RepulsiveWallsPass<2>;
template struct RepulsiveWallsPass<3>;

}  // namespace sph
