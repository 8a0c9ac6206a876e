// The registration point of every method a case chooses by name: one row per
// method with its name, a one-line summary (with its source), the case keys
// it uses, and the function that builds it. The factory (model_registry.hpp),
// the validation of choices, the "unused key" warnings, --help and the tests
// all read these tables; a method's name is written here and nowhere else.
//
// A row whose builder returns nothing is a choice that builds no object
// (viscosity "none").
#pragma once

#include "sph/case_config.hpp"
#include "sph/method_defaults.hpp"
#include "sph/integrators/integrators.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/models/wcsph.hpp"
#include "sph/passes/wcsph_forces.hpp"
#include "sph/terms/equation_of_state.hpp"

#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace sph {

// f(type_identity<Alt>) for every alternative Alt of the variant V.
template <class T>
struct TypeTag {
  using type = T;
};
template <class V, class F, std::size_t... I>
void forEachAlternative(F&& f, std::index_sequence<I...>) {
  (f(TypeTag<std::variant_alternative_t<I, V>>{}), ...);
}
template <class V, class F>
void forEachAlternative(F&& f) {
  forEachAlternative<V>(f, std::make_index_sequence<std::variant_size_v<V>>{});
}

template <class T>
struct Method {
  const char* name;
  const char* summary;
  std::vector<const char*> keys;  // the case keys this method reads
  T (*make)(const CaseConfig&);
};

template <int D>
const std::vector<Method<Kernel<D>>>& kernelMethods() {
  static const std::vector<Method<Kernel<D>>> m = {
      {"cubic_spline", "M4 cubic B-spline, support 2h (Monaghan & Lattanzio 1985)", {"h"},
       [](const CaseConfig& c) -> Kernel<D> { return CubicSpline<D>(c.h); }},
      {"wendland_c2", "Wendland C2, support 2h (Wendland 1995; as in DualSPHysics)", {"h"},
       [](const CaseConfig& c) -> Kernel<D> { return WendlandC2<D>(c.h); }},
      {"gaussian", "Gaussian truncated at 3h and renormalised", {"h"},
       [](const CaseConfig& c) -> Kernel<D> { return Gaussian<D>(c.h); }},
      {"muller", "Mueller, Charypar & Gross 2003 set, support h: poly6 density, spiky gradient, viscosity Laplacian",
       {"h"}, [](const CaseConfig& c) -> Kernel<D> { return Muller<D>(c.h); }},
  };
  return m;
}

inline const std::vector<Method<EquationOfState>>& eosMethods() {
  static const std::vector<Method<EquationOfState>> m = {
      {"linear", "p = k (rho - rho0)", {"k", "rho0"},
       [](const CaseConfig& c) -> EquationOfState { return LinearEos{c.k, c.rho0, c.backgroundPressure}; }},
      {"linear_clamped", "p = max(0, k (rho - rho0)): no tension (Monaghan 2000)", {"k", "rho0"},
       [](const CaseConfig& c) -> EquationOfState { return ClampedLinearEos{c.k, c.rho0}; }},
      {"tait", "p = rho0 c0^2/gamma ((rho/rho0)^gamma - 1) (Batchelor 1967; Monaghan 1994)", {"c0", "gamma", "rho0"},
       [](const CaseConfig& c) -> EquationOfState { return TaitEos{c.rho0, c.c0, c.gamma, c.backgroundPressure}; }},
      {"polytropic", "p = k rho^(1 + 1/n) (the toy star)", {"k", "polytropic_index"},
       [](const CaseConfig& c) -> EquationOfState { return PolytropicEos{c.k, c.polytropicIndex}; }},
  };
  return m;
}

inline const std::vector<Method<ViscosityChoice>>& viscosityMethods() {
  static const std::vector<Method<ViscosityChoice>> m = {
      {"laplacian",
       "mu sum m_j (v_j - v_i)/(rho_i rho_j) lap W (Mueller's viscosity kernel, or -2 W'/r: Brookshaw 1985)", {"mu"},
       [](const CaseConfig& c) -> ViscosityChoice {
         if (c.mu > 0) return LaplacianViscosityChoice{c.mu};
         return NoViscosity{};
       }},
      {"monaghan", "artificial viscosity on approaching pairs (Monaghan 1992)", {"alpha", "beta"},
       [](const CaseConfig& c) -> ViscosityChoice {
         if (c.alpha > 0 || c.beta > 0) return MonaghanViscosityChoice{c.alpha, c.beta};
         return NoViscosity{};
       }},
      {"morris",
       "laminar viscosity, kinematic viscosity nu: sum m_j (mu_i+mu_j)/(rho_i rho_j) r.gradW/(r^2+0.01h^2) v_ij "
       "(Morris, Fox & Zhu 1997, eq. 8)",
       {"nu"},
       [](const CaseConfig& c) -> ViscosityChoice {
         if (c.nu > 0) return MorrisViscosityChoice{c.nu};
         return NoViscosity{};
       }},
      {"none", "no viscosity", {}, [](const CaseConfig&) -> ViscosityChoice { return NoViscosity{}; }},
  };
  return m;
}

// Integrators are types (integrators.hpp): their rows come from the types'
// own name and summary, and each row builds its alternative.
template <int D>
const std::vector<Method<Integrator<D>>>& integratorMethods() {
  static const std::vector<Method<Integrator<D>>> m = [] {
    std::vector<Method<Integrator<D>>> rows;
    forEachAlternative<Integrator<D>>([&](auto type) {
      using T = typename decltype(type)::type;
      rows.push_back({T::name, T::summary, {}, [](const CaseConfig&) -> Integrator<D> { return T{}; }});
    });
    return rows;
  }();
  return m;
}

// Wall treatments. "reflecting" builds no wall particles: the scene clamps
// and reflects particles at the walls (boundaries/damped_reflecting_walls.hpp).
inline const std::vector<Method<WallTreatment>>& boundaryMethods() {
  static const std::vector<Method<WallTreatment>> m = {
      {"reflecting", "damped reflecting walls: clamp at distance h, normal velocity -e times itself (the seed's)",
       {"restitution"}, [](const CaseConfig&) { return WallTreatment::kNoParticles; }},
      {"dummy", "dummy wall particles with pressure extrapolated from the fluid (Adami, Hu & Adams 2012)",
       {"wall_layers", "wall_layers_override", "lid", "lid_velocity", "wall_slip", "obstacle_min", "obstacle_max"},
       [](const CaseConfig&) { return WallTreatment::kDummy; }},
      {"dynamic", "dynamic boundary particles: density by continuity, pressure by the EOS (Crespo et al. 2007)",
       {"wall_layers", "wall_layers_override", "lid", "wall_slip", "obstacle_min", "obstacle_max"},
       [](const CaseConfig&) { return WallTreatment::kDynamic; }},
      {"repulsive", "one layer of repulsive particles at dx/2 on the wall (seed document 004, after Liu et al. 2012)",
       {"lid", "obstacle_min", "obstacle_max"}, [](const CaseConfig&) { return WallTreatment::kRepulsive; }},
  };
  return m;
}

inline const std::vector<Method<DensityTreatment>>& densityMethods() {
  static const std::vector<Method<DensityTreatment>> m = {
      {"summation", "rho_i = sum_j m_j W_ij, self term included", {},
       [](const CaseConfig&) { return DensityTreatment::kSummation; }},
      {"continuity", "d rho_i/dt = sum_j m_j v_ij . grad W_ij, integrated, with density diffusion (delta)",
       {"delta", "diffusion"}, [](const CaseConfig&) { return DensityTreatment::kContinuity; }},
  };
  return m;
}

// Kernel corrections (seed document 004). Density re-initialisation every
// density_reinit_every steps, and the gradient correction.
inline const std::vector<Method<DensityReinit>>& densityReinitMethods() {
  static const std::vector<Method<DensityReinit>> m = {
      {"none", "no re-initialisation", {}, [](const CaseConfig&) { return DensityReinit::kNone; }},
      {"shepard", "rho_i = sum m_j W_ij / sum (m_j/rho_j) W_ij: zeroth order (Shepard 1968)",
       {"density_reinit_every"}, [](const CaseConfig&) { return DensityReinit::kShepard; }},
      {"mls", "rho_i = sum m_j W^MLS_ij, the first-order moving-least-squares kernel (Colagrossi & Landrieu 2003)",
       {"density_reinit_every"}, [](const CaseConfig&) { return DensityReinit::kMls; }},
  };
  return m;
}

inline const std::vector<Method<bool>>& gradientCorrectionMethods() {
  static const std::vector<Method<bool>> m = {
      {"none", "grad W as it is", {}, [](const CaseConfig&) { return false; }},
      {"cspm", "L_i grad W with L_i = [sum V_k (x_k - x_i) (x) grad W_ik]^-1 in the pressure gradient "
               "(Chen, Beraun & Carney 1999; Bonet & Lok 1999)",
       {}, [](const CaseConfig&) { return true; }},
  };
  return m;
}

// A model is composed (kernel, eos, viscosity and the other choices by name)
// or a fixed scheme (the seed's own kernels, EOS and forces).
struct ModelRow {
  const char* name;
  const char* summary;
  std::vector<const char*> keys;
  bool composed;
};
inline const std::vector<ModelRow>& modelMethods() {
  static const std::vector<ModelRow> m = {
      {"seed_wcsph", "the seed 2D weakly-compressible scheme exactly as written (its kernels, linear EOS, forces)",
       {"h", "k", "rho0", "mu", "g"}, false},
      {"wcsph", "weakly-compressible SPH composed from kernel, eos, viscosity, body forces and XSPH",
       {"h", "rho0", "g", "kernel", "eos", "viscosity", "xsph", "damping", "integrator", "cfl"}, true},
  };
  return m;
}

// The row called `name` of a table whose key names it (checkKeyRanges has
// refused unknown names), or a CaseError naming the key.
template <class Table>
const typename Table::value_type& methodRow(const Table& table, const char* key, const std::string& name) {
  for (const auto& row : table)
    if (name == row.name) return row;
  throw CaseError(std::string(key) + " = \"" + name + "\" is not known");
}

// The case's model row, and whether it is composed from named methods.
inline const ModelRow& modelOf(const CaseConfig& c) { return methodRow(modelMethods(), "model", c.model); }
inline bool composedModel(const CaseConfig& c) { return modelOf(c).composed; }

// The kernel a (raw or resolved) case uses under a composed model: its own
// or the default.
template <int D>
Kernel<D> chosenKernel(const CaseConfig& c) {
  return methodRow(kernelMethods<D>(), "kernel", c.kernel.empty() ? kDefaultKernel : c.kernel).make(c);
}

// How the walls act (boundary key, whether or not the box has walls), and
// whether the case has wall particles (walls on, a particle boundary).
inline WallTreatment wallTreatment(const CaseConfig& c) {
  return methodRow(boundaryMethods(), "boundary", c.boundary).make(c);
}
inline bool wallParticles(const CaseConfig& c) { return c.walls && wallTreatment(c) != WallTreatment::kNoParticles; }

// How the density is found (density key).
inline DensityTreatment densityTreatment(const CaseConfig& c) {
  return methodRow(densityMethods(), "density", c.density).make(c);
}
inline bool continuityDensity(const CaseConfig& c) { return densityTreatment(c) == DensityTreatment::kContinuity; }

// The names of a table, in order.
template <class Table>
std::vector<std::string> methodNames(const Table& table) {
  std::vector<std::string> names;
  for (const auto& row : table) names.push_back(row.name);
  return names;
}

// The row called `name`, or nullptr.
template <class Table>
const typename Table::value_type* findMethod(const Table& table, const std::string& name) {
  for (const auto& row : table)
    if (name == row.name) return &row;
  return nullptr;
}

}  // namespace sph
