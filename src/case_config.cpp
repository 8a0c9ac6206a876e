#include "sph/case_config.hpp"

#include <cmath>
#include <initializer_list>
#include <sstream>
#include <utility>

namespace sph {
namespace {

std::string fmt(Real x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

void requirePositive(const char* key, Real value) {
  if (!(value > 0) || !std::isfinite(value))
    throw CaseError(std::string(key) + " = " + fmt(value) + " is out of range: it must be > 0");
}

void requireSize(const char* key, const std::vector<Real>& v, int dim, bool allowEmpty) {
  if (allowEmpty && v.empty()) return;
  if (static_cast<int>(v.size()) != dim)
    throw CaseError(std::string(key) + " has " + std::to_string(v.size()) +
                    " values: it needs " + std::to_string(dim) + " (one per dimension)");
  for (Real x : v)
    if (!std::isfinite(x)) throw CaseError(std::string(key) + " must hold finite numbers");
}

void requireChoice(const char* key, const std::string& value, std::initializer_list<const char*> allowed) {
  std::string list;
  for (const char* a : allowed) {
    if (value == a) return;
    list += std::string(list.empty() ? "" : ", ") + "\"" + a + "\"";
  }
  throw CaseError(std::string(key) + " = \"" + value + "\" is not known: allowed are " + list);
}

}  // namespace

long stepsFor(const CaseConfig& c) {
  return static_cast<long>(std::ceil(c.endTime / c.dt - 1e-9));
}

void validateCase(const CaseConfig& c) {
  requireChoice("model", c.model, {"seed_wcsph", "wcsph"});
  const bool seed = c.model == "seed_wcsph";
  if (seed) {
    for (const auto& [key, value] : {std::pair<const char*, const std::string&>{"kernel", c.kernel},
                                     {"eos", c.eos}, {"viscosity", c.viscosity}})
      if (!value.empty())
        throw CaseError(std::string(key) + " = \"" + value + "\" does not apply to model seed_wcsph "
                        "(its kernels, EOS and viscosity are fixed); use model = \"wcsph\"");
    if (c.xsph != 0 || c.damping != 0 || c.starMass != 0 || c.cfl != 0)
      throw CaseError("xsph, damping, star_* and cfl need model = \"wcsph\"; model seed_wcsph "
                      "is the seed scheme exactly");
    if (!c.integrator.empty() && c.integrator != "leap_frog")
      throw CaseError("integrator = \"" + c.integrator + "\": model seed_wcsph uses leap_frog only");
  }
  if (!c.kernel.empty()) requireChoice("kernel", c.kernel, {"cubic_spline", "wendland_c2", "gaussian", "muller"});
  if (!c.eos.empty()) requireChoice("eos", c.eos, {"linear", "linear_clamped", "tait", "polytropic"});
  if (!c.viscosity.empty()) requireChoice("viscosity", c.viscosity, {"none", "laplacian", "monaghan"});
  if (!c.integrator.empty())
    requireChoice("integrator", c.integrator, {"leap_frog", "symplectic_euler", "rk4", "euler"});
  if (c.eos == "tait") {
    requirePositive("c0", c.c0);
    requirePositive("gamma", c.gamma);
  }
  if (c.eos == "polytropic") requirePositive("polytropic_index", c.polytropicIndex);
  if (!(c.alpha >= 0 && std::isfinite(c.alpha) && c.beta >= 0 && std::isfinite(c.beta)))
    throw CaseError("alpha = " + fmt(c.alpha) + ", beta = " + fmt(c.beta) + " are out of range: both must be finite and >= 0");
  if (!(c.xsph >= 0 && c.xsph <= 1)) throw CaseError("xsph = " + fmt(c.xsph) + " is out of range: it must be in [0, 1]");
  if (!(c.damping >= 0 && std::isfinite(c.damping))) throw CaseError("damping = " + fmt(c.damping) + " is out of range: it must be >= 0");
  if (!(c.cfl >= 0 && c.cfl <= 2)) throw CaseError("cfl = " + fmt(c.cfl) + " is out of range: it must be in [0, 2] (0: fixed dt)");
  if (c.dimension != 2 && c.dimension != 3)
    throw CaseError("dimension = " + std::to_string(c.dimension) + " is out of range: it must be 2 or 3");
  if (c.name.empty() || c.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") != std::string::npos)
    throw CaseError("name = \"" + c.name + "\" is not allowed: use letters, digits, '_', '-' and '.'");
  requirePositive("h", c.h);
  requirePositive("k", c.k);
  requirePositive("rho0", c.rho0);
  if (!(c.mu >= 0) || !std::isfinite(c.mu))
    throw CaseError("mu = " + fmt(c.mu) + " is out of range: it must be >= 0");
  if (!std::isfinite(c.g)) throw CaseError("g must be a finite number");
  if (!(c.restitution >= 0 && c.restitution <= 1))
    throw CaseError("restitution = " + fmt(c.restitution) + " is out of range: it must be in [0, 1]");
  requirePositive("dt", c.dt);
  requirePositive("end_time", c.endTime);
  if (c.outputEvery < 1)
    throw CaseError("output_every = " + std::to_string(c.outputEvery) + " is out of range: it must be >= 1");
  if (c.threads < 0 || c.threads > kMaxThreads)
    throw CaseError("threads = " + std::to_string(c.threads) + " is out of range: it must be in [0, " +
                    std::to_string(kMaxThreads) + "] (0: all cores)");
  if (c.endTime / c.dt > kMaxSteps)
    throw CaseError("end_time / dt = " + fmt(c.endTime / c.dt) + " steps is out of range: at most " +
                    fmt(kMaxSteps) + " (raise dt or lower end_time)");
  const int D = c.dimension;
  if (c.starMass != 0) {
    requirePositive("star_mass", c.starMass);
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
    if (c.eos != "polytropic") throw CaseError("a toy star needs eos = \"polytropic\"");
    if (!c.blockMin.empty() || !c.discCenter.empty() || !c.points.empty())
      throw CaseError("star_* generators cannot be combined with block, disc or points (their masses differ)");
  }
  requireSize("domain_min", c.domainMin, D, false);
  requireSize("domain_max", c.domainMax, D, false);
  for (int d = 0; d < D; ++d)
    if (!(c.domainMax[static_cast<std::size_t>(d)] > c.domainMin[static_cast<std::size_t>(d)] + 2 * c.h))
      throw CaseError("domain_max must exceed domain_min by more than 2 h in every dimension "
                      "(walls keep particles h away from each wall)");
  requireSize("block_min", c.blockMin, D, true);
  requireSize("block_max", c.blockMax, D, true);
  requireSize("disc_center", c.discCenter, D, true);
  requireSize("velocity", c.velocity, D, true);
  if (c.blockMin.empty() != c.blockMax.empty())
    throw CaseError("block_min and block_max go together: give both or neither");
  if (!c.blockMin.empty())
    for (int d = 0; d < D; ++d)
      if (!(c.blockMax[static_cast<std::size_t>(d)] > c.blockMin[static_cast<std::size_t>(d)]))
        throw CaseError("block_max must exceed block_min in every dimension");
  if (c.discCenter.empty() != (c.discRadius == 0))
    throw CaseError("disc_center and disc_radius go together: give both or neither");
  if (!c.discCenter.empty()) requirePositive("disc_radius", c.discRadius);
  if ((!c.blockMin.empty() || !c.discCenter.empty())) requirePositive("spacing", c.spacing);
  if (c.points.size() % static_cast<std::size_t>(D) != 0)
    throw CaseError("points has " + std::to_string(c.points.size()) +
                    " values: it needs a multiple of " + std::to_string(D) + " (x y" +
                    (D == 3 ? " z" : "") + " per point)");
  if (c.spacing < 0) throw CaseError("spacing = " + fmt(c.spacing) + " is out of range: it must be > 0");
  // Generated particle count, before anything is allocated: indices are
  // 32-bit and memory is finite.
  double count = static_cast<double>(c.points.size() / static_cast<std::size_t>(D));
  const char* countKey = "points";
  if (!c.blockMin.empty()) {
    double block = 1;
    for (int d = 0; d < D; ++d)
      block *= std::round((c.blockMax[static_cast<std::size_t>(d)] - c.blockMin[static_cast<std::size_t>(d)]) / c.spacing);
    count += block, countKey = "spacing";
  }
  if (!c.discCenter.empty()) count += std::pow(2 * std::floor(c.discRadius / c.spacing) + 1, D), countKey = "spacing";
  for (long n : c.starParticles) count += static_cast<double>(n), countKey = "star_particles";
  if (count > kMaxParticles)
    throw CaseError(std::string(countKey) + " gives about " + fmt(count) + " particles: at most " +
                    fmt(kMaxParticles) + " are allowed");
}

CaseConfig withDefaults(CaseConfig c) {
  if (c.integrator.empty()) c.integrator = "leap_frog";
  if (c.model == "wcsph") {
    if (c.kernel.empty()) c.kernel = "cubic_spline";
    if (c.eos.empty()) c.eos = "linear";
    if (c.viscosity.empty()) c.viscosity = "laplacian";
  }
  return c;
}

}  // namespace sph
