// The checks of the wall-particle and density keys (called by validateCase):
// which combinations a model allows, and whether the wall layers cover the
// kernel support.
#include "sph/case_config.hpp"

#include "sph/io/number_format.hpp"
#include "sph/methods.hpp"
#include "sph/wall_particles.hpp"

#include <cmath>
#include <string>

namespace sph {
namespace {

// The largest interaction distance of the case's model: the seed's h, or
// the kernel's support.
Real interactionRadius(const CaseConfig& c) {
  if (!composedModel(c)) return c.h;
  return std::visit([](const auto& k) { return k.support(); }, chosenKernel<2>(c));
}

// periodic: letters of distinct axes of the case's dimension; each periodic
// extent at least two supports (the minimum image is then the only image in
// range); wall particles need a whole number of spacings along it (the wall
// lattice must join up across the faces), and no lid on a periodic top.
void validatePeriodic(const CaseConfig& c) {
  if (c.periodic.empty() || c.periodic == "none") return;
  const std::string axes = c.dimension == 3 ? "xyz" : "xy";
  unsigned seen = 0;
  for (char ch : c.periodic) {
    const std::size_t a = axes.find(ch);
    if (a == std::string::npos || ((seen >> a) & 1u))
      throw CaseError("periodic = \"" + c.periodic + "\" is not allowed: give each periodic axis once, as letters " +
                      "of \"" + axes + "\" (for example \"x\"), or \"none\"");
    seen |= 1u << a;
  }
  const Real support = interactionRadius(c);
  const bool particleWalls = wallParticles(c);
  for (std::size_t a = 0; a < axes.size() && a < c.domainMin.size() && a < c.domainMax.size(); ++a) {
    if (!((seen >> a) & 1u)) continue;
    const Real L = c.domainMax[a] - c.domainMin[a];
    if (!(L >= 2 * support))
      throw CaseError("periodic = \"" + c.periodic + "\": the domain is " + significant(L) + " m along " + axes[a] +
                      ", less than 2 kernel supports (2 x " + significant(support) +
                      " m); widen domain_min/domain_max along it or lower h");
    if (particleWalls && c.spacing > 0 && std::abs(L / c.spacing - std::round(L / c.spacing)) > 1e-6)
      throw CaseError("periodic = \"" + c.periodic + "\": the domain length along " + axes[a] + " (" + significant(L) +
                      " m) is not a whole number of spacings (" + significant(c.spacing) +
                      " m): the wall particles would not join up across the periodic faces");
    if (c.lid && static_cast<int>(a) == c.dimension - 1)
      throw CaseError("lid = true puts walls on the top face, but the vertical axis is periodic (periodic = \"" +
                      c.periodic + "\")");
  }
}

}  // namespace

unsigned periodicAxes(const CaseConfig& c) {
  unsigned bits = 0;
  if (c.periodic == "none") return 0;
  for (char ch : c.periodic)
    if (ch >= 'x' && ch <= 'z') bits |= 1u << (ch - 'x');
  return bits;
}

void validateWallsAndDensity(const CaseConfig& c) {
  validatePeriodic(c);
  const bool seed = !composedModel(c);
  const bool particleWalls = wallParticles(c);
  const DensityTreatment density = densityTreatment(c);
  if (seed) {
    if (boundaryChoice(c).wallParticles())
      throw CaseError("boundary = \"" + c.boundary + "\": model seed_wcsph has the seed's reflecting walls only; "
                      "use model = \"wcsph\"");
    if (density != DensityTreatment::kSummation || c.hydrostaticStart || clampNegativePressure(c) || !c.obstacleMin.empty())
      throw CaseError("density, hydrostatic_start, negative_pressure and obstacles need model = \"wcsph\"; "
                      "model seed_wcsph is the seed scheme exactly");
  }
  if (c.backgroundPressure != 0 && (seed || !readsKey(chosenEos(c), "background_pressure")))
    throw CaseError("background_pressure = " + significant(c.backgroundPressure) +
                    " needs model = \"wcsph\" with eos = \"linear\" or \"tait\"");
  if ((particleWalls || !c.obstacleMin.empty()) && !(c.spacing > 0))
    throw CaseError("boundary = \"" + c.boundary + "\" builds wall particles on the fluid lattice: give spacing (> 0)");
  if (!c.obstacleMin.empty() && !particleWalls)
    throw CaseError("obstacle_min/obstacle_max need wall particles: boundary = \"dummy\", \"dynamic\" or \"repulsive\"");
  const std::size_t D = static_cast<std::size_t>(c.dimension);
  if (c.obstacleMin.size() != c.obstacleMax.size() || c.obstacleMin.size() % D != 0)
    throw CaseError("obstacle_min and obstacle_max need " + std::to_string(D) +
                    " values per obstacle, the same number of obstacles each (they have " +
                    std::to_string(c.obstacleMin.size()) + " and " + std::to_string(c.obstacleMax.size()) + " values)");
  for (std::size_t k = 0; k < c.obstacleMin.size(); k += D)
    for (std::size_t d = 0; d < D; ++d) {
      const Real a = c.obstacleMin[k + d], b = c.obstacleMax[k + d];
      if (!(b > a)) throw CaseError("obstacle " + std::to_string(k / D + 1) + ": obstacle_max must exceed obstacle_min in every dimension");
      if (a < c.domainMin[d] || b > c.domainMax[d])
        throw CaseError("obstacle " + std::to_string(k / D + 1) + " reaches outside the domain [domain_min, domain_max]");
    }
  if (c.paddle > 0) {
    const std::size_t count = c.obstacleMin.size() / D;
    if (static_cast<std::size_t>(c.paddle) > count)
      throw CaseError("paddle = " + std::to_string(c.paddle) + " names no obstacle: the case has " +
                      std::to_string(count) + " (obstacle_min/obstacle_max); give 1 to " + std::to_string(count) +
                      " or 0 for none");
    if (c.paddleAmplitude.size() != D)
      throw CaseError("paddle_amplitude has " + std::to_string(c.paddleAmplitude.size()) + " values: it needs " +
                      std::to_string(D) + " (the paddle's displacement amplitude per dimension)");
    const std::size_t k = static_cast<std::size_t>(c.paddle - 1) * D;
    for (std::size_t d = 0; d < D; ++d) {
      const Real A = std::abs(c.paddleAmplitude[d]);
      if (c.obstacleMin[k + d] - A < c.domainMin[d] || c.obstacleMax[k + d] + A > c.domainMax[d])
        throw CaseError("paddle " + std::to_string(c.paddle) + " with paddle_amplitude " + significant(c.paddleAmplitude[d]) +
                        " would leave the domain [domain_min, domain_max] along axis " + std::to_string(d));
    }
  }
  if (!c.lidVelocity.empty()) {
    if (c.lidVelocity.size() != D)
      throw CaseError("lid_velocity has " + std::to_string(c.lidVelocity.size()) + " values: it needs " +
                      std::to_string(D) + " (one per dimension)");
    if (!(c.lid && c.walls && readsKey(boundaryRow(c), "lid_velocity")))
      throw CaseError("lid_velocity needs a lid of dummy wall particles: lid = true, boundary = \"dummy\"");
    if (c.lidVelocity[D - 1] != 0)
      throw CaseError("lid_velocity = [..., " + significant(c.lidVelocity[D - 1]) +
                      "]: the lid may only slide along its plane (its last component must be 0; the lid's "
                      "particles do not move)");
  }
  if (c.hydrostaticStart && c.blockMax.empty() && c.discRadius.empty())
    throw CaseError("hydrostatic_start needs a fluid block or disc (block_min/block_max, disc_center/disc_radius): "
                    "the top of each body is the free surface its hydrostatic pressure starts from");
  // The chosen boundary's own rules (boundaries/*.hpp).
  if (const auto& boundary = boundaryRow(c); boundary.validate) boundary.validate(c);
}

void validateTension(const CaseConfig& c) {
  const std::size_t D = static_cast<std::size_t>(c.dimension);
  if (c.colourBoxMin.size() != c.colourBoxMax.size() || (!c.colourBoxMin.empty() && c.colourBoxMin.size() != D))
    throw CaseError("colour_box_min and colour_box_max need " + std::to_string(D) +
                    " values each, or neither is given (they have " + std::to_string(c.colourBoxMin.size()) +
                    " and " + std::to_string(c.colourBoxMax.size()) + ")");
  for (std::size_t d = 0; d < c.colourBoxMin.size(); ++d)
    if (!(c.colourBoxMax[d] > c.colourBoxMin[d]))
      throw CaseError("colour_box_max must exceed colour_box_min in every dimension");
  if (c.colourEllipseCenter.size() != c.colourEllipseRadii.size() ||
      (!c.colourEllipseCenter.empty() && c.colourEllipseCenter.size() != D))
    throw CaseError("colour_ellipse_center and colour_ellipse_radii need " + std::to_string(D) +
                    " values each, or neither is given");
  for (Real r : c.colourEllipseRadii)
    if (!(r > 0)) throw CaseError("colour_ellipse_radii must all be > 0");
}

}  // namespace sph
