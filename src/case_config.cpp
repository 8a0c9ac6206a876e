#include "sph/case_config.hpp"

#include "sph/case_keys.hpp"
#include "sph/io/number_format.hpp"
#include "sph/methods.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/terms/optional_terms.hpp"

#include <cmath>
#include <initializer_list>
#include <utility>

namespace sph {
namespace {

void requirePositive(const char* key, Real value) {
  if (!(value > 0) || !std::isfinite(value))
    throw CaseError(std::string(key) + " = " + significant(value) + " is out of range: it must be > 0");
}

void requireSize(const char* key, const std::vector<Real>& v, int dim, bool allowEmpty) {
  if (allowEmpty && v.empty()) return;
  if (static_cast<int>(v.size()) != dim)
    throw CaseError(std::string(key) + " has " + std::to_string(v.size()) +
                    " values: it needs " + std::to_string(dim) + " (one per dimension)");
  for (Real x : v)
    if (!std::isfinite(x)) throw CaseError(std::string(key) + " must hold finite numbers");
}


// Every toy star's ball, star_center +- star_radius, inside the domain (its
// random particles fill the ball).
void validateStarsInDomain(const CaseConfig& c) {
  if (c.starMass == 0) return;
  const std::size_t D = static_cast<std::size_t>(c.dimension);
  for (std::size_t s = 0; s < c.starParticles.size(); ++s)
    for (std::size_t d = 0; d < D; ++d) {
      const Real centre = c.starCenter[s * D + d];
      if (centre - c.starRadius < c.domainMin[d] || centre + c.starRadius > c.domainMax[d]) {
        std::string where;
        for (std::size_t e = 0; e < D; ++e) where += (e ? ", " : "") + significant(c.starCenter[s * D + e]);
        throw CaseError("star " + std::to_string(s + 1) + " (star_center = [" + where + "], star_radius = " +
                        significant(c.starRadius) + ") reaches outside the domain along axis " + std::to_string(d + 1) +
                        ": its ball must lie within [domain_min, domain_max] = [" + significant(c.domainMin[d]) + ", " +
                        significant(c.domainMax[d]) + "] there (move star_center, shrink star_radius or widen the domain)");
      }
    }
}

}  // namespace

long stepsFor(const CaseConfig& c) {
  return static_cast<long>(std::ceil(c.endTime / c.dt - 1e-9));
}

void validateCase(const CaseConfig& c) {
  // The output keys first: output_interval's range includes its "off" value 0.
  if (c.isGiven("output_every") && c.isGiven("output_interval"))
    throw CaseError("output_every and output_interval are both given: choose one (steps or seconds of simulated time)");
  if (c.isGiven("output_interval") && !(c.outputInterval > 0))
    throw CaseError("output_interval = " + significant(c.outputInterval) + " is out of range: it must be > 0 (seconds of simulated time)");
  checkKeyRanges(c);  // every key against its own range and choices (case_keys.cpp)
  const bool seed = !composedModel(c);
  if (seed) {
    for (const auto& [key, value] : {std::pair<const char*, const std::string&>{"kernel", c.kernel},
                                     {"eos", c.eos}, {"viscosity", c.viscosity}})
      if (!value.empty())
        throw CaseError(std::string(key) + " = \"" + value + "\" does not apply to model seed_wcsph "
                        "(its kernels, EOS and viscosity are fixed); use model = \"wcsph\"");
    if (c.xsph != 0 || c.starMass != 0 || c.cfl != 0)
      throw CaseError("xsph, star_* and cfl need model = \"wcsph\"; model seed_wcsph "
                      "is the seed scheme exactly");
    // The optional terms are model wcsph's (terms/optional_terms.hpp).
    forEachOptionalTerm([&](auto tag) {
      using T = typename decltype(tag)::type;
      if (T::fromCase(c).active())
        throw CaseError(std::string(T::keys().front().name) + " needs model = \"wcsph\"; model seed_wcsph is "
                        "the seed scheme exactly");
    });
    if (c.neighbourSkin != 0)
      throw CaseError("neighbour_skin = " + significant(c.neighbourSkin) + ": model seed_wcsph takes 0 only (its "
                      "pressure and viscosity factors are not cut off at the support, so a pair in the skin would "
                      "count); use model = \"wcsph\"");
    const char* only = modelOf(c).onlyIntegrator;
    if (only && !c.integrator.empty() && c.integrator != only)
      throw CaseError("integrator = \"" + c.integrator + "\": model seed_wcsph uses " + only + " only");
  }
  validateChosenMethods(c);  // each chosen method's own rules (methods.hpp)
  validateWallsAndDensity(c);
  validateTension(c);
  validateOptionalTerms(c);  // terms/optional_terms.hpp
  validateProbes(c);
  if (c.name.empty() || c.name == "." || c.name == ".." ||
      c.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") != std::string::npos)
    throw CaseError("name = \"" + c.name + "\" is not allowed: use letters, digits, '_', '-' and '.' (not . or ..)");
  requestedThreads(c);
  if (c.endTime / c.dt > kMaxSteps)
    throw CaseError("end_time / dt = " + significant(c.endTime / c.dt) + " steps is out of range: at most " +
                    significant(kMaxSteps) + " (raise dt or lower end_time)");
  const int D = c.dimension;
  // A toy star needs its mass and radius (the range check refused a given 0).
  const bool starKeys = c.isGiven("star_particles") || c.isGiven("star_center") || c.isGiven("star_radius") ||
                        c.isGiven("star_velocity");
  if (c.starMass == 0 && starKeys)
    throw CaseError("star_mass is missing: the case describes a toy star (star_particles, star_center, "
                    "star_radius) and its mass M must be " + findKey("star_mass")->range.text() + " kg");
  if (c.starMass != 0) {
    requirePositive("star_mass", c.starMass);
    if (c.starRadius == 0 && !c.isGiven("star_radius"))
      throw CaseError("star_radius is missing: a toy star's radius R must be " +
                      findKey("star_radius")->range.text() + " m");
    requirePositive("star_radius", c.starRadius);
    if (c.starParticles.empty()) throw CaseError("star_particles is missing: give the particles of each star");
    for (long n : c.starParticles)
      if (n < 1) throw CaseError("star_particles must be >= 1 for every star");
    const std::size_t stars = c.starParticles.size();
    if (c.starCenter.size() != stars * static_cast<std::size_t>(D))
      throw CaseError("star_center has " + std::to_string(c.starCenter.size()) + " values: it needs " +
                      std::to_string(stars * static_cast<std::size_t>(D)) + " (D per star)");
    if (!c.starVelocity.empty() && c.starVelocity.size() != stars * static_cast<std::size_t>(D))
      throw CaseError("star_velocity has " + std::to_string(c.starVelocity.size()) + " values: it needs " +
                      std::to_string(stars * static_cast<std::size_t>(D)) + " (D per star)");
    if (!std::holds_alternative<PolytropicEos>(chosenEos(c).make(c)))
      throw CaseError("a toy star needs eos = \"polytropic\"");
    if (!c.blockMin.empty() || !c.discCenter.empty() || !c.points.empty())
      throw CaseError("star_* generators cannot be combined with block, disc or points (their masses differ)");
  }
  if (c.isGiven("g") && c.isGiven("gravity"))
    throw CaseError("g and gravity are both given: choose one (g = 9.81 is the shorthand for gravity = [0, -9.81] "
                    "in 2D, [0, 0, -9.81] in 3D)");
  requireSize("gravity", c.gravity, D, true);
  if (seed && !c.gravity.empty())
    throw CaseError("gravity = [...] needs model = \"wcsph\"; model seed_wcsph has gravity along -y only (use g)");
  requireSize("domain_min", c.domainMin, D, false);
  requireSize("domain_max", c.domainMax, D, false);
  for (int d = 0; d < D; ++d) {
    const Real extent = c.domainMax[static_cast<std::size_t>(d)] - c.domainMin[static_cast<std::size_t>(d)];
    if (!(extent > 2 * c.h))
      throw CaseError("domain_max must exceed domain_min by more than 2 h in every dimension "
                      "(walls keep particles h away from each wall)");
    // The neighbour grid has cells of the support (at most 3h): bounded cell
    // indices keep its 64-bit hashing exact.
    if (extent / c.h > kMaxCellsPerAxis)
      throw CaseError("h = " + significant(c.h) + " is out of range for this domain: the domain is " + significant(extent) +
                      " m wide, more than " + significant(kMaxCellsPerAxis) + " h (raise h or shrink the domain)");
  }
  validateBodies(c);
  validateStarsInDomain(c);
}

int requestedThreads(const CaseConfig& c) {
  if (c.threads == "auto") return 0;
  std::size_t used = 0;
  long n = -1;
  try {
    n = std::stol(c.threads, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != c.threads.size() || n < 1 || n > kMaxThreads)
    throw CaseError("threads = " + c.threads + " is out of range: it must be auto or a count from 1 to " +
                    std::to_string(kMaxThreads));
  return static_cast<int>(n);
}

std::vector<std::pair<std::string, std::string>> unusedKeys(const ResolvedCase& c) {
  std::vector<std::pair<std::string, std::string>> unused;
  auto note = [&](const char* key, const std::string& why) { unused.emplace_back(key, why); };
  noteUnusedMethodKeys(c, note);  // the keys the methods declare (methods.hpp)
  noteUnusedTermKeys(c, note);  // the keys the optional terms declare
  if (!c.walls) note("restitution", "there are no walls (walls = false)");
  if (!wallParticles(c))
    note("wall_guard", "the walls are not particles; it applies to boundary dummy, dynamic or repulsive");
  if (!c.gravity.empty()) note("g", "gravity gives the body acceleration");
  if (c.starMass == 0)
    for (const char* key : {"star_radius", "star_particles", "star_center", "star_velocity", "seed"})
      note(key, "there is no toy star (no star_mass)");
  // (spacing stays used: it is the particle spacing the snapshots record.)
  if (!c.particleFile.empty())
    for (const char* key : {"block_min", "block_max", "disc_center", "disc_radius", "points", "velocity"})
      note(key, "particle_file " + c.particleFile + " replaces the generators");
  if (c.cfl == 0) note("cfl", "cfl = 0 is a fixed time step");
  if (c.paddle == 0)
    for (const char* key : {"paddle_amplitude", "paddle_period"}) note(key, "there is no paddle (paddle = 0)");
  if (c.probePoints.empty() && c.heightProbes.empty() && !c.frontProbe)
    note("probe_interval", "there are no probes (probe_points, height_probes, front_probe)");
  if (c.probePoints.empty())
    for (const char* key : {"probe_interpolation", "probe_radius", "probe_window"})
      note(key, "there are no point probes (probe_points)");
  if (c.catalyst.empty()) note("catalyst_every", "there is no Catalyst script (catalyst)");
  if (c.outputInterval > 0) note("output_every", "output_interval is used");
  else note("output_interval", "output_interval is off; output_every is used");
  return unused;
}

std::vector<std::string> unusedKeyNotes(const ResolvedCase& c) {
  std::vector<std::string> notes;
  for (const auto& [key, why] : unusedKeys(c))
    if (c.isGiven(key)) notes.push_back("key '" + key + "' is not used: " + why);
  return notes;
}

ResolvedCase withDefaults(CaseConfig c) {
  if (c.integrator.empty()) c.integrator = kDefaultIntegrator;
  if (composedModel(c)) {
    if (c.kernel.empty()) c.kernel = kDefaultKernel;
    if (c.eos.empty()) c.eos = kDefaultEos;
    if (c.viscosity.empty()) c.viscosity = kDefaultViscosity;
    if (!c.isGiven("neighbour_skin")) c.neighbourSkin = kDefaultNeighbourSkin;
  }
  return ResolvedCase(std::move(c));
}

ResolvedCase::ResolvedCase() : ResolvedCase(withDefaults(CaseConfig{})) {}

}  // namespace sph
