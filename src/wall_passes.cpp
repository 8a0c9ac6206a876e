// The run() of the wall-particle boundaries' passes (passes/wall_passes.hpp),
// compiled for D = 2 and 3.
#include "sph/passes/wall_passes.hpp"

#include "sph/boundaries/dummy_adami2012.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/pair_loop.hpp"
#include "sph/terms/term_bits.hpp"

#include <variant>

namespace sph {

template <int D>
unsigned AdamiWallsPass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const {
  const WallAcceleration<D> moving =
      motion ? WallAcceleration<D>{motion->firstId, motion->endId, motion->acceleration(ctx.time)}
             : WallAcceleration<D>{};
  std::visit(
      [&](const auto& k, const auto& e) {
        extrapolateToWalls(P, neighbours, k, e, bodyAcceleration, noSlip, rho0, moving);
      },
      kernel, eos);
  return term_bits::kAdamiWalls;
}

// The walls' force on each fluid particle from its wall neighbours
// (repulsive_liu2012.hpp).
template <int D>
unsigned RepulsiveWallsPass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const {
  {
    const std::size_t nFluid = P.fluidCount();
#pragma omp parallel for schedule(static) if (nFluid >= kMinParallelSize)
    for (std::size_t i = 0; i < nFluid; ++i) {
      Vec<D> a = Vec<D>::Zero();
      forEachNeighbourSeparationByKind(
          P, neighbours, i, [](std::uint32_t, const Vec<D>&) {},
          [&](std::uint32_t, const Vec<D>& rij) { a += force.factor(rij.norm()) * rij; });
      P.a[i] += a;
    }
  }
  return term_bits::kRepulsiveWalls;
}

template struct AdamiWallsPass<2>;
template struct AdamiWallsPass<3>;
template struct RepulsiveWallsPass<2>;
template struct RepulsiveWallsPass<3>;

}  // namespace sph
