// Boundary "repulsive": one layer of wall particles on the wall surface at
// spacing dx/2, which take no part in the SPH sums and push the fluid away
// with a soft repulsive force after the forces (seed document 004, after
// Liu et al. 2012; the force in repulsive_liu2012.hpp).
#pragma once

#include "sph/boundaries/wall_particle_boundary.hpp"
#include "sph/passes/wall_passes.hpp"

namespace sph {

struct RepulsiveBoundary : WallParticleBoundary {
  static constexpr const char* name = "repulsive";
  static constexpr const char* summary =
      "one layer of repulsive particles at dx/2 on the wall (seed document 004, after Liu et al. 2012)";
  static constexpr WallLattice kParticles = WallLattice::kOnSurface;
  static constexpr WallSums kSums{false, false};
  static inline const std::vector<const char*> reads{"lid", "wall_guard", "obstacle_min", "obstacle_max"};

  template <int D>
  static void afterForces(BoundaryBuild<D>& b) {
    b.passes.push_back(makePass(RepulsiveWallsPass<D>{RepulsiveForce{b.c0 * b.c0, b.spacing, b.h}}));
    b.info.termNames.push_back("repulsive_walls_liu2012");
  }
};

}  // namespace sph
