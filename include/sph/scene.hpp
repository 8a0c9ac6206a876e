// Scene<D>: particles, neighbour grid, model, walls, integrator and time-step
// control, advanced one step at a time.
//
// evaluate() = sort by cell (permuting the state fields), rebuild the grid
// and the neighbour list, then the model's rho, p, a at the current state.
// One step = the integrator's update with as many evaluate() calls as it
// needs (1 for leap-frog and the Euler schemes, 4 for RK4), the walls after
// each full position update, then the state check.
// Model and integrator are variants resolved once per step (std::visit).
#pragma once

#include "sph/boundaries/damped_reflecting_walls.hpp"
#include "sph/hash_grid.hpp"
#include "sph/integrators/explicit_euler.hpp"
#include "sph/integrators/leap_frog.hpp"
#include "sph/integrators/runge_kutta4.hpp"
#include "sph/integrators/symplectic_euler.hpp"
#include "sph/mass_scaling.hpp"
#include "sph/models/seed_wcsph.hpp"
#include "sph/models/wcsph.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"
#include "sph/state_check.hpp"
#include "sph/time_step.hpp"

#include <optional>
#include <utility>
#include <variant>

namespace sph {

struct Energy {
  Real kinetic = 0, potential = 0;
  Real total() const { return kinetic + potential; }
};

template <int D>
using Model = std::variant<SeedWcsph<D>, Wcsph<D>>;

template <int D>
using Integrator = std::variant<LeapFrog<D>, SymplecticEuler<D>, ExplicitEuler<D>, RungeKutta4<D>>;

template <int D>
class Scene {
 public:
  Scene(Particles<D> particles, Model<D> model, std::optional<DampedReflectingWalls<D>> walls,
        StateCheck<D> check, TimeStepControl timeStep, Real startTime = 0,
        Integrator<D> integrator = LeapFrog<D>{})
      : P_(std::move(particles)),
        model_(std::move(model)),
        integrator_(std::move(integrator)),
        walls_(std::move(walls)),
        check_(std::move(check)),
        timeStep_(timeStep),
        grid_(support()),
        startTime_(startTime),
        time_(startTime) {
    P_.resize(P_.size());
    const FieldNeeds modelNeeds = std::visit([](const auto& m) { return m.needs(); }, model_);
    const FieldNeeds integratorNeeds = std::visit([](const auto& i) { return i.needs(); }, integrator_);
    P_.allocate(modelNeeds | integratorNeeds);
    P_.shrinkToFit();
  }

  // Sort, optionally scale the masses to rho0, and evaluate rho, p, a at the
  // initial state. Returns a failure if the initial state is not finite.
  std::optional<StateFailure> initialise(bool scaleMass) {
    sort();
    if (scaleMass)
      std::visit([&](const auto& m) { scaleMassToRestDensity(P_, neighbours_, m); }, model_);
    computeDerived();
    return check_(P_);
  }

  std::optional<StateFailure> step() {
    const TimeStepChoice choice =
        std::visit([&](const auto& m) { return timeStep_.next(P_, m, time_); }, model_);
    lastStep_ = choice;
    std::visit(
        [&](const auto& integrator) {
          integrator.step(P_, choice.dt, [&] { evaluate(); },
                          [&] {
                            if (walls_) walls_->apply(P_);
                          });
        },
        integrator_);
    ++step_;
    // A fixed dt keeps time = start + n dt exact; adaptive steps add up.
    time_ = timeStep_.adaptive() ? time_ + choice.dt : startTime_ + static_cast<Real>(step_) * choice.dt;
    return check_(P_);
  }

  Energy energy() const {
    Energy e;
    for (std::size_t i = 0; i < P_.size(); ++i) e.kinetic += 0.5 * P_.m[i] * P_.v[i].squaredNorm();
    e.potential = std::visit([&](const auto& m) { return m.potentialEnergy(P_); }, model_);
    return e;
  }

  const Particles<D>& particles() const { return P_; }
  Particles<D>& particles() { return P_; }
  const Model<D>& model() const { return model_; }
  const HashGrid<D>& grid() const { return grid_; }
  Real time() const { return time_; }
  long stepIndex() const { return step_; }
  // dt and criterion of the last step (before the first: the fixed dt).
  const TimeStepChoice& lastTimeStep() const { return lastStep_; }
  Real support() const {
    return std::visit([](const auto& m) { return m.support(); }, model_);
  }

  // Mean number of neighbours per particle (j != i inside the support).
  Real meanNeighbours() const {
    return P_.size() ? static_cast<Real>(neighbours_.pairCount()) / static_cast<Real>(P_.size()) : 0;
  }

  std::size_t bytesAllocated() const {
    return P_.bytesAllocated() + grid_.bytesAllocated() + neighbours_.bytesAllocated();
  }

 private:
  void sort() {
    grid_.build(P_.x);
    P_.permute(grid_.order());
    neighbours_.build(grid_, P_.x, support());
  }

  void computeDerived() {
    std::visit([&](const auto& m) { m.computeDerived(P_, neighbours_); }, model_);
  }

  void evaluate() {
    sort();
    computeDerived();
  }

  Particles<D> P_;
  Model<D> model_;
  Integrator<D> integrator_;
  std::optional<DampedReflectingWalls<D>> walls_;
  StateCheck<D> check_;
  TimeStepControl timeStep_;
  HashGrid<D> grid_;
  NeighbourList<D> neighbours_;
  Real startTime_;
  Real time_;
  long step_ = 0;
  TimeStepChoice lastStep_{timeStep_.dt, "fixed"};
};

}  // namespace sph
