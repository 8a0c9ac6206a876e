// The checks of the fluid bodies (called by validateCase): any number of
// lattice blocks and discs/balls, each with its own velocity; counts of the
// coordinate lists; two fluid bodies that overlap are refused naming both
// (a fluid body in a solid one is refused by the particle sources, which
// know the particles); and the particle count they give, bounded before
// anything is allocated.
#include "sph/case_config.hpp"
#include "sph/io/number_format.hpp"

#include <cmath>
#include <string>

namespace sph {

namespace {

void requireMultiple(const char* key, const std::vector<Real>& v, std::size_t per, const char* what) {
  if (v.size() % per != 0)
    throw CaseError(std::string(key) + " has " + std::to_string(v.size()) + " values: it needs " +
                    std::to_string(per) + " per " + what);
  for (Real x : v)
    if (!std::isfinite(x)) throw CaseError(std::string(key) + " must hold finite numbers");
}

struct Body {
  std::string name;
  bool disc;
  std::vector<Real> lo, hi;  // block corners, or the disc's centre in lo
  Real radius = 0;
};

// Interiors overlap (bodies that only touch, like two blocks side by side, may).
bool overlap(const Body& a, const Body& b, std::size_t D) {
  if (!a.disc && !b.disc) {
    for (std::size_t d = 0; d < D; ++d)
      if (!(a.lo[d] < b.hi[d] && b.lo[d] < a.hi[d])) return false;
    return true;
  }
  if (a.disc && b.disc) {
    Real r2 = 0;
    for (std::size_t d = 0; d < D; ++d) r2 += (a.lo[d] - b.lo[d]) * (a.lo[d] - b.lo[d]);
    return std::sqrt(r2) < a.radius + b.radius;
  }
  const Body& disc = a.disc ? a : b;
  const Body& box = a.disc ? b : a;
  Real r2 = 0;
  for (std::size_t d = 0; d < D; ++d) {
    const Real nearest = std::min(std::max(disc.lo[d], box.lo[d]), box.hi[d]);
    r2 += (disc.lo[d] - nearest) * (disc.lo[d] - nearest);
  }
  return std::sqrt(r2) < disc.radius;
}

}  // namespace

void validateBodies(const CaseConfig& c) {
  const auto D = static_cast<std::size_t>(c.dimension);
  requireMultiple("block_min", c.blockMin, D, "block (its lower corner)");
  requireMultiple("block_max", c.blockMax, D, "block (its upper corner)");
  requireMultiple("disc_center", c.discCenter, D, "disc");
  if (c.blockMin.size() != c.blockMax.size())
    throw CaseError("block_min and block_max go together: " + std::to_string(c.blockMin.size() / D) + " lower and " +
                    std::to_string(c.blockMax.size() / D) + " upper corners given");
  const std::size_t blocks = c.blockMin.size() / D, discs = c.discCenter.size() / D;
  if (c.discRadius.size() != discs)
    throw CaseError("disc_center and disc_radius go together: " + std::to_string(discs) + " centres and " +
                    std::to_string(c.discRadius.size()) + " radii given (one radius per disc)");
  if (!c.velocity.empty() && c.velocity.size() != D)
    throw CaseError("velocity has " + std::to_string(c.velocity.size()) + " values: it needs " + std::to_string(D) +
                    " (one per dimension)");
  for (Real x : c.velocity)
    if (!std::isfinite(x)) throw CaseError("velocity must hold finite numbers");
  if (!c.blockVelocity.empty() && c.blockVelocity.size() != blocks * D)
    throw CaseError("block_velocity has " + std::to_string(c.blockVelocity.size()) + " values: it needs " +
                    std::to_string(D) + " per block (" + std::to_string(blocks * D) + ")");
  if (!c.discVelocity.empty() && c.discVelocity.size() != discs * D)
    throw CaseError("disc_velocity has " + std::to_string(c.discVelocity.size()) + " values: it needs " +
                    std::to_string(D) + " per disc (" + std::to_string(discs * D) + ")");
  std::vector<Body> bodies;
  for (std::size_t k = 0; k < blocks; ++k) {
    Body b{"block " + std::to_string(k + 1), false, {}, {}};
    for (std::size_t d = 0; d < D; ++d) {
      b.lo.push_back(c.blockMin[k * D + d]);
      b.hi.push_back(c.blockMax[k * D + d]);
      if (!(b.hi[d] > b.lo[d]))
        throw CaseError((blocks > 1 ? b.name + ": " : std::string()) + "block_max must exceed block_min in every dimension");
    }
    bodies.push_back(b);
  }
  for (std::size_t k = 0; k < discs; ++k) {
    Body b{"disc " + std::to_string(k + 1), true, {}, {}, c.discRadius[k]};
    for (std::size_t d = 0; d < D; ++d) b.lo.push_back(c.discCenter[k * D + d]);
    if (!(b.radius > 0)) throw CaseError("disc_radius = " + significant(b.radius) + " is out of range: it must be > 0");
    bodies.push_back(b);
  }
  for (std::size_t a = 0; a < bodies.size(); ++a)
    for (std::size_t b = a + 1; b < bodies.size(); ++b)
      if (overlap(bodies[a], bodies[b], D))
        throw CaseError("the fluid bodies " + bodies[a].name + " and " + bodies[b].name +
                        " overlap: move one, or make them one body");
  // A fluid body in a solid one (obstacle_min/obstacle_max, already checked
  // for its sizes).
  if (c.obstacleMin.size() == c.obstacleMax.size() && c.obstacleMin.size() % D == 0)
    for (std::size_t k = 0; k < c.obstacleMin.size() / D; ++k) {
      Body solid{"obstacle " + std::to_string(k + 1), false, {}, {}};
      for (std::size_t d = 0; d < D; ++d) {
        solid.lo.push_back(c.obstacleMin[k * D + d]);
        solid.hi.push_back(c.obstacleMax[k * D + d]);
      }
      for (const Body& b : bodies)
        if (overlap(b, solid, D))
          throw CaseError("the fluid body " + b.name + " overlaps the solid " + solid.name +
                          " (obstacle_min/obstacle_max): fluid and solid cannot share space");
    }
  if (!bodies.empty() && !(c.spacing > 0))
    throw CaseError("spacing = " + significant(c.spacing) + " is out of range: blocks and discs need spacing > 0");
  if (c.points.size() % D != 0)
    throw CaseError("points has " + std::to_string(c.points.size()) + " values: it needs a multiple of " +
                    std::to_string(D) + " (x y" + (D == 3 ? " z" : "") + " per point)");
  // Generated particle count, before anything is allocated: indices are
  // 32-bit and memory is finite.
  double count = static_cast<double>(c.points.size() / D);
  const char* countKey = "points";
  for (const Body& b : bodies) {
    double n = 1;
    for (std::size_t d = 0; d < D; ++d)
      n *= b.disc ? 2 * std::floor(b.radius / c.spacing) + 1 : std::round((b.hi[d] - b.lo[d]) / c.spacing);
    count += n, countKey = "spacing";
  }
  for (long n : c.starParticles) count += static_cast<double>(n), countKey = "star_particles";
  if (count > kMaxParticles)
    throw CaseError(std::string(countKey) + " gives about " + significant(count) + " particles: at most " +
                    significant(kMaxParticles) + " are allowed");
}

}  // namespace sph
