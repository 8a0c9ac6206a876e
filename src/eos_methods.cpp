// The rows of the equations of state (methods.hpp declares the table;
// terms/equation_of_state.hpp defines the types): name, summary, the keys
// each reads and declares, its builder and its rules.
#include "sph/methods.hpp"
#include "sph/terms/equation_of_state.hpp"

#include <cmath>
#include <vector>

namespace sph {

const std::vector<Method<EquationOfState>>& eosMethods() {
  using key_range::above;
  using key_range::within;
  static const std::vector<Method<EquationOfState>> m = {
      {"linear", "p = k (rho - rho0)", {"k", "rho0", "background_pressure"},
       [](const CaseConfig& c) -> EquationOfState { return LinearEos{c.k, c.rho0, c.backgroundPressure}; },
       {{"k", KeyGroup::kPhysics, &CaseConfig::k, "m^2/s^2 (linear EOS)",
       "EOS stiffness: p = k (rho - rho0) (linear, seed), or p = k rho^(1+1/n) (polytropic)", above(0, 1e15),
       nullptr, nullptr}}},
      {"linear_clamped", "p = max(0, k (rho - rho0)): no tension (Monaghan 2000)", {"k", "rho0"},
       [](const CaseConfig& c) -> EquationOfState { return ClampedLinearEos{c.k, c.rho0}; }},
      {"tait", "p = rho0 c0^2/gamma ((rho/rho0)^gamma - 1) (Batchelor 1967; Monaghan 1994)",
       {"c0", "gamma", "rho0", "background_pressure"},
       [](const CaseConfig& c) -> EquationOfState { return TaitEos{c.rho0, c.c0, c.gamma, c.backgroundPressure}; },
       {{"c0", KeyGroup::kPhysics, &CaseConfig::c0, "m/s", "Tait sound speed (eos tait; usually 10x the largest flow speed)",
       within(0, 1e6), "none", nullptr},
        {"background_pressure", KeyGroup::kPhysics, &CaseConfig::backgroundPressure, "Pa",
       "Background pressure p_b added to p (eos linear and tait; for flows without a free surface, e.g. a periodic "
       "box: keeps p > 0 against the tensile instability)",
       within(0, 1e12), nullptr, nullptr},
        {"gamma", KeyGroup::kPhysics, &CaseConfig::gamma, "", "Tait exponent (eos tait)", above(0, 20), nullptr, nullptr}},
       [](const CaseConfig& c) {
         if (!(c.c0 > 0) || !std::isfinite(c.c0))
           throw CaseError("c0 = " + significant(c.c0) + " is out of range: it must be > 0");
       }},
      {"polytropic", "p = k rho^(1 + 1/n) (the toy star)", {"k", "polytropic_index"},
       [](const CaseConfig& c) -> EquationOfState { return PolytropicEos{c.k, c.polytropicIndex}; },
       {{"polytropic_index", KeyGroup::kPhysics, &CaseConfig::polytropicIndex, "", "n in p = k rho^(1 + 1/n) (eos polytropic)",
       above(0, 100), nullptr, nullptr}}},
  };
  return m;
}

}  // namespace sph
