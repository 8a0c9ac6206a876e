// Damped reflecting walls of a box [lo, hi] (the seed scheme's boundary).
//
// A particle closer than `distance` (= h) to a wall is put back at that
// distance and its normal velocity becomes -e times itself (e = restitution
// in [0, 1]). Both the half-step and the integer-time velocities are
// reflected, so leap-frog stays consistent. Two rules for which particles
// are reflected:
//   kSeed         every clamped particle (the seed document and its C++:
//                 `if (x < h) { x = h; u = -e u; }`), used by seed_wcsph;
//   kApproaching  only a particle moving into the wall; one already moving
//                 away keeps its velocity, since flipping it would drive it
//                 back into the wall (used by wcsph).
#pragma once

#include "sph/particles.hpp"

namespace sph {

enum class ReflectionRule { kSeed, kApproaching };

template <int D>
struct DampedReflectingWalls {
  Vec<D> lo, hi;
  Real distance;
  Real restitution;
  ReflectionRule rule = ReflectionRule::kApproaching;

  // Particle i, right after its position update (integrator_support.hpp).
  void operator()(Particles<D>& P, std::size_t i) const {
    for (int d = 0; d < D; ++d) {
      const Real lower = lo[d] + distance, upper = hi[d] - distance;
      if (P.x[i][d] < lower) {
        P.x[i][d] = lower;
        reflect(P, i, d, -1);
      } else if (P.x[i][d] > upper) {
        P.x[i][d] = upper;
        reflect(P, i, d, +1);
      }
    }
  }

  // Would the walls move a particle at x (closer than `distance` to one)?
  bool clamps(const Vec<D>& x) const {
    return (x.array() - lo.array()).minCoeff() < distance || (hi.array() - x.array()).minCoeff() < distance;
  }

 private:
  // outward: -1 for a lower wall, +1 for an upper wall.
  void reflect(Particles<D>& P, std::size_t i, int d, int outward) const {
    const bool always = rule == ReflectionRule::kSeed;
    if (!P.vHalf.empty() && (always || P.vHalf[i][d] * outward > 0)) P.vHalf[i][d] *= -restitution;
    if (!P.vPrev.empty() && (always || P.vPrev[i][d] * outward > 0)) P.vPrev[i][d] *= -restitution;
    if (always || P.v[i][d] * outward > 0) P.v[i][d] *= -restitution;
  }
};

}  // namespace sph
