// The registration point of every method a case chooses by name: one row per
// method with its name, a one-line summary (with its source), the case keys
// it uses, and the function that builds it. The factory (model_registry.hpp),
// the validation of choices, the "unused key" warnings, --help and the tests
// all read these tables; a method's name is written here and nowhere else
// (the EOS rows: src/eos_methods.cpp, compiled apart, declared below).
//
// A row whose builder returns nothing is a choice that builds no object
// (viscosity "none"). A family may declare more of its rows (Traits): what
// `sph check` advises from (kernels, integrators, viscosities).
#pragma once

#include "sph/case_config.hpp"
#include "sph/case_keys.hpp"
#include "sph/io/number_format.hpp"
#include "sph/method_defaults.hpp"
#include "sph/neighbour_storage.hpp"
#include "sph/boundaries/dummy_boundary.hpp"
#include "sph/boundaries/dynamic_crespo2007.hpp"
#include "sph/boundaries/reflecting_boundary.hpp"
#include "sph/boundaries/repulsive_boundary.hpp"
#include "sph/integrators/integrators.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/models/wcsph_choices.hpp"
#include "sph/terms/equation_of_state_fwd.hpp"

#include <cmath>
#include <optional>
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

struct NoTraits {};

// Whether a case's model is composed from named methods (below).
inline bool composedModel(const CaseConfig& c);

// The row called `name` of a table whose key names it (checkKeyRanges has
// refused unknown names), or a CaseError naming the key.
template <class Table>
const typename Table::value_type& methodRow(const Table& table, const char* key, const std::string& name) {
  for (const auto& row : table)
    if (name == row.name) return row;
  throw CaseError(std::string(key) + " = \"" + name + "\" is not known");
}

// The names of a table, in order.
template <class Table>
std::vector<std::string> methodNames(const Table& table) {
  std::vector<std::string> names;
  for (const auto& row : table) names.push_back(row.name);
  return names;
}

template <class T, class Traits = NoTraits>
struct Method {
  const char* name;
  const char* summary;
  std::vector<const char*> keys;  // the case keys this method reads
  T (*make)(const CaseConfig&);
  MethodKeys params = MethodKeys();
  void (*validate)(const CaseConfig&) = nullptr;
  Traits traits = {};
};

// What `sph check` says of a kernel, measured with sph by the stability
// atlas at h/dx 1.3 (docs/stability-atlas.md, validation/stability_atlas.py
// against tests/reference/acoustic_cfl_limits.csv): the c0 dt / h from which
// waves grow, per integrator class (integrator_support.hpp), and the h/dx
// from which it pairs particles (0: not seen to 2.0).
struct KernelAdvice {
  Real acousticLimit[kAcousticClasses];
  Real pairsFrom = 0;
  const char* pairing = nullptr;  // the warning's text past "<label> at h/dx X: "
  const char* label = "";
};

// An integrator's advice, from its type (integrators/*.hpp): its class of
// acoustic limits, why it is unstable at every dt (nullptr: it is not), and
// the fraction of the viscous limit it is stable to (1: the usual limit).
struct IntegratorAdvice {
  AcousticClass acoustic = AcousticClass::kLeapFrog;
  const char* unstable = nullptr;
  Real viscousFraction = 1;
};

// A viscosity's advice: the kinematic viscosity of an artificial viscosity
// in terms of h and c0 (nullptr: none beyond Model::kinematicViscosity()).
struct ViscosityAdvice {
  Real (*artificialNu)(const CaseConfig&, Real h, Real c0) = nullptr;
};

// Whether a row (a method or a model) reads `key`.
template <class Row>
bool readsKey(const Row& row, const std::string& key) {
  for (const char* k : row.keys)
    if (key == k) return true;
  return false;
}

// The acoustic limits of the Gaussian and Mueller kernels were not
// measured: sph check uses the cubic spline's for them.
template <int D>
const std::vector<Method<Kernel<D>, KernelAdvice>>& kernelMethods() {
  static const KernelAdvice cubic{{1.88, 2.67, 0.89}, 1.3,
                                  "it pairs particles from h/dx 1.3 (measured: 39% paired at 1.3, 52-70% from 1.5); "
                                  "wendland_c2 stays clean to 2.0",
                                  "cubic spline"};
  static const KernelAdvice unmeasured{{1.88, 2.67, 0.89}};
  static const std::vector<Method<Kernel<D>, KernelAdvice>> m = {
      {"cubic_spline", "M4 cubic B-spline, support 2h (Monaghan & Lattanzio 1985)", {"h"},
       [](const CaseConfig& c) -> Kernel<D> { return CubicSpline<D>(c.h); }, {}, nullptr, cubic},
      {"wendland_c2", "Wendland C2, support 2h (Wendland 1995; as in DualSPHysics)", {"h"},
       [](const CaseConfig& c) -> Kernel<D> { return WendlandC2<D>(c.h); }, {}, nullptr, KernelAdvice{{1.81, 2.56, 0.86}}},
      {"gaussian", "Gaussian truncated at 3h and renormalised", {"h"},
       [](const CaseConfig& c) -> Kernel<D> { return Gaussian<D>(c.h); }, {}, nullptr, unmeasured},
      {"muller", "Mueller, Charypar & Gross 2003 set, support h: poly6 density, spiky gradient, viscosity Laplacian",
       {"h"}, [](const CaseConfig& c) -> Kernel<D> { return Muller<D>(c.h); }, {}, nullptr, unmeasured},
  };
  return m;
}

// The equations of state (terms/equation_of_state.hpp), registered in
// src/eos_methods.cpp: compiled apart, so that touching an EOS rebuilds the
// units that evaluate one, not every unit that reads the method tables.
const std::vector<Method<EquationOfState>>& eosMethods();

inline const std::vector<Method<ViscosityChoice, ViscosityAdvice>>& viscosityMethods() {
  using key_range::within;
  static const std::vector<Method<ViscosityChoice, ViscosityAdvice>> m = {
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
       nullptr}},
       nullptr,
       // nu = alpha h c0 / 8 (Monaghan 2005, sec. 4.1)
       {[](const CaseConfig& c, Real h, Real c0) -> Real { return c.alpha * h * c0 / 8; }}},
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
const std::vector<Method<Integrator<D>, IntegratorAdvice>>& integratorMethods() {
  static const std::vector<Method<Integrator<D>, IntegratorAdvice>> m = [] {
    std::vector<Method<Integrator<D>, IntegratorAdvice>> rows;
    forEachAlternative<Integrator<D>>([&](auto type) {
      using T = typename decltype(type)::type;
      rows.push_back({T::name, T::summary, {}, [](const CaseConfig&) -> Integrator<D> { return T{}; }, {}, nullptr,
                      IntegratorAdvice{T::kAcousticClass, T::kUnstable, T::kViscousFraction}});
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

// Density diffusion (terms/density_diffusion.hpp): the form of the delta-SPH
// term of the continuity equation.
inline const std::vector<Method<DensityDiffusionChoice>>& diffusionMethods() {
  static const std::vector<Method<DensityDiffusionChoice>> m = {
      {"fourtakas", "psi_ij less its hydrostatic part: keeps a fluid at rest in hydrostatic balance (Fourtakas et al. 2019)",
       {"delta"}, [](const CaseConfig& c) { return DensityDiffusionChoice{c.delta, true, "density_diffusion_fourtakas"}; }},
      {"molteni", "psi_ij = rho_j - rho_i (Molteni & Colagrossi 2009)", {"delta"},
       [](const CaseConfig& c) { return DensityDiffusionChoice{c.delta, false, "density_diffusion_molteni"}; }},
  };
  return m;
}

inline const std::vector<Method<DensityTreatment>>& densityMethods() {
  using key_range::within;
  static const std::vector<Method<DensityTreatment>> m = {
      {"summation", "rho_i = sum_j m_j W_ij, self term included", {},
       [](const CaseConfig&) { return DensityTreatment::kSummation; }, {},
       [](const CaseConfig& c) {
         if (c.delta > 0)
           throw CaseError("delta = " + std::to_string(c.delta) + " needs density = \"continuity\" (density diffusion "
                           "acts on the continuity equation)");
       }},
      {"continuity", "d rho_i/dt = sum_j m_j v_ij . grad W_ij, integrated, with density diffusion (delta)",
       {"delta", "diffusion"}, [](const CaseConfig&) { return DensityTreatment::kContinuity; },
       {{"delta", KeyGroup::kPhysics, &CaseConfig::delta, "",
         "Density diffusion coefficient delta (density continuity; 0: off; 0.1 usual)", within(0, 1), nullptr, nullptr},
        {"diffusion", KeyGroup::kPhysics, &CaseConfig::diffusion, "",
         "Density diffusion: fourtakas (keeps a hydrostatic state; Fourtakas 2019) or molteni (Molteni & Colagrossi 2009)",
         {}, nullptr, [] { return methodNames(diffusionMethods()); }}}},
  };
  return m;
}

// Kernel corrections (seed document 004). Density re-initialisation every
// density_reinit_every steps, and the gradient correction.
// The kernel corrections need a composed model (the seed's scheme is fixed).
inline void requireComposedForCorrections(const CaseConfig& c) {
  if (!composedModel(c))
    throw CaseError("density_reinit and gradient_correction need model = \"wcsph\"; model seed_wcsph is the seed "
                    "scheme exactly");
}

inline const std::vector<Method<DensityReinit>>& densityReinitMethods() {
  using key_range::count;
  // A re-initialisation resets the integrated density: it needs one.
  static const auto rules = [](const CaseConfig& c) {
    requireComposedForCorrections(c);
    if (methodRow(densityMethods(), "density", c.density).make(c) != DensityTreatment::kContinuity)
      throw CaseError("density_reinit = \"" + c.densityReinit + "\" needs density = \"continuity\" (summation "
                      "density is recomputed from the positions at every step)");
  };
  static const std::vector<Method<DensityReinit>> m = {
      {"none", "no re-initialisation", {}, [](const CaseConfig&) { return DensityReinit::kNone; }},
      {"shepard", "rho_i = sum m_j W_ij / sum (m_j/rho_j) W_ij: zeroth order (Shepard 1968)",
       {"density_reinit_every"}, [](const CaseConfig&) { return DensityReinit::kShepard; },
       {{"density_reinit_every", KeyGroup::kNumerics, &CaseConfig::densityReinitEvery, "",
         "Steps between two density re-initialisations", count(1, 1e9), nullptr, nullptr}},
       rules},
      {"mls", "rho_i = sum m_j W^MLS_ij, the first-order moving-least-squares kernel (Colagrossi & Landrieu 2003)",
       {"density_reinit_every"}, [](const CaseConfig&) { return DensityReinit::kMls; }, {}, rules},
  };
  return m;
}

inline const std::vector<Method<bool>>& gradientCorrectionMethods() {
  static const std::vector<Method<bool>> m = {
      {"none", "grad W as it is", {}, [](const CaseConfig&) { return false; }},
      {"cspm", "L_i grad W with L_i = [sum V_k (x_k - x_i) (x) grad W_ik]^-1 in the pressure gradient "
               "(Chen, Beraun & Carney 1999; Bonet & Lok 1999)",
       {}, [](const CaseConfig&) { return true; }, {}, [](const CaseConfig& c) { requireComposedForCorrections(c); }},
  };
  return m;
}

// Negative pressures (negative_pressure key): kept, or clamped to 0 by the
// EOS passes. Builds whether they are clamped.
inline const std::vector<Method<bool>>& negativePressureMethods() {
  static const std::vector<Method<bool>> m = {
      {"none", "negative pressures are kept", {}, [](const CaseConfig&) { return false; }},
      {"clamp", "p = max(0, p) after the EOS; the density diffusion reads max(rho, rho at p = 0) (with dummy or dynamic walls, or none)", {},
       [](const CaseConfig&) { return true; }},
  };
  return m;
}

// How the passes visit each particle's neighbours (neighbour_walk key;
// neighbour_list.hpp): from a list stored at each build, from the same list
// packed as one bit per candidate of the cells around each particle, or by
// scanning the grid's cells again at every visit. The same pairs in the
// same order, so the same results.
inline const std::vector<Method<NeighbourStorage>>& neighbourWalkMethods() {
  static const std::vector<Method<NeighbourStorage>> m = {
      {"list", "the pairs stored at each build of the neighbour list (a 4-byte index each) and read back by "
               "every pass",
       {}, [](const CaseConfig&) { return NeighbourStorage::kList; }},
      {"packed", "the same list packed: one bit per particle of the 3^D cells around each particle, "
                 "unpacked at every visit (about an eighth of the list's bytes in 2D, a sixth in 3D; on "
                 "several MPI ranks, whose rows are ordered by id, the plain list)",
       {}, [](const CaseConfig&) { return NeighbourStorage::kPacked; }},
      {"cells", "no stored list: every pass scans the 3^D cells around each particle again, as DualSPHysics "
                "does (the list's bytes saved, more time per walk)",
       {}, [](const CaseConfig&) { return NeighbourStorage::kCells; }},
  };
  return m;
}

// How the narrow fields are stored (precision key; sph::Narrow, types.hpp):
// a property of the build (cmake -DSPH_PRECISION), so the other row is
// refused with how to get it.
inline void requireBuildPrecision(const CaseConfig& c) {
  if (c.precision != kBuildPrecision)
    throw CaseError("precision = " + c.precision + " needs sph built with cmake -DSPH_PRECISION=" + c.precision +
                    " (this build stores " + kBuildPrecision + ")");
}
inline const std::vector<Method<bool>>& precisionMethods() {
  static const std::vector<Method<bool>> m = {
      {"double", "every particle field in double precision", {}, [](const CaseConfig&) { return false; },
       {}, requireBuildPrecision},
      {"mixed", "the density rate, pressure, sound speed and mass stored in single precision (16 bytes per "
                "particle fewer, 12 without a sound speed field); positions, velocities, accelerations, density "
                "and every sum in double",
       {}, [](const CaseConfig&) { return true; }, {}, requireBuildPrecision},
  };
  return m;
}

// Colour-field surface tension (terms/colour_surface_tension.hpp): the
// curvature method, none for no surface tension.
inline void requireComposedForTension(const CaseConfig& c) {
  if (!composedModel(c))
    throw CaseError("surface_tension needs model = \"wcsph\"; model seed_wcsph is the seed "
                    "scheme exactly");
}
inline const std::vector<Method<std::optional<CurvatureMethod>>>& surfaceTensionMethods() {
  using key_range::coordinate;
  using key_range::within;
  static const std::vector<const char*> keys = {"sigma", "surface_threshold", "colour_box_min", "colour_box_max",
                                                "colour_ellipse_center", "colour_ellipse_radii"};
  static const auto rules = [](const CaseConfig& c) {
    requireComposedForTension(c);
    if (!(c.sigma > 0))
      throw CaseError("surface_tension = \"" + c.surfaceTension + "\" needs sigma > 0 (N/m in 3D, N per unit depth in 2D)");
  };
  using Curvature = std::optional<CurvatureMethod>;
  static const std::vector<Method<Curvature>> m = {
      {"none", "no surface tension", {}, [](const CaseConfig&) -> Curvature { return std::nullopt; }},
      {"morris", "kappa = -div(n/|n|) (Morris 2000)", keys,
       [](const CaseConfig&) -> Curvature { return CurvatureMethod::kMorris; },
       {{"sigma", KeyGroup::kPhysics, &CaseConfig::sigma, "N/m (3D), N (2D, per unit depth)",
         "Surface tension coefficient (surface_tension morris, muller or corrected; must be > 0 then)", within(0, 1e9),
         nullptr, nullptr},
        {"surface_threshold", KeyGroup::kPhysics, &CaseConfig::surfaceThreshold, "",
         "A reliable normal (curvature, force) where |grad c| > surface_threshold / h (morris, muller, corrected)",
         within(0, 100), nullptr, nullptr},
        {"colour_box_min", KeyGroup::kScene, &CaseConfig::colourBoxMin, "m",
         "Surface tension between two phases: fluid particles inside this box start with colour 1, the rest with "
         "colour 0 (D values; no colour box or ellipse: every fluid particle has colour 1, a free surface)",
         coordinate(), "none", nullptr},
        {"colour_box_max", KeyGroup::kScene, &CaseConfig::colourBoxMax, "m", "Upper corner of the colour box (D values)",
         coordinate(), "none", nullptr},
        {"colour_ellipse_center", KeyGroup::kScene, &CaseConfig::colourEllipseCenter, "m",
         "Two phases: fluid particles inside this ellipse (ellipsoid) start with colour 1 too (D values)", coordinate(),
         "none", nullptr},
        {"colour_ellipse_radii", KeyGroup::kScene, &CaseConfig::colourEllipseRadii, "m",
         "Semi-axes of the colour ellipse along x, y[, z] (equal: a circle or sphere)", within(0, 1e9), "none",
         nullptr}},
       rules},
      {"muller", "kappa = -lap c/|n|, f = -sigma lap c n/|n| (Mueller, Charypar & Gross 2003)", keys,
       [](const CaseConfig&) -> Curvature { return CurvatureMethod::kMuller; }, {}, rules},
      {"corrected", "morris with the kernel-gradient correction (Bonet & Lok 1999) in grad c and div(n/|n|)", keys,
       [](const CaseConfig&) -> Curvature { return CurvatureMethod::kCorrected; }, {}, rules},
  };
  return m;
}

// Particle shifting (particle_shifting.hpp): whether the scene shifts.
inline const std::vector<Method<bool>>& shiftingMethods() {
  using key_range::within;
  static const std::vector<Method<bool>> m = {
      {"none", "no shifting", {}, [](const CaseConfig&) { return false; }},
      {"fickian", "dr = -A h U dt grad C (Lind et al. 2012; Sun et al. 2017)", {"shifting_coefficient", "spacing"},
       [](const CaseConfig&) { return true; },
       {{"shifting_coefficient", KeyGroup::kPhysics, &CaseConfig::shiftingCoefficient, "",
         "A in the particle shift (shifting fickian)", within(0, 100), nullptr, nullptr}},
       [](const CaseConfig& c) {
         if (!composedModel(c) || !(c.spacing > 0))
           throw CaseError("shifting = \"" + c.shifting + "\" needs model = \"wcsph\" and the lattice spacing "
                           "(spacing > 0): the shift's tensile term compares W_ij with W(dx)");
       }},
  };
  return m;
}

// The initial flow field of the fluid (particle_sources.cpp).
enum class InitialFlow { kNone, kTaylorGreen };
inline const std::vector<Method<InitialFlow>>& initialFlowMethods() {
  using key_range::within;
  static const std::vector<Method<InitialFlow>> m = {
      {"none", "the particles' own velocities", {}, [](const CaseConfig&) { return InitialFlow::kNone; }},
      {"taylor_green", "the Taylor-Green vortex array of a periodic square box (2D)", {"flow_speed"},
       [](const CaseConfig&) { return InitialFlow::kTaylorGreen; },
       {{"flow_speed", KeyGroup::kScene, &CaseConfig::flowSpeed, "m/s", "U of the initial flow (initial_flow taylor_green)",
         within(0, 1e6), nullptr, nullptr}},
       [](const CaseConfig& c) {
         if (!composedModel(c) || c.dimension != 2 || c.periodic != "xy")
           throw CaseError("initial_flow = \"taylor_green\" needs model = \"wcsph\", dimension = 2 and periodic = \"xy\" "
                           "(the vortex array of a periodic square box)");
         const Real Lx = c.domainMax[0] - c.domainMin[0], Ly = c.domainMax[1] - c.domainMin[1];
         if (std::abs(Lx - Ly) > 1e-9 * Lx)
           throw CaseError("initial_flow = \"taylor_green\" needs a square domain: domain_max - domain_min is " +
                           significant(Lx) + " x " + significant(Ly) + " m");
       }},
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
  return sph::methodRow(eosMethods(), "eos", c.eos.empty() ? kDefaultEos : c.eos);  // qualified: ADL would complete the EOS types
}

// The viscosity row a (raw or resolved) composed case uses.
inline const Method<ViscosityChoice, ViscosityAdvice>& chosenViscosity(const CaseConfig& c) {
  return methodRow(viscosityMethods(), "viscosity", c.viscosity.empty() ? kDefaultViscosity : c.viscosity);
}

// The kernel and integrator rows a (raw or resolved) case uses.
template <int D>
const Method<Kernel<D>, KernelAdvice>& chosenKernelRow(const CaseConfig& c) {
  return methodRow(kernelMethods<D>(), "kernel", c.kernel.empty() ? kDefaultKernel : c.kernel);
}
template <int D>
const Method<Integrator<D>, IntegratorAdvice>& chosenIntegratorRow(const CaseConfig& c) {
  return methodRow(integratorMethods<D>(), "integrator", c.integrator.empty() ? kDefaultIntegrator : c.integrator);
}

// The families every model has, with the key that chooses in each (the
// seed model's choices are their defaults; their rules refuse the rest).
template <class F>
void forEachSharedFamily(const CaseConfig& c, F&& f) {
  f(densityMethods(), "density", c.density);
  f(densityReinitMethods(), "density_reinit", c.densityReinit);
  f(gradientCorrectionMethods(), "gradient_correction", c.gradientCorrection);
  f(surfaceTensionMethods(), "surface_tension", c.surfaceTension);
  f(shiftingMethods(), "shifting", c.shifting);
  f(initialFlowMethods(), "initial_flow", c.initialFlow);
  f(negativePressureMethods(), "negative_pressure", c.negativePressure);
  f(neighbourWalkMethods(), "neighbour_walk", c.neighbourWalk);
  f(precisionMethods(), "precision", c.precision);
}

// The combination rules of the methods a case chooses.
inline void validateChosenMethods(const CaseConfig& c) {
  const auto check = [&](const auto& row) {
    if (row.validate) row.validate(c);
  };
  forEachSharedFamily(c, [&](const auto& table, const char* key, const std::string& chosen) {
    check(methodRow(table, key, chosen));
  });
  if (!composedModel(c)) return;
  check(chosenEos(c));
  check(chosenViscosity(c));
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
      std::vector<std::string> names;
      for (const auto& m : table)
        if (readsKey(m, key.name)) names.push_back(m.name);
      std::string owners;  // "a", "a or b", "a, b or c"
      for (std::size_t i = 0; i < names.size(); ++i)
        owners += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
      note(key.name, std::string(family) + " is " + chosen + "; it applies to " + family + " " + owners);
    }
}

// The unused-key notes of the method families: the keys each family's
// methods declare that its chosen method does not read; for eos and
// viscosity under a fixed scheme, every key they declare that the model
// does not read.
template <class Note>
void noteUnusedMethodKeys(const CaseConfig& c, Note&& note) {
  forEachSharedFamily(c, [&](const auto& table, const char* key, const std::string& chosen) {
    noteUnreadParameters(table, key, chosen, note);
  });
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

// The density diffusion of a continuity case (diffusion and delta keys).
inline DensityDiffusionChoice densityDiffusion(const CaseConfig& c) {
  return methodRow(diffusionMethods(), "diffusion", c.diffusion).make(c);
}

// How the passes visit each particle's neighbours (neighbour_walk key).
inline NeighbourStorage neighbourStorage(const CaseConfig& c) {
  return methodRow(neighbourWalkMethods(), "neighbour_walk", c.neighbourWalk).make(c);
}

// Whether negative pressures are clamped (negative_pressure key).
inline bool clampNegativePressure(const CaseConfig& c) {
  return methodRow(negativePressureMethods(), "negative_pressure", c.negativePressure).make(c);
}

// The curvature method of the case's surface tension, none without.
inline std::optional<CurvatureMethod> surfaceTensionCurvature(const CaseConfig& c) {
  return methodRow(surfaceTensionMethods(), "surface_tension", c.surfaceTension).make(c);
}

// Whether the scene shifts particles (shifting key).
inline bool shiftingOn(const CaseConfig& c) { return methodRow(shiftingMethods(), "shifting", c.shifting).make(c); }

// The initial flow field (initial_flow key).
inline InitialFlow initialFlow(const CaseConfig& c) {
  return methodRow(initialFlowMethods(), "initial_flow", c.initialFlow).make(c);
}

// The measured acoustic limit c0 dt / h of the case's kernel and integrator
// (sph check's advice).
template <int D>
Real acousticLimit(const CaseConfig& c) {
  return chosenKernelRow<D>(c).traits.acousticLimit[static_cast<int>(chosenIntegratorRow<D>(c).traits.acoustic)];
}

// The row called `name`, or nullptr.
template <class Table>
const typename Table::value_type* findMethod(const Table& table, const std::string& name) {
  for (const auto& row : table)
    if (name == row.name) return &row;
  return nullptr;
}

}  // namespace sph
