// Time-step control: a fixed dt, or an adaptive dt from the usual explicit
// limits (Monaghan 1992; Morris, Fox & Zhu 1997, J. Comput. Phys. 136):
//
//   dt_cfl     = C h / (c_max + |v|_max)        (acoustic CFL)
//   dt_viscous = 0.125 h^2 / nu                  (nu = mu / rho0)
//   dt_force   = 0.25 sqrt(h / |a|_max)
//   dt = min(dt_cfl, dt_viscous, dt_force, dt_max), cut to land on end_time,
//
// with the safety factor C = `cfl` of the case. Each step records which
// criterion set its dt.
#pragma once

#include "sph/particles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sph {

struct TimeStepChoice {
  Real dt;
  const char* criterion;  // "fixed", "cfl", "viscous", "force", "max", "end", "output"
};

// The extremes of the state that the time step needs, reduced by the scene
// in the step's last loop.
struct StateExtremes {
  Real v2Max = 0, a2Max = 0;  // largest |v|^2, |a|^2 over the fluid
  Real rhoMin = std::numeric_limits<Real>::infinity(), rhoMax = 0;
};

struct TimeStepControl {
  Real dt = 1e-4;   // fixed dt, or the largest adaptive dt
  Real cfl = 0;     // 0: fixed dt; > 0: adaptive with this CFL factor
  Real endTime = std::numeric_limits<Real>::infinity();

  bool adaptive() const { return cfl > 0; }

  // The next dt; adaptive steps are cut to land on end_time and on `landOn`
  // (an output time) rather than overshoot them.
  template <class Model>
  TimeStepChoice next(const StateExtremes& s, const Model& model, Real time,
                      Real landOn = std::numeric_limits<Real>::infinity()) const {
    TimeStepChoice choice{dt, adaptive() ? "max" : "fixed"};
    if (adaptive()) {
      const Real h = model.smoothingLength();
      consider(choice, cfl * h / (model.maxSoundSpeed(s.rhoMin, s.rhoMax) + std::sqrt(s.v2Max)), "cfl");
      const Real nu = model.kinematicViscosity();
      if (nu > 0) consider(choice, 0.125 * h * h / nu, "viscous");
      if (s.a2Max > 0) consider(choice, 0.25 * std::sqrt(h / std::sqrt(s.a2Max)), "force");
    }
    // Land exactly on end_time and on landOn rather than overshoot them, or
    // stop short of them by round-off (a step that reaches them to 1e-12
    // lands on them). Adaptive only: a fixed dt keeps its value and the
    // step count ceil(end_time / dt).
    auto reaches = [&](Real t) { return time + choice.dt > t - 1e-12 * std::abs(t); };
    if (adaptive() && reaches(endTime)) choice = {endTime - time, "end"};
    if (adaptive() && landOn > time && reaches(landOn)) choice = {landOn - time, "output"};
    return choice;
  }

 private:
  static void consider(TimeStepChoice& c, Real candidate, const char* name) {
    if (candidate < c.dt) c = {candidate, name};
  }
};

}  // namespace sph
