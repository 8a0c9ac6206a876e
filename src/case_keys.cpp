#include "sph/case_keys.hpp"

#include "sph/integrators/integrators.hpp"
#include "sph/io/number_format.hpp"
#include "sph/methods.hpp"
#include "sph/terms/optional_terms.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>

namespace sph {
namespace {

using namespace key_range;

std::vector<std::string> kernelNames() { return methodNames(kernelMethods<2>()); }
std::vector<std::string> eosNames() { return methodNames(eosMethods()); }
std::vector<std::string> viscosityNames() { return methodNames(viscosityMethods()); }
std::vector<std::string> integratorNames() { return methodNames(integratorMethods<2>()); }
std::vector<std::string> modelNames() { return methodNames(modelMethods()); }
std::vector<std::string> boundaryNames() { return methodNames(boundaryMethods()); }
std::vector<std::string> densityNames() { return methodNames(densityMethods()); }
std::vector<std::string> negativePressureNames() { return methodNames(negativePressureMethods()); }
std::vector<std::string> neighbourWalkNames() { return methodNames(neighbourWalkMethods()); }
std::vector<std::string> precisionNames() { return methodNames(precisionMethods()); }
std::vector<std::string> densityReinitNames() { return methodNames(densityReinitMethods()); }
std::vector<std::string> gradientCorrectionNames() { return methodNames(gradientCorrectionMethods()); }
std::vector<std::string> surfaceTensionNames() { return methodNames(surfaceTensionMethods()); }
std::vector<std::string> regimeCheckNames() { return {"stop", "warn", "off"}; }
std::vector<std::string> probeInterpolationNames() { return {"shepard", "plain"}; }
std::vector<std::string> shiftingNames() { return methodNames(shiftingMethods()); }
std::vector<std::string> initialFlowNames() { return methodNames(initialFlowMethods()); }

// The keys the methods of `table` declare, in table order, into `rows`
// after the row of `chooser`.
template <class Table>
void insertMethodParameters(std::vector<KeySpec>& rows, const char* chooser, const Table& table) {
  auto at = std::find_if(rows.begin(), rows.end(), [&](const KeySpec& k) { return std::string(k.name) == chooser; });
  if (at != rows.end()) ++at;
  for (const auto& method : table)
    for (const KeySpec& key : method.params) at = rows.insert(at, key) + 1;
}

// The keys the optional terms declare, in list order, after the row of `after`.
void insertTermKeys(std::vector<KeySpec>& rows, const char* after) {
  auto at = std::find_if(rows.begin(), rows.end(), [&](const KeySpec& k) { return std::string(k.name) == after; });
  if (at != rows.end()) ++at;
  forEachOptionalTerm([&](auto term) {
    for (const KeySpec& key : decltype(term)::type::keys()) at = rows.insert(at, key) + 1;
  });
}

}  // namespace

const char* groupName(KeyGroup g) {
  switch (g) {
    case KeyGroup::kScene: return "Scene: model, domain and particles";
    case KeyGroup::kPhysics: return "Physics";
    case KeyGroup::kNumerics: return "Numerics: time stepping and threads";
    case KeyGroup::kOutput: return "Output";
  }
  return "";
}

std::string KeyRange::text() const {
  const bool hasLo = std::isfinite(lo), hasHi = std::isfinite(hi);
  if (hasLo && hasHi) {
    if (!loOpen && !hiOpen) return significant(lo) + " to " + significant(hi);
    return std::string(loOpen ? "> " : ">= ") + significant(lo) + " and " + (hiOpen ? "< " : "<= ") + significant(hi);
  }
  if (hasLo) return std::string(loOpen ? "> " : ">= ") + significant(lo);
  if (hasHi) return std::string(hiOpen ? "< " : "<= ") + significant(hi);
  return "any finite number";
}

bool KeyRange::contains(double x) const {
  if (!std::isfinite(x)) return false;
  if (integer && x != std::floor(x)) return false;
  if (loOpen ? !(x > lo) : !(x >= lo)) return false;
  if (hiOpen ? !(x < hi) : !(x <= hi)) return false;
  return true;
}

const std::vector<KeySpec>& caseKeys() {
  using G = KeyGroup;
  using C = CaseConfig;
  static const std::vector<KeySpec> keys = [] {
    std::vector<KeySpec> rows = {
      // Scene
      {"model", G::kScene, &C::model, "", "Physics model", {}, nullptr, modelNames},
      {"dimension", G::kScene, &C::dimension, "", "Spatial dimension", count(2, 3), nullptr, nullptr},
      {"domain_min", G::kScene, &C::domainMin, "m", "Lower corner of the domain box (D values)", coordinate(),
       nullptr, nullptr},
      {"domain_max", G::kScene, &C::domainMax, "m",
       "Upper corner of the domain box (D values; more than 2h above domain_min)", coordinate(), nullptr, nullptr},
      {"walls", G::kScene, &C::walls, "", "The domain box has walls (--no-walls: none); boundary says how they act", {},
       nullptr, nullptr},
      {"periodic", G::kScene, &C::periodic, "",
       "Periodic axes of the domain box, as letters: \"x\", \"xy\", \"xz\", \"xyz\", ... (no walls on those faces; "
       "each periodic extent at least 2 kernel supports)",
       {}, "none", nullptr},
      {"block_min", G::kScene, &C::blockMin, "m",
       "Lattice blocks of fluid: lower corners, D values per block (any number of blocks)", coordinate(), "none",
       nullptr},
      {"block_max", G::kScene, &C::blockMax, "m", "Lattice blocks of fluid: upper corners, D values per block",
       coordinate(), "none", nullptr},
      {"block_velocity", G::kScene, &C::blockVelocity, "m/s",
       "Initial velocity of each block, D values per block (instead of velocity)", within(-1e6, 1e6), "velocity",
       nullptr},
      {"disc_center", G::kScene, &C::discCenter, "m",
       "Lattice discs (2D) or balls (3D) of fluid: centres, D values per disc", coordinate(), "none", nullptr},
      {"disc_radius", G::kScene, &C::discRadius, "m", "Disc or ball radii, one per disc", above(0, 1e9), "none",
       nullptr},
      {"disc_velocity", G::kScene, &C::discVelocity, "m/s",
       "Initial velocity of each disc, D values per disc (instead of velocity)", within(-1e6, 1e6), "velocity",
       nullptr},
      {"initial_flow", G::kScene, &C::initialFlow, "",
       "Initial velocity and pressure field of the fluid: none, or taylor_green (2D, periodic square box of side L: "
       "u = -U cos(2 pi x/L) sin(2 pi y/L), v = U sin(2 pi x/L) cos(2 pi y/L), p = -rho0 U^2/4 (cos 4 pi x/L + cos 4 pi y/L))",
       {}, nullptr, initialFlowNames},
      {"spacing", G::kScene, &C::spacing, "m", "Lattice spacing dx of blocks and discs", within(0, 1e9), "none",
       nullptr},
      {"velocity", G::kScene, &C::velocity, "m/s", "Initial velocity of generated particles (D values)",
       within(-1e6, 1e6), "0", nullptr},
      {"points", G::kScene, &C::points, "m", "Explicit particles: x y [z] per point", coordinate(), "none", nullptr},
      {"particle_file", G::kScene, &C::particleFile, "",
       "Particles from a CSV (header x,y[,z][,vx,vy[,vz]]), a .vtp written by sph or a .pvtp (a parallel snapshot); replaces the generators",
       {}, "none", nullptr},
      {"star_mass", G::kScene, &C::starMass, "kg", "Toy star mass M (not given: no star; model wcsph, eos polytropic)",
       above(0, 1e12), "none", nullptr},
      {"star_radius", G::kScene, &C::starRadius, "m", "Toy star radius R", above(0, 1e9), "none", nullptr},
      {"star_particles", G::kScene, &C::starParticles, "", "Particles per star", count(1, 1e9), "none", nullptr},
      {"star_center", G::kScene, &C::starCenter, "m",
       "Star centres, D values per star (the attraction -lambda x always pulls to the origin)", coordinate(),
       "none", nullptr},
      {"star_velocity", G::kScene, &C::starVelocity, "m/s", "Star velocities, D values per star",
       within(-1e6, 1e6), "0", nullptr},
      {"seed", G::kScene, &C::seed, "", "Random seed of the star particles", count(0, 4294967295.0), nullptr,
       nullptr},
      // Physics
      {"h", G::kPhysics, &C::h, "m",
       "Smoothing length h: the seed scheme's support radius; kernel support is 2h (cubic, Wendland), "
       "3h (Gaussian), h (Mueller)",
       within(1e-9, 1e9), nullptr, nullptr},
      {"rho0", G::kPhysics, &C::rho0, "kg/m^3 (3D), kg/m^2 (2D)", "Rest density", above(0, 1e10), nullptr, nullptr},
      {"eos", G::kPhysics, &C::eos, "", "Equation of state (model wcsph)", {}, kDefaultEos, eosNames},
      {"kernel", G::kPhysics, &C::kernel, "", "Kernel (model wcsph)", {}, kDefaultKernel, kernelNames},
      {"viscosity", G::kPhysics, &C::viscosity, "", "Viscosity (model wcsph)", {}, kDefaultViscosity, viscosityNames},
      {"g", G::kPhysics, &C::g, "m/s^2",
       "Gravity magnitude, pointing along -y in 2D and -z in 3D: shorthand for gravity = [0, -g] or [0, 0, -g] "
       "(0 switches it off; not with gravity)",
       within(-1e6, 1e6), nullptr, nullptr},
      {"gravity", G::kPhysics, &C::gravity, "m/s^2",
       "Body acceleration as a vector, D values, any direction (e.g. [0, -9.81], or [1e-4, 0] to drive a channel "
       "flow); replaces g, which must then not be given",
       within(-1e6, 1e6), "[0, -g] / [0, 0, -g]", nullptr},
      // Walls and density (model wcsph)
      {"boundary", G::kPhysics, &C::boundary, "",
       "How the walls act: reflecting (clamp and reflect), or wall particles: dummy (Adami 2012), dynamic "
       "(Crespo 2007, needs density continuity), repulsive (Liu 2012)",
       {}, nullptr, boundaryNames},
      {"obstacle_min", G::kScene, &C::obstacleMin, "m", "Solid boxes of wall particles inside the domain: lower corners, D values per box",
       coordinate(), "none", nullptr},
      {"obstacle_max", G::kScene, &C::obstacleMax, "m", "Solid boxes: upper corners, D values per box", coordinate(), "none",
       nullptr},
      {"paddle", G::kScene, &C::paddle, "",
       "The obstacle (1 = the first of obstacle_min/obstacle_max) that moves as a paddle, d(t) = paddle_amplitude "
       "sin(2 pi t / paddle_period); 0: none",
       count(0, 1000000), nullptr, nullptr},
      {"paddle_amplitude", G::kScene, &C::paddleAmplitude, "m", "The paddle's amplitude A, D values (its direction too)",
       within(-1e6, 1e6), "none", nullptr},
      {"paddle_period", G::kScene, &C::paddlePeriod, "s", "The paddle's period T", above(0, 1e9), nullptr, nullptr},
      {"density", G::kPhysics, &C::density, "",
       "Density: summation (rho = sum m W) or continuity (d rho/dt = sum m v.grad W, integrated)", {}, nullptr,
       densityNames},
      {"hydrostatic_start", G::kPhysics, &C::hydrostaticStart, "",
       "Start the fluid at rest in hydrostatic balance: density from the EOS inverse of rho0 g (H - y), H the top of its block",
       {}, nullptr, nullptr},
      {"negative_pressure", G::kPhysics, &C::negativePressure, "", "Negative pressures: none (kept) or clamp (set to 0)",
       {}, nullptr, negativePressureNames},
      {"shifting", G::kPhysics, &C::shifting, "",
       "Particle shifting each step, dr = -A h U dt grad C, U the largest fluid speed (Lind 2012, Sun 2017): none or fickian; for internal "
       "flows (no shift within a support of a free surface)",
       {}, nullptr, shiftingNames},
      {"xsph", G::kPhysics, &C::xsph, "", "XSPH epsilon (model wcsph; 0: off)", within(0, 1), nullptr, nullptr},
      // (the optional terms' keys follow xsph: terms/optional_terms.hpp)
      // Surface tension (model wcsph)
      {"surface_tension", G::kPhysics, &C::surfaceTension, "",
       "Colour-field surface tension f = sigma kappa grad c: none; morris: kappa = -div(n/|n|) (Morris 2000); "
       "muller: kappa = -lap c/|n|, f = -sigma lap c n/|n| (Mueller, Charypar & Gross 2003); corrected: morris with "
       "the kernel-gradient correction (Bonet & Lok 1999) in grad c and div(n/|n|), the force over the whole band "
       "(two phases; the Laplace jump within 2%)",
       {}, nullptr, surfaceTensionNames},
      // Numerics
      {"integrator", G::kNumerics, &C::integrator, "", "Time integrator", {}, kDefaultIntegrator, integratorNames},
      {"dt", G::kNumerics, &C::dt, "s", "Time step (with cfl > 0: the largest step)", above(0, 1e9), nullptr,
       nullptr},
      {"cfl", G::kNumerics, &C::cfl, "", "Adaptive dt with this CFL factor (model wcsph; 0: fixed dt)",
       within(0, 2), nullptr, nullptr},
      {"end_time", G::kNumerics, &C::endTime, "s",
       "Simulated time at which the run ends (absolute: a run continued from a snapshot at t ends there too)",
       above(0, 1e12), nullptr, nullptr},
      {"density_reinit", G::kNumerics, &C::densityReinit, "",
       "Density re-initialisation every density_reinit_every steps (model wcsph, density continuity): none, "
       "shepard (zeroth order: keeps a constant density) or mls (first order, Colagrossi & Landrieu 2003: keeps "
       "a linear one)",
       {}, nullptr, densityReinitNames},
      {"gradient_correction", G::kNumerics, &C::gradientCorrection, "",
       "Kernel gradient correction (model wcsph): none, or cspm (L_i grad W, exact for linear fields, in the "
       "pressure gradient; the continuity sum keeps grad W)",
       {}, nullptr, gradientCorrectionNames},
      {"neighbour_skin", G::kNumerics, &C::neighbourSkin, "",
       "Verlet skin of the neighbour list, as a fraction of the kernel support: the list holds the pairs within "
       "support (1 + skin) and is rebuilt (with the sort by cell) only when a particle has moved more than half "
       "the skin since the last build; 0: rebuilt at every evaluation",
       within(0, 1), "0.05 for model wcsph, 0 for seed_wcsph", nullptr},
      {"neighbour_walk", G::kNumerics, &C::neighbourWalk, "",
       "How the passes visit each particle's neighbours: list (the pairs stored at each build, read back by every "
       "pass), packed (the same list as one bit per particle of the cells around each particle, about an eighth "
       "of its bytes) or cells (no stored list: the grid's cells scanned again at every visit, slower); the same "
       "pairs in the same order, so the same results",
       {}, nullptr, neighbourWalkNames},
      {"precision", G::kNumerics, &C::precision, "",
       "How the density rate, pressure, sound speed and mass are stored: double, or mixed (single precision, 16 "
       "bytes per particle fewer, 12 without a sound speed field; positions, velocities, accelerations, density "
       "and every sum stay in double). "
       "Fixed when sph is built (cmake -DSPH_PRECISION=mixed, the default | double); a build refuses the other",
       {}, "the build's (sph --version)", precisionNames},
      {"rebalance_tolerance", G::kNumerics, &C::rebalanceTolerance, "",
       "On several MPI ranks: the particles are shared out again (along the Morton curve, weighted by each "
       "particle's work: 1 + its neighbours) at the next list build when the busiest rank's work exceeds the "
       "mean by more than this fraction; no effect on the results, only on the speed",
       within(0.001, 100), "0.1", nullptr},
      {"regime_check", G::kNumerics, &C::regimeCheck, "",
       "Every 10 steps and before every snapshot: Mach number above 1, a Tait fluid 10% above rho0, a fluid "
       "particle's density not positive, the fluid breaking up (over half its particles alone), particles "
       "collapsing (4x the neighbours), pairing (a warning): stop the run naming the cause (no snapshot of it "
       "written), only warn, or off",
       {}, nullptr, regimeCheckNames},
      {"threads", G::kNumerics, &C::threads, "",
       "OpenMP threads: a count from 1 to 1024 (OMP_NUM_THREADS is obeyed too), or auto: start from the cores "
       "this process may use and the load, and keep the faster of that and fewer threads, timed during the run",
       {}, nullptr, nullptr},
      // Output
      {"output", G::kOutput, &C::output, "", "Output folder", {}, "runs/<name>", nullptr},
      {"name", G::kOutput, &C::name, "",
       "Run name: files <name>.pvd, <name>_NNNNN.vtp (letters, digits, _ - .)", {}, "the case file's name",
       nullptr},
      {"output_every", G::kOutput, &C::outputEvery, "", "A snapshot every N steps, and at the end",
       count(1, 1e12), nullptr, nullptr},
      {"output_interval", G::kOutput, &C::outputInterval, "s",
       "A snapshot every this many seconds of simulated time, and at the end (instead of output_every)",
       within(0, 1e12), "off", nullptr},
      {"probe_points", G::kOutput, &C::probePoints, "m",
       "Point probes: pressure, density and velocity interpolated there (Shepard-normalised SPH), D values per "
       "probe, into probes.csv",
       coordinate(), "none", nullptr},
      {"probe_names", G::kOutput, &C::probeNames, "", "Names of the point probes, comma-separated (\"gauge_a, gauge_b\")",
       {}, "p1, p2, ...", nullptr},
      {"height_probes", G::kOutput, &C::heightProbes, "m",
       "Water-height gauges: the horizontal position of each (x in 2D, x y in 3D), into heights.csv",
       coordinate(), "none", nullptr},
      {"front_probe", G::kOutput, &C::frontProbe, "", "Write the surge front's x (furthest fluid particle + dx/2) into front.csv",
       {}, nullptr, nullptr},
      {"probe_interpolation", G::kOutput, &C::probeInterpolation, "",
       "Point probes: shepard (sum_j A_j V_j W / sum_j V_j W: a constant exactly, also at a surface) or plain "
       "(sum_j A_j V_j W: the bare SPH sum, low where the support is not full)",
       {}, nullptr, probeInterpolationNames},
      {"probe_interval", G::kOutput, &C::probeInterval, "s",
       "Probes are sampled every this many seconds of simulated time (0: every step)", within(0, 1e12), "0: every step",
       nullptr},
      {"probe_radius", G::kOutput, &C::probeRadius, "m",
       "Point probes as pressure sensors of this radius: the pressure averaged over a disc (a segment in 2D) on "
       "the wall face nearest to each point (sph/probes.hpp)",
       within(0, 1e9), "0: the point", nullptr},
      {"probe_window", G::kOutput, &C::probeWindow, "s",
       "A column per point probe with its pressure's moving average over this many seconds of samples (a "
       "sensor's response; lags by half the window)",
       within(0, 1e9), "0: none", nullptr},
      {"progress", G::kOutput, &C::progress, "",
       "Progress: a live line on a terminal, a line every few seconds otherwise (--no-progress: none)", {},
       nullptr, nullptr},
      {"overwrite", G::kOutput, &C::overwrite, "",
       "Run into a folder that holds another run: its files are removed first", {}, nullptr, nullptr},
      {"resume", G::kOutput, &C::resume, "",
       "Continue the run in this folder from its last snapshot, into the same series (no case file needed)", {},
       "none", nullptr},
      {"catalyst", G::kOutput, &C::catalyst, "",
       "ParaView Catalyst pipeline script (paraview/catalyst_png.py, catalyst_live.py): the particles are handed "
       "to it in situ, besides the usual output (command line only, not in a case file)",
       {}, "none", nullptr},
      {"catalyst_every", G::kOutput, &C::catalystEvery, "",
       "With catalyst: hand the particles to the script at the start, every N steps and at the end (command line "
       "only)",
       count(1, 1e12), nullptr, nullptr},
  };
    // The parameters of the methods (methods.hpp), after the key that chooses them.
    insertMethodParameters(rows, "eos", eosMethods());
    insertMethodParameters(rows, "viscosity", viscosityMethods());
    insertMethodParameters(rows, "initial_flow", initialFlowMethods());
    insertMethodParameters(rows, "density", densityMethods());
    insertMethodParameters(rows, "shifting", shiftingMethods());
    insertMethodParameters(rows, "surface_tension", surfaceTensionMethods());
    insertMethodParameters(rows, "density_reinit", densityReinitMethods());
    insertMethodParameters(rows, "boundary", boundaryMethods());
    insertTermKeys(rows, "xsph");
    return rows;
  }();
  return keys;
}

const KeySpec* findKey(const std::string& name) {
  for (const KeySpec& k : caseKeys())
    if (name == k.name) return &k;
  return nullptr;
}

namespace {
template <class T>
T termKeyOf(const CaseConfig& c, const std::string& name) {
  const KeySpec* k = findKey(name);
  const auto* key = k ? std::get_if<TermKey<T>>(&k->field) : nullptr;
  if (!key) throw std::logic_error("no term key " + name + " of this type");
  return keyValue(c, *key);
}
}  // namespace

Real termReal(const CaseConfig& c, const std::string& name) { return termKeyOf<Real>(c, name); }
long termCount(const CaseConfig& c, const std::string& name) { return termKeyOf<long>(c, name); }

std::string keyHelp(const KeySpec& k) {
  std::string text = k.help;
  std::vector<std::string> parts;
  if (*k.unit) parts.push_back(k.unit);
  const bool numeric = !std::holds_alternative<std::string CaseConfig::*>(k.field) &&
                       !std::holds_alternative<bool CaseConfig::*>(k.field);
  if (numeric && (std::isfinite(k.range.lo) || std::isfinite(k.range.hi))) parts.push_back(k.range.text());
  if (k.choices) {
    std::string list;
    for (const std::string& n : k.choices()) list += (list.empty() ? "" : " | ") + n;
    parts.push_back(list);
  }
  if (k.defaultText) parts.push_back(std::string("default: ") + k.defaultText);
  if (!parts.empty()) {
    text += " [";
    for (std::size_t i = 0; i < parts.size(); ++i) text += (i ? "; " : "") + parts[i];
    text += "]";
  }
  return text;
}

void checkKeyRanges(const CaseConfig& c) {
  static const CaseConfig unset;
  for (const KeySpec& k : caseKeys()) {
    auto bad = [&](const std::string& value) {
      throw CaseError(std::string(k.name) + " = " + value + " is out of range: it must be " + k.range.text());
    };
    std::visit(
        [&](auto member) {
          using T = std::decay_t<decltype(keyValue(c, member))>;
          const T& value = keyValue(c, member);
          if constexpr (std::is_same_v<T, Real> || std::is_same_v<T, long> || std::is_same_v<T, int>) {
            // A key not given keeps its initial value, which may stand for
            // "none" outside the range (star_mass, star_radius: no star).
            if (!c.isGiven(k.name) && value == keyValue(unset, member)) return;
            if (!k.range.contains(static_cast<double>(value))) bad(significant(static_cast<double>(value)));
          } else if constexpr (std::is_same_v<T, std::vector<Real>> || std::is_same_v<T, std::vector<long>>) {
            for (const auto& x : value)
              if (!k.range.contains(static_cast<double>(x)))
                throw CaseError(std::string(k.name) + " holds " + significant(static_cast<double>(x)) +
                                ": every value must be " + k.range.text());
          } else if constexpr (std::is_same_v<T, std::string>) {
            if (!k.choices || value.empty()) return;
            std::string list;
            for (const std::string& n : k.choices()) {
              if (value == n) return;
              list += (list.empty() ? "\"" : ", \"") + n + "\"";
            }
            throw CaseError(std::string(k.name) + " = \"" + value + "\" is not known: allowed are " + list);
          }
        },
        k.field);
  }
}

// A number as case-file text: integers as integers (100000, not 1e+05,
// which CLI11 does not read back as an integer), reals as the shortest
// decimal that reads back the same.
namespace {
template <class T>
std::string numberText(T x) {
  if constexpr (std::is_same_v<T, Real>) return shortestDecimal(x);
  else return std::to_string(x);
}
}  // namespace

std::string keyValueText(const CaseConfig& c, const KeySpec& k) {
  return std::visit(
      [&](auto member) -> std::string {
        using T = std::decay_t<decltype(keyValue(c, member))>;
        const T& value = keyValue(c, member);
        if constexpr (std::is_same_v<T, bool>) {
          return value ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::string>) {
          if (value.empty()) return "";
          std::string q = "\"";
          for (char ch : value) {
            if (ch == '"' || ch == '\\') q += '\\';
            q += ch;
          }
          return q + "\"";
        } else if constexpr (std::is_same_v<T, std::vector<Real>> || std::is_same_v<T, std::vector<long>>) {
          if (value.empty()) return "";
          std::string list = "[";
          for (std::size_t i = 0; i < value.size(); ++i) list += (i ? ", " : "") + numberText(value[i]);
          return list + "]";
        } else {
          // A number at its initial value outside its range is "none" (star_mass).
          static const CaseConfig unset;
          if (value == keyValue(unset, member) && !k.range.contains(static_cast<double>(value))) return "";
          return numberText(value);
        }
      },
      k.field);
}

bool isRunOnlyKey(const KeySpec& k) {
  const std::string name = k.name;
  return name == "resume" || name == "overwrite" || isCommandLineOnlyKey(name);
}

bool isCommandLineOnlyKey(const std::string& name) { return name == "catalyst" || name == "catalyst_every"; }

namespace {
const char* const kResumeKeys[] = {"end_time", "output_every", "output_interval", "threads", "progress"};
}

bool isResumeKey(const std::string& name) {
  return std::find(std::begin(kResumeKeys), std::end(kResumeKeys), name) != std::end(kResumeKeys);
}

std::string resumeKeysText() {
  std::string text;
  const std::size_t n = std::size(kResumeKeys);
  for (std::size_t i = 0; i < n; ++i) text += (i == 0 ? "" : i + 1 == n ? " and " : ", ") + std::string(kResumeKeys[i]);
  return text;
}

std::string resolvedCaseText(const ResolvedCase& c) {
  std::string text =
      "# The case as this run resolved it: every key with the value used (defaults\n"
      "# filled in, command-line flags applied; keys nothing reads are comments).\n"
      "# `sph run` on this file repeats the run; `sph run --resume` of its folder reads it.\n";
  std::map<std::string, std::string> unused;
  for (const auto& [key, why] : unusedKeys(c)) unused[key] = why;
  KeyGroup group = KeyGroup::kScene;
  bool first = true;
  for (const KeySpec& k : caseKeys()) {
    if (isRunOnlyKey(k)) continue;
    if (first || k.group != group) text += std::string("\n# ") + groupName(k.group) + "\n";
    first = false;
    group = k.group;
    const std::string value = keyValueText(c, k);
    if (value.empty()) text += std::string("# ") + k.name + ": none\n";
    else if (unused.count(k.name)) text += std::string("# ") + k.name + " = " + value + "  (not used: " + unused[k.name] + ")\n";
    else text += std::string(k.name) + " = " + value + "\n";
  }
  return text;
}

}  // namespace sph
