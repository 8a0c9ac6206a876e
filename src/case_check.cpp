// sph check: what a case implies before it runs (case_check.hpp).
//
// The stable ranges it warns about were measured with sph (docs/methods/seed-model.md, "Where
// the seed scheme works", and docs/stability-atlas.md, issue 9); the methods
// declare them (methods.hpp: KernelAdvice, IntegratorAdvice, ViscosityAdvice):
//   acoustic   each kernel's c0 dt / h limit per integrator class (leap-frog
//              and symplectic Euler from 1.88 with the cubic spline, 1.81
//              with Wendland C2 at h/dx 1.3, rk4 from 2.67 and 2.56); the usual
//              aim is c0 dt / h <= 0.25, and past half the limit waves grow;
//   pairing    the h/dx from which a kernel pairs particles (the cubic spline
//              from 1.3); Wendland C2 stays clean to 2.0;
//   Mach       density varies as Ma^2: Ma <= 0.1 keeps it within 1%;
//   an integrator unstable at every dt (explicit Euler gains energy every
//   step), and one stable to a fraction of the viscous limit only.
#include "sph/io/number_format.hpp"
#include "sph/case_check.hpp"

#include "sph/case_file.hpp"
#include "sph/model_registry.hpp"
#include "sph/run_case.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/time_step.hpp"
#include "sph/wall_particles.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace sph {
namespace {

std::string fmt(Real x, int digits = 3) { return significant(x, digits); }

}  // namespace

template <int D>
int checkCase(const CaseConfig& given, std::ostream& out, std::ostream& err) {
  ResolvedCase c;
  InitialState<D> init;
  try {
    validateCase(given);
    c = withDefaults(given);
    init = buildInitialState<D>(c);
  } catch (const CaseError& e) {
    err << "sph: error: " << escapeControl(e.what()) << "\n";
    return kBadInput;
  } catch (const std::runtime_error& e) {
    err << "sph: error: " << escapeControl(e.what()) << "\n";
    return kBadInput;
  }
  for (const std::string& note : unusedKeyNotes(c)) err << "sph: warning: " << escapeControl(note) << "\n";
  const bool scale = !init.massesGiven;
  Scene<D> scene = makeScene<D>(c, std::move(init));
  if (const auto failure = scene.initialise(scale)) {
    err << "sph: error: the initial state fails the state check: " << escapeControl(failure->detail) << "\n";
    return kBadInput;
  }
  int warnings = 0;
  auto warn = [&](const std::string& s) {
    out << "  warning: " << s << "\n";
    ++warnings;
  };
  const Particles<D>& P = scene.particles();
  const Model<D>& model = scene.model();
  const std::size_t nFluid = P.fluidCount();
  const Real h = model.smoothingLength(), dx = c.spacing;
  Real rhoMin = std::numeric_limits<Real>::infinity(), rhoMax = 0, pMin = rhoMin, pMax = -rhoMin, v2 = 0;
  Real yMin = rhoMin, yMax = -rhoMin;
  for (std::size_t i = 0; i < nFluid; ++i) {
    rhoMin = std::min(rhoMin, P.rho[i]);
    rhoMax = std::max(rhoMax, P.rho[i]);
    pMin = std::min<Real>(pMin, P.p[i]);
    pMax = std::max<Real>(pMax, P.p[i]);
    v2 = std::max(v2, P.v[i].squaredNorm());
    yMin = std::min(yMin, P.x[i][D - 1]);
    yMax = std::max(yMax, P.x[i][D - 1]);
  }
  out << "sph check: " << c.name << "  (model " << c.model << ", " << D << "D)\n";
  out << "  particles        " << P.size() << " (" << nFluid << " fluid, " << P.size() - nFluid << " wall)\n";
  if (dx > 0)
    out << "  h / dx           " << fmt(h / dx) << "  (h = " << fmt(h) << " m, dx = " << fmt(dx) << " m)\n";
  out << "  neighbours       " << fmt(scene.meanNeighbours()) << " per particle (mean at the start)\n";
  out << "  density          " << fmt(rhoMin, 6) << " .. " << fmt(rhoMax, 6) << "  (rho0 = " << fmt(c.rho0, 6) << ")\n";
  out << "  pressure         " << fmt(pMin) << " .. " << fmt(pMax) << (D == 2 ? " N/m" : " Pa") << "\n";

  // The speed the case can reach: the largest of its initial velocities, a
  // fall over the fluid's height (sqrt(2 g H)), a sliding lid's speed and a
  // paddle's peak speed 2 pi |A| / T (d(t) = A sin(2 pi t / T)).
  const Real g = gravityVector<D>(c).norm();
  const Real H = nFluid ? yMax - yMin + dx : 0;
  struct Speed {
    const char* what;
    Real value;
  };
  std::vector<Speed> speeds{{"initial", std::sqrt(v2)}, {"sqrt(2 g H)", std::sqrt(2 * g * H)}};
  auto norm = [](const std::vector<Real>& v) {
    Real s2 = 0;
    for (Real x : v) s2 += x * x;
    return std::sqrt(s2);
  };
  if (c.walls && c.lid && !c.lidVelocity.empty()) speeds.push_back({"lid", norm(c.lidVelocity)});
  if (c.paddle > 0) speeds.push_back({"paddle 2 pi A / T", 2 * M_PI * norm(c.paddleAmplitude) / c.paddlePeriod});
  Speed fastest{"", 0};
  std::string listed;
  for (const Speed& s : speeds) {
    if (s.value > fastest.value) fastest = s;
    if (s.value > 0) listed += (listed.empty() ? "" : ", ") + std::string(s.what) + " " + fmt(s.value);
  }
  const Real vExpected = fastest.value;
  const Real c0 = model.maxSoundSpeed(c.rho0, c.rho0);
  if (c0 > 0 && vExpected > 0) {
    const Real mach = vExpected / c0;
    out << "  sound speed      c0 = " << fmt(c0) << " m/s; expected speed " << fmt(vExpected) << " m/s (" << listed
        << (g > 0 ? "; H = " + fmt(H) + " m" : "") << "): Mach " << fmt(mach) << "\n";
    // Ma <= 0.1 needs c >= 10 v: c0 itself with eos tait; k = c^2 with the
    // linear EOS and the seed's p = k (rho - rho0).
    const Real cNeeded = 10 * vExpected;
    const auto& eos = model.eos();
    const bool tait = std::holds_alternative<TaitEos>(eos),
               linear = std::holds_alternative<LinearEos>(eos) || std::holds_alternative<ClampedLinearEos>(eos);
    std::string how;
    if (tait) how = ": c0 >= " + fmt(cNeeded) + " m/s";
    else if (linear) how = ": k >= " + fmt(cNeeded * cNeeded) + " m^2/s^2 (c = sqrt(k))";
    if (mach > 0.1)
      warn("Mach " + fmt(mach) + " > 0.1: the density will vary by ~" + fmt(100 * mach * mach) +
           "% (Ma^2); a sound speed of at least " + fmt(cNeeded) + " m/s keeps Mach <= 0.1" + how);
  }

  // dt against the limits (time_step.hpp gives the adaptive ones).
  const Real dt = c.dt;
  const IntegratorAdvice& integrator = chosenIntegratorRow<D>(c).traits;
  out << "  time step        dt = " << fmt(dt) << " s" << (c.cfl > 0 ? " (largest; adaptive, cfl " + fmt(c.cfl) + ")" : " (fixed)")
      << "\n";
  if (c0 > 0) {
    const Real courant = c0 * dt / h;
    // The stability atlas's measured limits at h/dx 1.3 (docs/stability-atlas.md).
    const Real limit = acousticLimit<D>(c);
    out << "    acoustic       c0 dt / h = " << fmt(courant) << " (aim <= 0.25; ";
    if (integrator.unstable) out << c.integrator << " is unstable at every dt)\n";
    else out << c.integrator << " measured unstable from ~" << fmt(limit) << ")\n";
    if (c.cfl == 0 && courant > 0.5 * limit)
      warn("c0 dt / h = " + fmt(courant) + " is past half the measured acoustic limit " + fmt(limit) +
           ": lower dt to " + fmt(0.25 * h / c0) + " s");
  }
  const Real nu = model.kinematicViscosity();
  if (nu > 0) {
    const Real viscous = 0.125 * h * h / nu;
    out << "    viscous        dt / (0.125 h^2 / nu) = " << fmt(dt / viscous) << "\n";
    if (c.cfl == 0 && dt > viscous) warn("dt is " + fmt(dt / viscous) + "x the viscous limit " + fmt(viscous) + " s");
  }
  // The two-step leap-frog amplifies diffusion: its filtered roots leave the
  // unit circle at lambda dt = -2 nu/(1 + nu) = -0.095 (explicit Euler: -2),
  // so a viscous term (laminar, or Monaghan's, nu = alpha h c0 / 8) is
  // stable only to about 1/20 of the viscous limit
  // (integrators/two_step_leap_frog.hpp; Taylor-Green at 0.045 blew up).
  if (integrator.viscousFraction < 1) {
    const auto artificialNu = composedModel(c) ? chosenViscosity(c).traits.artificialNu : nullptr;
    const Real nuAll = nu + (artificialNu && c0 > 0 ? artificialNu(c, h, c0) : 0);
    const Real bound = nuAll > 0 ? integrator.viscousFraction * 0.125 * h * h / nuAll : 0;
    if (nuAll > 0 && dt > bound)
      warn("integrator " + c.integrator + " amplifies the viscous term past dt ~ " + fmt(bound) + " s (1/" +
           fmt(1 / integrator.viscousFraction) + " of the viscous limit for nu = " + fmt(nuAll) +
           " m^2/s): lower dt or use " + kDefaultIntegrator);
  }
  if (g > 0) {
    const Real force = 0.25 * std::sqrt(h / g);
    out << "    body force     dt / (0.25 sqrt(h / g)) = " << fmt(dt / force) << "\n";
    if (c.cfl == 0 && dt > force) warn("dt is " + fmt(dt / force) + "x the body-force limit " + fmt(force) + " s");
  }
  if (integrator.unstable) warn("integrator " + c.integrator + " " + integrator.unstable + ": use " + kDefaultIntegrator);

  // Walls and kernels.
  if (activeBoundary(c).particles == WallLattice::kLayers) {
    const int needed = wallLayersNeeded(c), layers = wallLayersUsed(c);
    out << "  wall layers      " << layers << " (the support needs " << needed << ")\n";
    if (layers < needed) warn("fewer wall layers than the support needs: particles near a wall see a gap and leak");
  }
  if (wallParticles(c)) {
    if (c.wallGuard)
      out << "  wall guard       on: no fluid particle crosses a wall surface (the wall forces alone do not hold an "
             "isolated splash particle: boundaries/wall_guard.hpp)\n";
    else
      warn("wall_guard = false: the wall particles alone hold the fluid; an isolated splash particle at p <= 0 can "
           "pass them and stop the run (measured: the obstacle dam break, through the floor at 0.69 s)");
  }
  if (composedModel(c)) {
    const KernelAdvice& kernel = chosenKernelRow<D>(c).traits;
    if (dx > 0 && kernel.pairsFrom > 0 && h / dx >= kernel.pairsFrom)
      warn(std::string(kernel.label) + " at h/dx " + fmt(h / dx) + ": " + kernel.pairing);
  }

  {
    // Where the bytes are, per particle (ghosts' arrays counted, per owned particle).
    const auto parts = scene.memoryParts();
    const Real n = static_cast<Real>(std::max<std::size_t>(scene.globalCount(), 1));
    const auto perParticle = [&](std::size_t b) { return fmt(static_cast<Real>(b) / n); };
    out << "  memory           " << fmt(static_cast<Real>(parts.total()) / (1 << 20)) << " MiB, "
        << perParticle(parts.total()) << " B per particle: fields " << perParticle(parts.fields) << ", scratch "
        << perParticle(parts.particleScratch) << ", grid " << perParticle(parts.grid) << ", neighbour list "
        << perParticle(parts.list) << "\n";
  }
  // A short timed sample on one thread (a run's threads = auto may do
  // better): one warm-up step, then 20 timed ones.
  omp_set_num_threads(1);
  const int sample = 20;
  if (scene.time() < c.endTime) (void)scene.step();
  const Real start = scene.time();
  const auto t0 = std::chrono::steady_clock::now();
  int taken = 0;
  for (; taken < sample && scene.time() < c.endTime; ++taken)
    if (scene.step()) break;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (taken > 0) {
    const Real perStep = seconds / taken;
    const Real stepDt = scene.time() > start ? (scene.time() - start) / taken : dt;
    const Real steps = std::ceil((c.endTime - start) / stepDt);
    out << "  time estimate    " << fmt(perStep * 1e3) << " ms per step x " << fmt(steps) << " steps = "
        << fmt(perStep * steps) << " s on 1 thread (from " << taken << " timed steps, no output)\n";
  }
  out << "  " << warnings << (warnings == 1 ? " warning" : " warnings") << "\n";
  return kSuccess;
}

template int checkCase<2>(const CaseConfig&, std::ostream&, std::ostream&);
template int checkCase<3>(const CaseConfig&, std::ostream&, std::ostream&);

}  // namespace sph
