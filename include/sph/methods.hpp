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
#include "sph/case_keys.hpp"
#include "sph/io/number_format.hpp"
#include "sph/method_defaults.hpp"
#include "sph/boundaries/dummy_boundary.hpp"
#include "sph/boundaries/dynamic_crespo2007.hpp"
#include "sph/boundaries/reflecting_boundary.hpp"
#include "sph/boundaries/repulsive_boundary.hpp"
#include "sph/integrators/integrators.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/models/wcsph.hpp"
#include "sph/passes/wcsph_forces.hpp"
#include "sph/terms/equation_of_state.hpp"

#include <cmath>
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

// A method: its name, a one-line summary, the case keys it reads (its own
// and shared ones), its builder, the keys it declares (their one row: the
// key table, --help, docs/keys.md and the unused-key notes read them from
// here) and its combination rules (nullptr: none).
// The keys a method declares (a wrapper: GCC 12 fails on a defaulted
// std::vector<KeySpec> member of the Method template).
struct MethodKeys {
  std::vector<KeySpec> rows;
  MethodKeys() noexcept {}
  MethodKeys(std::initializer_list<KeySpec> keys) : rows(keys) {}
  auto begin() const { return rows.begin(); }
  auto end() const { return rows.end(); }
};

template <class T>
struct Method {
  const char* name;
  const char* summary;
  std::vector<const char*> keys;  // the case keys this method reads
  T (*make)(const CaseConfig&);
  MethodKeys params = MethodKeys();
  void (*validate)(const CaseConfig&) = nullptr;
};

// Whether a row (a method or a model) reads `key`.
template <class Row>
bool readsKey(const Row& row, const std::string& key) {
  for (const char* k : row.keys)
    if (key == k) return true;
  return false;
}

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

inline const std::vector<Method<ViscosityChoice>>& viscosityMethods() {
  using key_range::within;
  static const std::vector<Method<ViscosityChoice>> m = {
      {"laplacian",
       "mu sum m_j (v_j - v_i)/(rho_i rho_j) lap W (Mueller's viscosity kernel, or -2 W'/r: Brookshaw 1985)", {"mu"},
       [](const CaseConfig& c) -> ViscosityChoice {
         if (c.mu > 0) return LaplacianViscosityChoice{c.mu};
         return NoViscosity{};
       },
       {{"mu", KeyGroup::kPhysics, &CaseConfig::mu, "Pa s (3D), kg/s (2D)",
       "Dynamic viscosity (seed model, viscosity laplacian; 0 switches it off)", within(0, 1e10), nullptr, nullptr}}},
      {"monaghan", "artificial viscosity on approaching pairs (Monaghan 1992)", {"alpha", "beta"},
       [](const CaseConfig& c) -> ViscosityChoice {
         if (c.alpha > 0 || c.beta > 0) return MonaghanViscosityChoice{c.alpha, c.beta};
         return NoViscosity{};
       },
       {{"alpha", KeyGroup::kPhysics, &CaseConfig::alpha, "", "Monaghan viscosity alpha (viscosity monaghan)", within(0, 100),
       nullptr, nullptr},
        {"beta", KeyGroup::kPhysics, &CaseConfig::beta, "", "Monaghan viscosity beta (viscosity monaghan)", within(0, 100), nullptr,
       nullptr}}},
      {"morris",
       "laminar viscosity, kinematic viscosity nu: sum m_j (mu_i+mu_j)/(rho_i rho_j) r.gradW/(r^2+0.01h^2) v_ij "
       "(Morris, Fox & Zhu 1997, eq. 8)",
       {"nu"},
       [](const CaseConfig& c) -> ViscosityChoice {
         if (c.nu > 0) return MorrisViscosityChoice{c.nu};
         return NoViscosity{};
       },
       {{"nu", KeyGroup::kPhysics, &CaseConfig::nu, "m^2/s",
       "Kinematic viscosity (viscosity morris; 0 switches it off; water 1e-6)", within(0, 1e6), nullptr, nullptr}}},
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

// Boundaries: one type per boundary (boundaries/*_boundary.hpp), its row
// made from the type (name, summary, keys, validate, the Boundary value).
template <class B>
Method<Boundary> boundaryMethod() {
  Method<Boundary> row{B::name, B::summary, B::reads, [](const CaseConfig&) { return describeBoundary<B>(); }};
  row.params.rows = B::keys();
  row.validate = &B::validate;
  return row;
}
inline std::vector<Method<Boundary>>& boundaryRegistry() {
  static std::vector<Method<Boundary>> m = {
      boundaryMethod<ReflectingBoundary>(),
      boundaryMethod<DummyBoundary>(),
      boundaryMethod<DynamicBoundary>(),
      boundaryMethod<RepulsiveBoundary>(),
  };
  return m;
}
inline const std::vector<Method<Boundary>>& boundaryMethods() { return boundaryRegistry(); }
// A boundary defined elsewhere (a test's), added after the built-in ones
// for as long as the returned registration lives.
struct BoundaryRegistration {
  const char* name;
  BoundaryRegistration(const BoundaryRegistration&) = delete;
  BoundaryRegistration& operator=(const BoundaryRegistration&) = delete;
  ~BoundaryRegistration() {
    auto& rows = boundaryRegistry();
    for (auto it = rows.begin(); it != rows.end(); ++it)
      if (it->name == name) {
        rows.erase(it);
        break;
      }
  }
};
template <class B>
BoundaryRegistration registerBoundary() {
  boundaryRegistry().push_back(boundaryMethod<B>());
  return BoundaryRegistration{B::name};
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
  const char* onlyIntegrator;  // the one integrator a fixed scheme runs with (nullptr: any)
};
inline const std::vector<ModelRow>& modelMethods() {
  static const std::vector<ModelRow> m = {
      {"seed_wcsph", "the seed 2D weakly-compressible scheme exactly as written (its kernels, linear EOS, forces)",
       {"h", "k", "rho0", "mu", "g"}, false, "leap_frog"},
      {"wcsph", "weakly-compressible SPH composed from kernel, eos, viscosity, body forces and XSPH",
       {"h", "rho0", "g", "kernel", "eos", "viscosity", "xsph", "damping", "integrator", "cfl"}, true, nullptr},
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

// The EOS row a (raw or resolved) composed case uses: its own or the default.
inline const Method<EquationOfState>& chosenEos(const CaseConfig& c) {
  return methodRow(eosMethods(), "eos", c.eos.empty() ? kDefaultEos : c.eos);
}

// The combination rules of the methods a composed case chooses.
inline void validateChosenMethods(const CaseConfig& c) {
  if (!composedModel(c)) return;
  const auto check = [&](const auto& row) {
    if (row.validate) row.validate(c);
  };
  check(chosenEos(c));
  check(methodRow(viscosityMethods(), "viscosity", c.viscosity.empty() ? kDefaultViscosity : c.viscosity));
}

// The unused-key notes of a family under a composed model: each key its
// methods declare that the chosen method does not read ("viscosity is
// laplacian; it applies to viscosity monaghan").
template <class Table, class Note>
void noteUnreadParameters(const Table& table, const char* family, const std::string& chosen, Note&& note) {
  const auto& row = methodRow(table, family, chosen);
  for (const auto& method : table)
    for (const KeySpec& key : method.params) {
      if (readsKey(row, key.name)) continue;
      std::string owners;
      for (const auto& m : table)
        if (readsKey(m, key.name)) owners += (owners.empty() ? "" : " or ") + std::string(m.name);
      note(key.name, std::string(family) + " is " + chosen + "; it applies to " + family + " " + owners);
    }
}

// The unused-key notes of the method families (eos, viscosity): under a
// fixed scheme every key they declare that the model does not read, else
// those the chosen methods do not read.
template <class Note>
void noteUnusedMethodKeys(const CaseConfig& c, Note&& note) {
  const ModelRow& model = modelOf(c);
  if (!model.composed) {
    const auto fixed = [&](const auto& table) {
      for (const auto& method : table)
        for (const KeySpec& key : method.params)
          if (!readsKey(model, key.name))
            note(key.name, "model " + std::string(model.name) + " has its own fixed terms; it applies to model wcsph");
    };
    fixed(eosMethods());
    fixed(viscosityMethods());
    return;
  }
  noteUnreadParameters(eosMethods(), "eos", c.eos, note);
  noteUnreadParameters(viscosityMethods(), "viscosity", c.viscosity, note);
}

// The boundary key's row and its boundary (whether or not the box has
// walls); the boundary that acts (none without walls); whether the case has
// wall particles.
inline const Method<Boundary>& boundaryRow(const CaseConfig& c) { return methodRow(boundaryMethods(), "boundary", c.boundary); }
inline Boundary boundaryChoice(const CaseConfig& c) { return boundaryRow(c).make(c); }
inline Boundary activeBoundary(const CaseConfig& c) { return c.walls ? boundaryChoice(c) : Boundary{}; }
inline bool wallParticles(const CaseConfig& c) { return activeBoundary(c).wallParticles(); }

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
