// Scene<D>: particles, neighbour grid, model, walls and integrator, advanced
// one step at a time.
//
// One step (leap-frog, see integrators/leap_frog.hpp):
//   kick + drift -> walls -> sort by cell, rebuild grid and neighbour list ->
//   rho, p, a at the
//   new positions -> closing half kick (v at integer time) -> state check.
// Sorting every step keeps neighbours close in memory; the sort permutes the
// state fields once and the derived fields are recomputed right after it.
#pragma once

#include "sph/boundaries/damped_reflecting_walls.hpp"
#include "sph/hash_grid.hpp"
#include "sph/integrators/leap_frog.hpp"
#include "sph/mass_scaling.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/models/seed_wcsph.hpp"
#include "sph/particles.hpp"
#include "sph/state_check.hpp"

#include <optional>
#include <utility>

namespace sph {

struct Energy {
  Real kinetic = 0, potential = 0;
  Real total() const { return kinetic + potential; }
};

template <int D>
class Scene {
 public:
  Scene(Particles<D> particles, SeedWcsph<D> model,
        std::optional<DampedReflectingWalls<D>> walls, StateCheck<D> check, Real dt,
        Real startTime = 0)
      : P_(std::move(particles)),
        model_(std::move(model)),
        walls_(std::move(walls)),
        check_(std::move(check)),
        grid_(model_.support()),
        dt_(dt),
        time_(startTime),
        startTime_(startTime) {
    P_.resize(P_.size());
    P_.shrinkToFit();
  }

  // Sort, optionally scale the masses to rho0, and evaluate rho, p, a at the
  // initial positions. Returns a failure if the initial state is not finite.
  std::optional<StateFailure> initialise(bool scaleMass) {
    sort();
    if (scaleMass) scaleMassToRestDensity(P_, neighbours_, model_);
    model_.computeDerived(P_, neighbours_);
    return check_(P_);
  }

  std::optional<StateFailure> step() {
    integrator_.kickDrift(P_, dt_);
    if (walls_) walls_->apply(P_);
    sort();
    model_.computeDerived(P_, neighbours_);
    integrator_.closingKick(P_, dt_);
    ++step_;
    time_ = startTime_ + static_cast<Real>(step_) * dt_;
    return check_(P_);
  }

  Energy energy() const {
    Energy e;
    for (std::size_t i = 0; i < P_.size(); ++i) e.kinetic += 0.5 * P_.m[i] * P_.v[i].squaredNorm();
    e.potential = model_.potentialEnergy(P_);
    return e;
  }

  const Particles<D>& particles() const { return P_; }
  Particles<D>& particles() { return P_; }
  const SeedWcsph<D>& model() const { return model_; }
  const HashGrid<D>& grid() const { return grid_; }
  Real time() const { return time_; }
  Real dt() const { return dt_; }
  long stepIndex() const { return step_; }

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
    neighbours_.build(grid_, P_.x, model_.support());
  }

  Particles<D> P_;
  SeedWcsph<D> model_;
  std::optional<DampedReflectingWalls<D>> walls_;
  StateCheck<D> check_;
  HashGrid<D> grid_;
  NeighbourList<D> neighbours_;
  LeapFrog<D> integrator_;
  Real dt_;
  Real time_;
  Real startTime_;
  long step_ = 0;
};

}  // namespace sph
