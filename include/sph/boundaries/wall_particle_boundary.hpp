// What the three wall-particle boundaries (dummy, dynamic, repulsive) share:
// they make wall particles around the box and the obstacles
// (wall_particles.cpp), the wall guard is their per-particle constraint
// (wall_guard.hpp, key wall_guard), and the state check knows a fluid
// particle outside the box or inside an obstacle went through a wall (within
// half a spacing). Each boundary type derives from it and states what differs.
#pragma once

#include "sph/boundaries/boundary.hpp"
#include "sph/wall_particles.hpp"

#include <string>
#include <vector>

namespace sph {

// The case's obstacle boxes (obstacle_min/obstacle_max), in order.
template <int D>
std::vector<AxisBox<D>> obstacleBoxes(const CaseConfig& c) {
  std::vector<AxisBox<D>> boxes;
  for (std::size_t k = 0; k + D <= c.obstacleMin.size() && k + D <= c.obstacleMax.size(); k += D)
    boxes.push_back({toVec<D>({c.obstacleMin.begin() + k, c.obstacleMin.begin() + k + D}),
                     toVec<D>({c.obstacleMax.begin() + k, c.obstacleMax.begin() + k + D})});
  return boxes;
}

// The guard at the wall particles' surfaces: the faces of the domain box
// that have walls (not periodic, not an open top) and every obstacle box.
template <int D>
WallGuard<D> makeWallGuard(const ResolvedCase& c) {
  WallGuard<D> guard;
  const unsigned periodic = periodicAxes(c);
  for (int d = 0; d < D; ++d) {
    if ((periodic >> d) & 1u) continue;
    guard.lo[d] = c.domainMin[static_cast<std::size_t>(d)];
    if (d < D - 1 || c.lid) guard.hi[d] = c.domainMax[static_cast<std::size_t>(d)];
  }
  guard.obstacles = obstacleBoxes<D>(c);
  guard.paddle = static_cast<int>(c.paddle) - 1;
  return guard;
}

// Layers of wall particles behind the surface (dummy, dynamic): as many as
// the kernel support needs, unless wall_layers_override allows fewer.
inline void validateWallLayers(const CaseConfig& c) {
  if (!c.walls) return;
  const int needed = wallLayersNeeded(c);
  if (c.wallLayers > 0 && c.wallLayers < needed && !c.wallLayersOverride)
    throw CaseError("wall_layers = " + std::to_string(c.wallLayers) + " is too few: the kernel support (" + c.kernel +
                    ", h = " + std::to_string(c.h) + ", spacing = " + std::to_string(c.spacing) + ") needs " +
                    std::to_string(needed) +
                    " layers (give wall_layers_override = true to run with fewer, and see the fluid leak)");
}

struct WallParticleBoundary : NoWallsBoundary {
  static constexpr WallLattice kParticles = WallLattice::kLayers;

  template <int D>
  static WallConstraint<D> constraint(const ResolvedCase& c) {
    if (!c.wallGuard) return {};
    return WallConstraint<D>(makeWallGuard<D>(c));
  }

  // (The paddle moves: fluid inside it is not looked for.)
  template <int D>
  static void stateCheck(StateCheck<D>& check, const ResolvedCase& c) {
    check.wallParticles = true;
    check.tolerance = c.spacing / 2;
    check.openTop = !c.lid;
    const auto boxes = obstacleBoxes<D>(c);
    for (std::size_t k = 0; k < boxes.size(); ++k)
      if (static_cast<long>(k) + 1 != c.paddle) check.obstacles.push_back(boxes[k]);
  }
};

}  // namespace sph
