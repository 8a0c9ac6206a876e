// RegimeCheck<D>: is the run still in the regime its method is valid in?
// The state check (state_check.hpp) stops a run at a NaN or a leak; this one
// stops it earlier, when the numbers are still finite but no longer physics,
// and names the cause (issue 9; the density window is DualSPHysics' RhopOut
// idea). Every `every` steps, over the fluid particles:
//   Mach number      M = max|v| / c_ref, c_ref the EOS sound speed at rho0
//                    (Tait: c0; linear: sqrt(k)). Weakly-compressible SPH
//                    needs M of about 0.1; M > 1 means the flow outruns its
//                    own sound speed: stop. (None for the polytropic EOS.)
//   breaking up      the fraction of fluid particles with no neighbour:
//                    above 50% (from a start below 10%) the fluid has
//                    scattered into spray: stop.
//   collapsing       mean neighbours per particle above 4x the start:
//                    particles are falling onto each other: stop.
//   compressed       the densest fluid particle above 1.1 rho0: a weakly-
//                    compressible flow keeps its density within about 1%
//                    (c0 ~ 10 U); 10% means shocks, not water: stop. (Only
//                    above: a free surface with summation density reads
//                    0.7 rho0 and is fine. Tait EOS only: a linear EOS and
//                    the seed scheme set a stiffness k and are compressible
//                    by design, the seed dam break reaching 1.2 rho0.)
//                    Measured on the shipped water cases: at most 1.034.
//   rarefied         a fluid particle's density not positive: its volume
//                    m/rho is meaningless, whatever the model: stop (after
//                    Mach, which names a time step too large; before
//                    compressed, which may follow from it in a neighbour
//                    and would blame the time step). (With continuity
//                    density and density diffusion of negative pressures
//                    kept, a splash particle's density drifts from what its
//                    packing gives, and at a wall it can fall below zero;
//                    clamped, the diffusion leaves them alone:
//                    docs/methods/boundaries.md.)
//   pairing          the fraction of fluid particles with a neighbour closer
//                    than 0.2 dx: above 10% a warning, once (the pairing
//                    instability; it need not end the run).
// Cost: one pass over the neighbour list every `every` steps (10 by
// default), about 1/10 of a density pass per step.
#pragma once

#include "sph/mpi/collectives.hpp"
#include "sph/types.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

namespace sph {

template <int D>
struct Particles;
template <int D>
class NeighbourList;

struct RegimeState {
  Real mach = 0;               // max |v| / c_ref (0 without c_ref)
  Real maxSpeed = 0;
  Real isolatedFraction = 0;   // fluid particles with no neighbour
  Real meanNeighbours = 0;     // per fluid particle
  Real pairedFraction = 0;     // fluid particles with a neighbour closer than 0.2 dx
  Real densityMax = 0;         // largest rho / rho0 of a fluid particle (0 without rho0)
  Real densityMin = std::numeric_limits<Real>::infinity();  // smallest rho of a fluid particle [kg/m^3]
};

// A fluid particle more than this above rho0 is not weakly compressible.
constexpr Real kDensityWindow = 0.1;

// The state above, over the fluid particles (and over every rank's with
// comm). Defined in src/regime_check.cpp, for D = 2 and 3: this header
// leaves the neighbour walk (and the pair loop's term headers) out of the
// units that only judge a state.
template <int D>
RegimeState measureRegime(const Particles<D>& P, const NeighbourList<D>& neighbours, Real cRef, Real dx,
                          Real rho0 = 0, Real support = std::numeric_limits<Real>::infinity(),
                          const mpi::Communicator& comm = {});
extern template RegimeState measureRegime<2>(const Particles<2>&, const NeighbourList<2>&, Real, Real, Real, Real,
                                             const mpi::Communicator&);
extern template RegimeState measureRegime<3>(const Particles<3>&, const NeighbourList<3>&, Real, Real, Real, Real,
                                             const mpi::Communicator&);

class RegimeCheck {
 public:
  // cRef: 0 for no Mach check; dx: 0 for no pairing check; fluid: the
  // number of fluid particles (few-particle cases are not a fluid: only the
  // Mach check applies to them).
  RegimeCheck(Real cRef, Real dx, std::size_t fluid) : cRef_(cRef), dx_(dx), fluid_(fluid) {}

  Real soundSpeed() const { return cRef_; }
  Real spacing() const { return dx_; }

  // The start: what "collapsing" and "breaking up" are measured against.
  void start(const RegimeState& s) { start_ = s; }

  struct Verdict {
    std::string stop;     // the cause, "" when the run may go on
    std::string warning;  // "" or a warning to print once
  };

  // dt, h: the last step and the smoothing length, for the acoustic number
  // c_ref dt / h the Mach message names.
  Verdict judge(const RegimeState& s, Real dt, Real h) {
    Verdict v;
    char text[512];
    if (cRef_ > 0 && s.mach > 1) {
      std::snprintf(text, sizeof text,
                    "Mach %.3g: the fastest fluid particle moves at %.3g m/s against the sound speed %.3g m/s; "
                    "weakly-compressible SPH needs Mach of about 0.1 (c dt / h = %.3g: a time step too large for "
                    "the integrator makes a run explode like this; lower dt, or raise c0)",
                    s.mach, s.maxSpeed, cRef_, cRef_ * dt / h);
      v.stop = text;
      return v;
    }
    if (s.densityMin <= 0) {
      std::snprintf(text, sizeof text,
                    "rarefied: a fluid particle's density is %.3g kg/m^3, not positive, so its volume m/rho is "
                    "meaningless (c dt / h = %.3g; with continuity density, a splash particle's density drifts "
                    "from what its packing gives, and at a wall it can fall below zero: with negative pressures "
                    "kept, or at reflecting or repulsive walls, whose particles do not fill the support; against "
                    "dummy or dynamic walls, clamped, the diffusion leaves densities below rho0 alone: "
                    "docs/methods/boundaries.md)",
                    s.densityMin, cRef_ * dt / h);
      v.stop = text;
      return v;
    }
    if (s.densityMax > 1 + kDensityWindow) {
      std::snprintf(text, sizeof text,
                    "compressed: a fluid particle's density is %.3g rho0, more than %.0f%% above rho0; a weakly-"
                    "compressible flow stays within about 1%% (c dt / h = %.3g: a time step too large for the "
                    "integrator, or a sound speed too low for the flow; lower dt, or raise c0)",
                    s.densityMax, 100 * kDensityWindow, cRef_ * dt / h);
      v.stop = text;
      return v;
    }
    const bool aFluid = fluid_ >= 100;
    if (aFluid && start_.isolatedFraction < 0.1 && s.isolatedFraction > 0.5) {
      std::snprintf(text, sizeof text,
                    "the fluid is breaking up: %.0f%% of its particles have no neighbour (%.0f%% at the start); "
                    "the flow has scattered into spray (lower dt)",
                    100 * s.isolatedFraction, 100 * start_.isolatedFraction);
      v.stop = text;
      return v;
    }
    if (aFluid && start_.meanNeighbours > 0 && s.meanNeighbours > 4 * start_.meanNeighbours) {
      std::snprintf(text, sizeof text,
                    "particles are collapsing onto each other: %.3g neighbours per particle against %.3g at the "
                    "start (lower dt, or use a kernel that does not pair: wendland_c2)",
                    s.meanNeighbours, start_.meanNeighbours);
      v.stop = text;
      return v;
    }
    if (aFluid && dx_ > 0 && s.pairedFraction > 0.1 && !pairingWarned_) {
      pairingWarned_ = true;
      std::snprintf(text, sizeof text,
                    "pairing: %.0f%% of the fluid particles have a neighbour closer than 0.2 dx (the pairing "
                    "instability: particles clump in pairs; in model wcsph the wendland_c2 kernel does not pair)",
                    100 * s.pairedFraction);
      v.warning = text;
    }
    return v;
  }

 private:
  Real cRef_, dx_;
  std::size_t fluid_;
  RegimeState start_;
  bool pairingWarned_ = false;
};

}  // namespace sph
