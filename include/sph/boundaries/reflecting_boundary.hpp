// Boundary "reflecting": damped reflecting walls on the faces of the domain
// box (damped_reflecting_walls.hpp), the seed scheme's boundary. No wall
// particles; the constraint clamps a particle at distance h from a wall and
// turns its normal velocity to -e times itself (e = restitution). Along a
// periodic axis the faces are at infinity. The seed model reflects every
// clamped particle (ReflectionRule::kSeed), a composed model only those
// moving into the wall.
#pragma once

#include "sph/boundaries/boundary.hpp"

#include <limits>

namespace sph {

inline bool composedModel(const CaseConfig& c);  // methods.hpp

struct ReflectingBoundary : NoWallsBoundary {
  static constexpr const char* name = "reflecting";
  static constexpr const char* summary =
      "damped reflecting walls: clamp at distance h, normal velocity -e times itself (the seed's)";
  static inline const std::vector<const char*> reads{"restitution"};
  static std::vector<KeySpec> keys() {
    return {{"restitution", KeyGroup::kPhysics, &CaseConfig::restitution, "",
             "Reflecting walls: the normal velocity becomes -e times itself", key_range::within(0, 1), nullptr, nullptr}};
  }

  template <int D>
  static WallConstraint<D> constraint(const ResolvedCase& c) {
    Vec<D> lo = toVec<D>(c.domainMin), hi = toVec<D>(c.domainMax);
    const unsigned periodic = periodicAxes(c);
    for (int d = 0; d < D; ++d)
      if ((periodic >> d) & 1u)
        lo[d] = -std::numeric_limits<Real>::infinity(), hi[d] = std::numeric_limits<Real>::infinity();
    return DampedReflectingWalls<D>{lo, hi, c.h, c.restitution,
                                    composedModel(c) ? ReflectionRule::kApproaching : ReflectionRule::kSeed};
  }
};

}  // namespace sph
