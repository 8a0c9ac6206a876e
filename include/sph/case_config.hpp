// CaseConfig: the typed content of a case file (and of its command-line
// overrides). One field per key; the key names, units, defaults, allowed
// ranges and help are listed once, in the key table (case_keys.hpp), which
// drives CLI11 (src/main.cpp), --help and the range checks.
//
// validateCase() checks every range and every combination before anything
// runs or is written, and throws CaseError naming the key and what is
// allowed.
#pragma once

#include "sph/method_defaults.hpp"
#include "sph/types.hpp"

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sph {

class CaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The values of the keys the optional terms declare (terms/optional_terms.hpp),
// by key name: a term's keys are declared in its own file, not as fields
// here. A key absent from the map has its declared initial value
// (termKeyValue, case_keys.hpp).
struct TermKeyValues {
  std::map<std::string, Real> reals;
  std::map<std::string, long> counts;
};

struct CaseConfig {
  std::string caseFile;  // path of the case file ("" when none)
  std::string name = "sph";  // run name: output files are <name>.pvd, <name>_NNNNN.vtp
  std::string output;    // output folder
  std::string model = kDefaultModel;
  int dimension = 2;

  // physics shared by the models
  Real h = 0.01;
  Real k = 2000;
  Real rho0 = 1000;
  Real mu = 1;
  Real g = 9.81;            // shorthand: gravity = -g e_up
  std::vector<Real> gravity;  // body acceleration, D values (instead of g)
  Real restitution = 0.5;
  bool walls = true;        // the domain box has walls
  std::string periodic;     // periodic axes of the domain box: "x", "xy", "xz", ... ("" or "none": none)

  // walls and density (model wcsph)
  std::string boundary = kDefaultBoundary;  // reflecting | dummy | dynamic | repulsive
  long wallLayers = 0;                  // layers of wall particles (0: as many as the support needs)
  bool wallLayersOverride = false;      // allow fewer layers than the support needs
  bool lid = false;                     // wall particles on the top of the box too
  bool wallGuard = true;                // no fluid particle crosses a wall surface (boundaries/wall_guard.hpp)
  std::vector<Real> lidVelocity;        // the lid slides with this velocity (D values, tangential)
  std::string wallSlip = "no_slip";     // no_slip | free_slip
  std::vector<Real> obstacleMin, obstacleMax;  // boxes of wall particles inside the domain, D values each
  long paddle = 0;                      // the obstacle (1-based) that moves as a paddle; 0: none
  std::vector<Real> paddleAmplitude;    // its displacement A sin(2 pi t / T), D values
  Real paddlePeriod = 1;                // T [s]
  std::string density = kDefaultDensity;    // summation | continuity
  Real delta = 0;                       // delta-SPH coefficient (0: off)
  std::string diffusion = "fourtakas";  // fourtakas | molteni
  bool hydrostaticStart = false;        // start at rest in hydrostatic balance
  std::string negativePressure = "none";  // none | clamp
  std::string shifting = "none";        // none | fickian (particle_shifting.hpp)
  Real shiftingCoefficient = 4;         // A in dr = -A h U dt grad C
  std::string initialFlow = "none";     // none | taylor_green (initial velocity and pressure field)
  Real flowSpeed = 1;                   // U of the initial flow

  // kernel corrections (model wcsph)
  std::string densityReinit = "none";      // none | shepard | mls
  long densityReinitEvery = 20;            // steps between two re-initialisations
  std::string gradientCorrection = "none"; // none | cspm

  // wcsph: choices by name ("" = the model's default)
  std::string kernel;       // cubic_spline | wendland_c2 | gaussian | muller
  std::string eos;          // linear | linear_clamped | tait | polytropic
  std::string viscosity;    // none | laplacian | monaghan | morris
  Real gamma = 7;           // Tait exponent
  Real c0 = 0;              // Tait sound speed (0: 10 sqrt(2 g H) is the user's job)
  Real polytropicIndex = 1; // n in p = k rho^(1 + 1/n)
  Real backgroundPressure = 0;  // p_b added by eos linear and tait
  Real alpha = 1, beta = 2; // Monaghan artificial viscosity
  Real nu = 1e-6;           // kinematic viscosity (viscosity morris)
  Real xsph = 0;            // XSPH epsilon (0: off)
  TermKeyValues termKeys;   // the optional terms' keys (damping, artificial_pressure, ...)
  std::string surfaceTension = "none";  // none | morris | muller (colour-field force, terms/colour_surface_tension.hpp)
  Real sigma = 0;                // surface tension coefficient [N/m in 3D, N in 2D per unit depth]
  Real surfaceThreshold = 0.1;   // the force acts where |grad c| > surface_threshold / h
  std::vector<Real> colourBoxMin, colourBoxMax;  // particles inside start with colour 1, the rest 0
  std::vector<Real> colourEllipseCenter, colourEllipseRadii;  // ... or inside this ellipse (ellipsoid)

  // toy star(s)
  Real starMass = 0;                // M (0: no star)
  Real starRadius = 0;              // R
  std::vector<long> starParticles;  // particles per star
  std::vector<Real> starCenter;     // D values per star
  std::vector<Real> starVelocity;   // D values per star
  long seed = 1;

  // time
  std::string integrator;   // leap_frog | symplectic_euler | rk4 | euler
  Real dt = 1e-4;
  Real cfl = 0;             // 0: fixed dt; > 0: adaptive dt with this CFL factor
  Real endTime = 1.0;
  long outputEvery = 100;
  Real outputInterval = 0;  // > 0: a snapshot every this many seconds of simulated time

  // probes (sph/probes.hpp): sampled during the run into CSV files
  std::vector<Real> probePoints;   // D values per point probe
  std::string probeNames;          // "a, b, ...": one name per point probe
  std::vector<Real> heightProbes;  // D - 1 horizontal coordinates per water-height gauge
  bool frontProbe = false;         // the surge front's x
  std::string probeInterpolation = "shepard";  // shepard | plain
  Real probeInterval = 0;          // seconds of simulated time between samples; 0: every step
  Real probeRadius = 0;            // > 0: point probes are sensors, pressure averaged over a disc on the wall
  Real probeWindow = 0;            // > 0: a moving average of each probe's pressure over this many seconds

  // neighbour list (sph/scene.hpp): Verlet skin as a fraction of the support;
  // withDefaults() sets kDefaultNeighbourSkin for model wcsph, 0 for the seed
  Real neighbourSkin = 0;
  std::string neighbourWalk = "list";  // list | packed | cells

  // the storage of the narrow fields (sph::Narrow, types.hpp): double |
  // mixed, fixed when sph is built (SPH_PRECISION); a case may name the
  // one it needs, and a build of the other refuses it
  std::string precision = kBuildPrecision;

  // several MPI ranks (sph/scene.hpp): share the particles out again when the
  // busiest rank's work exceeds the mean by more than this fraction
  Real rebalanceTolerance = 0.1;

  // regime check (sph/regime_check.hpp): stop | warn | off
  std::string regimeCheck = "stop";

  // domain (walls)
  std::vector<Real> domainMin{0, 0};
  std::vector<Real> domainMax{1, 1};

  // initial particles: any combination of the generators below
  Real spacing = 0;                  // lattice spacing for block and disc
  // Any number of bodies: D values per block corner, D per disc centre, one
  // radius per disc; block_velocity / disc_velocity: D per body (empty: all
  // move with `velocity`).
  std::vector<Real> blockMin, blockMax, blockVelocity;
  std::vector<Real> discCenter, discVelocity;
  std::vector<Real> discRadius;
  std::vector<Real> points;          // x0 y0 [z0] x1 y1 [z1] ...
  std::vector<Real> velocity;        // initial velocity of generated particles
  std::string particleFile;          // .csv (x,y[,z][,vx,vy[,vz]]) or .vtp from sph

  std::string threads = "auto";      // "auto" or a count
  bool progress = true;              // progress line when stderr is a terminal
  bool overwrite = false;            // replace another run's files in the output folder
  std::string resume;                // continue the run in this folder
  std::string catalyst;              // ParaView Catalyst pipeline script (empty: off), command line only
  long catalystEvery = 10;           // hand the particles to it every this many steps

  // How sph was called (for run.json).
  std::vector<std::string> commandLine;

  // The keys the case file or the command line set (the rest are defaults).
  std::set<std::string> given;
  bool isGiven(const std::string& key) const { return given.count(key) > 0; }
};

// Limits of validateCase: 32-bit particle indices, OpenMP team sizes, and a
// step count that a long can hold with room to spare.
constexpr double kMaxParticles = 1e9;
constexpr int kMaxThreads = 1024;
// Domain extent over support radius, per axis: cell indices and the hash
// grid's strides must fit in 64 bits in 3D.
constexpr double kMaxCellsPerAxis = 1e6;
constexpr double kMaxSteps = 1e12;

void validateCase(const CaseConfig& c);

// The wall-particle and density keys (src/case_physics.cpp), part of validateCase.
void validateWallsAndDensity(const CaseConfig& c);
// The surface-tension keys (src/case_physics.cpp), part of validateCase (the optional terms' keys:
// validateOptionalTerms, terms/optional_terms.hpp).
void validateTension(const CaseConfig& c);

// The fluid bodies: blocks, discs, their velocities, overlaps and the
// particle count (src/case_bodies.cpp), part of validateCase.
void validateBodies(const CaseConfig& c);

// The probe keys (src/case_probes.cpp), part of validateCase.
void validateProbes(const CaseConfig& c);

// The thread count a validated `threads` key asks for (0: auto).
int requestedThreads(const CaseConfig& c);

// A case with the model-dependent defaults filled in ("" choices get the
// registry's default method, methods.hpp): what builds the particles, the
// model and the scene. Only withDefaults makes one from a raw case, once,
// after validateCase; applying the defaults again does not compile.
class ResolvedCase : public CaseConfig {
 public:
  ResolvedCase();  // the default case, resolved

 private:
  explicit ResolvedCase(CaseConfig c) : CaseConfig(std::move(c)) {}
  friend ResolvedCase withDefaults(CaseConfig c);
};

// The defaults filled in, after validation.
ResolvedCase withDefaults(CaseConfig c);
ResolvedCase withDefaults(const ResolvedCase&) = delete;  // defaults are applied once

// Keys that nothing the case chose reads (alpha with the seed model, gamma
// with a linear EOS, output_interval with output_every, ...), given or not,
// each with the reason; a resolved case (run.case) leaves them out.
std::vector<std::pair<std::string, std::string>> unusedKeys(const ResolvedCase& c);
// The warnings for the keys among those that the case sets.
std::vector<std::string> unusedKeyNotes(const ResolvedCase& c);

// The body acceleration of a validated case: `gravity`, or -g along the
// last axis.
template <int D>
Vec<D> gravityVector(const CaseConfig& c) {
  Vec<D> a = Vec<D>::Zero();
  if (!c.gravity.empty()) {
    for (int d = 0; d < D; ++d) a[d] = c.gravity[static_cast<std::size_t>(d)];
    return a;
  }
  a[D - 1] = -c.g;
  return a;
}

// The periodic axes of a validated case as bits (bit a: axis a).
unsigned periodicAxes(const CaseConfig& c);

// The first D values of a validated vector key as a Vec<D>.
template <int D>
Vec<D> toVec(const std::vector<Real>& v) {
  Vec<D> out;
  for (int d = 0; d < D; ++d) out[d] = v[static_cast<std::size_t>(d)];
  return out;
}

// Number of steps that reach end_time with a fixed dt: ceil(end_time / dt)
// up to round-off.
long stepsFor(const CaseConfig& c);

}  // namespace sph
