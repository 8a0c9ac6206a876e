// Scene<D>: particles, neighbour grid, model, walls, integrator and time-step
// control, advanced one step at a time.
//
// evaluate() = sort by cell (permuting the state and stage fields; with a
// periodic box, wrapping the particles and making their ghosts,
// periodic_ghosts.hpp), rebuild the grid and the neighbour list, then the
// model's passes at the current state.
//
// Verlet skin (neighbour_skin = s > 0, a fraction of the support R; Verlet
// 1967, as in Allen & Tildesley 1987, sec. 5.3.1): the list holds every
// pair closer than R (1 + s) at the positions x_b of its build, and the
// sort, the grid, the ghosts and the list are kept until some particle is
// more than s R / 2 from x_b: until then two particles closer than R now
// were closer than R + s R at the build, so the list still holds every
// pair the passes need, and the pairs beyond R it holds contribute exactly
// 0 (every kernel's W and grad W are 0 from the support on). The check is
// made before every use of the list at new positions (every evaluation,
// RK4's stages included, and leap-frog's half-step density rate), in the
// parallel region that refreshes the ghosts; a rebuild there carries every
// field with its particle (rates and derived ones too: they are read after
// it). Positions are wrapped into a periodic box only at a rebuild, so a
// ghost stays at its source plus its shift. The positions of the build
// (field xList) go into every snapshot: a resumed run builds its list
// again at them (the particles are still in the build's order, and the
// ghosts are made in the order of ids), so it holds the pairs, in the
// order, of the list the interrupted run had, and goes on bit for bit,
// wherever it was stopped. s = 0: a list per evaluation, as before (the
// seed scheme). The ghosts (and MPI halos) are refreshed from their
// sources wherever the owned particles changed and a neighbour walk follows,
// each time with only the fields that changed: a pass's declared writes
// (Model::sync), the integrator's advanced state (x, v, rho:
// integrator_support.hpp) at a list check and before its density-rate
// pass, what its finish() wrote after each step; every field after the
// mass scaling and when a sort makes them anew. One step = the scene's own
// passes at its start (shifting, wall motion: passes/step_start.hpp, each
// followed by the ghosts of what it wrote), the integrator's advance (as many evaluate() calls as it
// needs: 1 for leap-frog and the Euler schemes, 4 for RK4; the walls act on
// each particle right after its position update), then one loop that
// finishes every particle, checks the state and reduces what the next time
// step needs; then the model's after-step passes (density re-initialisation)
// act on the finished state. The integrator is a variant resolved once per step.
#pragma once

#include "sph/boundaries/boundary.hpp"
#include "sph/hash_grid.hpp"
#include "sph/integrators/integrators.hpp"
#include "sph/mass_scaling.hpp"
#include "sph/mpi/collectives.hpp"
#include "sph/mpi/domain_decomposition.hpp"
#include "sph/models/model.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"
#include "sph/passes/step_start.hpp"
#include "sph/periodic_ghosts.hpp"
#include "sph/state_check.hpp"
#include "sph/time_step.hpp"
#include "sph/wall_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace sph {

struct Energy {
  Real kinetic = 0, potential = 0;
  Real total() const { return kinetic + potential; }
};

template <int D>
class Scene {
 public:
  // walls: the boundary's per-particle constraint (boundaries/boundary.hpp).
  Scene(Particles<D> particles, Model<D> model, WallConstraint<D> walls,
        StateCheck<D> check, TimeStepControl timeStep, Real startTime = 0,
        Integrator<D> integrator = LeapFrog<D>{}, Real neighbourSkin = 0)
      : P_(std::move(particles)),
        model_(std::move(model)),
        integrator_(std::move(integrator)),
        walls_(std::move(walls)),
        check_(std::move(check)),
        timeStep_(timeStep),
        grid_(model_.support() * (1 + neighbourSkin)),
        skin_(neighbourSkin),
        listRadius_(model_.support() * (1 + neighbourSkin)),
        startTime_(startTime),
        time_(startTime) {
    // (Ghosts and halos of particles handed on from another scene are
    // dropped; particles filled without a resize() are all owned.)
    P_.clearGhosts();
    P_.resize(P_.size() ? P_.size() : P_.x.size(), P_.fluidCount() ? P_.fluidCount() : SIZE_MAX);
    const bool density = (model_.needs() & fieldBit(kFieldDrho)) != 0;
    const FieldSet integratorNeeds = std::visit([&](const auto& i) { return i.needs(density); }, integrator_);
    // The state the integrator carries between steps (two-step leap-frog's
    // previous velocity and density) that the particles came without: a
    // resumed run cannot continue without it (resume()).
    // Likewise the positions of the last list build (a snapshot's
    // list_build_position): without them resume() builds a new list.
    const std::size_t n = P_.size();
    P_.forEachField([&](const FieldInfo& info, const auto& field) {
      if (((integratorNeeds >> info.id) & 1u) && info.role == FieldRole::kState && field.size() != n)
        carriedMissing_ |= fieldBit(info.id);
    });
    listRecorded_ = n > 0 && P_.xList.size() == n;
    P_.allocate(model_.needs() | integratorNeeds | (skin_ > 0 ? fieldBit(kFieldXList) : FieldSet(0)));
    if (auto* leapFrog = std::get_if<LeapFrog<D>>(&integrator_))
      leapFrog->forcesSeeHalfStepVelocity = model_.forcesSeeHalfStepVelocity();
  }

  // Periodic axes of the domain box; call before initialise() or resume().
  // With a skin, the state check lets a particle stand half the skin
  // beyond a periodic face (it is wrapped at the next rebuild).
  void setPeriodic(const PeriodicBox<D>& box) {
    if (box.any()) ghosts_.emplace(box, listRadius_);
    else ghosts_.reset();
    for (int a = 0; a < D; ++a)
      if (box.periodic(a)) {
        check_.lo[a] -= skinDistance() / 2;
        check_.hi[a] += skinDistance() / 2;
      }
  }
  // The neighbour list's Verlet skin, a fraction of the support (see the top).
  Real neighbourSkin() const { return skin_; }
  // Pack the list, or walk the grid's cells at every visit, instead of
  // storing the list (neighbour_walk = packed | cells; neighbour_list.hpp):
  // the same pairs in the same order, so the same results, in less memory.
  // Both keep the positions of each build in xList. Call before
  // initialise() or resume().
  void setNeighbourStorage(NeighbourStorage storage) {
    neighbours_.setStorage(storage);
    if (neighbours_.visitsBuildPositions()) P_.allocate(P_.allocated() | fieldBit(kFieldXList));
  }
  // Run on the ranks of `comm` (R > 1; with one rank nothing changes): keep
  // this rank's share of the particles (every rank built the same), and
  // from the first sort on, own the particles of this rank's cells
  // (mpi/domain_decomposition.hpp: migrated at every sort) with the halo of
  // other ranks' particles within the list's radius, refreshed wherever the
  // ghosts are. The cells are shared out by particle count at the first
  // sort, then again, weighted by each particle's work (1 + its neighbours
  // at the last build), at any sort where the busiest rank's work exceeds
  // the mean by more than `tolerance` (rebalance_tolerance). The reductions
  // of a step (time step, state check, skin, energy, counts) span the ranks.
  // Call before initialise().
  void setDecomposition(const mpi::Communicator& comm, Real tolerance) {
    if (comm.size == 1) return;
    comm_ = comm;
    rebalanceTolerance_ = tolerance;
    decomposition_ = std::make_unique<mpi::DomainDecomposition<D>>(comm, listRadius_);
    decomposition_->keepShare(P_);
    P_.allocate(P_.allocated());  // give back the room the other ranks' particles took (the same fields)
    if (shifting_) shifting_->shifting.setCommunicator(comm);
    P_.setRemoteRefresh(&mpi::DomainDecomposition<D>::refreshRemote, decomposition_.get());
  }
  // Several ranks: the busiest rank's work over the mean in the current
  // list (1: even; 1 on one rank; collective), and how many times the
  // particles were shared out (the first sort's included).
  Real workImbalance() const { return decomposition_ && listBuilds_ > 0 ? measureWork() : 1; }
  long balances() const { return balances_; }
  const mpi::Communicator& communicator() const { return comm_; }
  // Particles of all ranks, fluid and walls (this rank's: particles().size()).
  std::size_t globalCount() const {
    return static_cast<std::size_t>(mpi::allSum(comm_, static_cast<std::int64_t>(P_.size())));
  }
  // Fluid particles of all ranks.
  std::size_t globalFluidCount() const {
    return static_cast<std::size_t>(mpi::allSum(comm_, static_cast<std::int64_t>(P_.fluidCount())));
  }
  // Halo particles on this rank (0 on one rank).
  std::size_t haloCount() const { return decomposition_ ? decomposition_->haloCount() : 0; }
  // Make the neighbour list fit the particles' current positions: with no
  // skin, sort and build it; with one, keep it if it still holds (the
  // ghosts refreshed), else rebuild. (Each evaluation calls it.)
  void prepareList() {
    if (skin_ == 0 || !neighbours_.bound() || !listStillHolds()) sort();
  }
  const Integrator<D>& integrator() const { return integrator_; }
  // Builds of the neighbour list so far (one per evaluation without a skin).
  long listBuilds() const { return listBuilds_; }
  PeriodicBox<D> periodicBox() const { return ghosts_ ? ghosts_->box() : PeriodicBox<D>{}; }
  // Particle shifting at the start of every step (particle_shifting.hpp;
  // a pass of the scene's, passes/step_start.hpp).
  void setShifting(ParticleShifting<D> shifting) {
    shifting.setCommunicator(comm_);
    shifting_.emplace(ShiftingPass<D>{std::move(shifting)});
  }
  // A paddle's prescribed motion, moved at the start of every step, after
  // the shifting (wall_motion.hpp; passes/step_start.hpp).
  void setWallMotion(const SinusoidalWallMotion<D>& motion) { wallMotion_.emplace(WallMotionPass<D>{motion}); }
  const std::optional<ShiftingPass<D>>& shiftingPass() const { return shifting_; }
  const std::optional<WallMotionPass<D>>& wallMotionPass() const { return wallMotion_; }
  // How often the guard put a fluid particle back (position updates it
  // changed), on all ranks (collective).
  long wallGuardActions() const { return static_cast<long>(mpi::allSum(comm_, static_cast<std::int64_t>(guardActions_))); }

  // Sort, optionally scale the masses to rho0, and evaluate the model at the
  // initial state. Returns a failure if the initial state is not finite.
  std::optional<StateFailure> initialise(bool scaleMass);

  // Continue from a snapshot of this scene taken after step `step` at time
  // `time`: its particles already carry the rates the integrator needs (a,
  // and drho, the XSPH correction), which are NOT evaluated again: leap-
  // frog's a was evaluated with the predicted velocity, so re-evaluating it
  // from the snapshot's v would not continue the run bit for bit. The
  // snapshot is in sorted order, so the sort must leave it as it is.
  // inSortOrder = false (a .pvtp's pieces, or several ranks, where each
  // rank's share and order are its own sort's): not checked; on several
  // ranks a particle's sums do not depend on the order (neighbour_list.hpp:
  // order by id), so the run goes on bit for bit on any number of ranks > 1.
  std::optional<StateFailure> resume(long step, Real time, bool inSortOrder = true);

  // One step; an adaptive dt is cut so that the step ends no later than
  // `landOn` (the next output time).
  std::optional<StateFailure> step(Real landOn = std::numeric_limits<Real>::infinity());

  Energy energy() const;

  const Particles<D>& particles() const { return P_; }
  Particles<D>& particles() { return P_; }
  const Model<D>& model() const { return model_; }
  const HashGrid<D>& grid() const { return grid_; }
  const NeighbourList<D>& neighbours() const { return neighbours_; }
  Real time() const { return time_; }
  long stepIndex() const { return step_; }
  // dt and criterion of the last step (before the first: the fixed dt).
  const TimeStepChoice& lastTimeStep() const { return lastStep_; }
  Real support() const { return model_.support(); }

  // Mean number of neighbours per particle (j != i inside the support;
  // with a skin the list holds more, which are not counted).
  Real meanNeighbours() const {
    const auto owned = mpi::allSum(comm_, static_cast<std::int64_t>(P_.size()));
    if (owned == 0) return 0;
    std::size_t pairs = neighbours_.pairCount();
    if (skin_ > 0) {
      pairs = 0;
      const Real support2 = model_.support() * model_.support();
      for (std::size_t i = 0; i < P_.size(); ++i)
        neighbours_.forEach(i, [&](std::uint32_t j) { pairs += (P_.x[i] - P_.x[j]).squaredNorm() < support2; });
    }
    return static_cast<Real>(mpi::allSum(comm_, static_cast<std::int64_t>(pairs))) / static_cast<Real>(owned);
  }

  // Where the bytes of the scene's arrays are, the ghosts' included (all
  // ranks': collective): the particles' fields, the rest of the particles'
  // arrays (the re-sort's scratch, which the pair loops borrow for their
  // per-particle p/rho^2 and m/rho, and the ghosts' bookkeeping), the grid
  // and the neighbour list.
  struct MemoryParts {
    std::size_t fields = 0, particleScratch = 0, grid = 0, list = 0;
    std::size_t total() const { return fields + particleScratch + grid + list; }
  };
  MemoryParts memoryParts() const {
    std::int64_t b[4] = {static_cast<std::int64_t>(P_.fieldBytes()),
                         static_cast<std::int64_t>(P_.bytesAllocated() - P_.fieldBytes()),
                         static_cast<std::int64_t>(grid_.bytesAllocated()),
                         static_cast<std::int64_t>(neighbours_.bytesAllocated())};
    mpi::allSum(comm_, b, 4);
    const auto u = [](std::int64_t v) { return static_cast<std::size_t>(v); };
    return {u(b[0]), u(b[1]), u(b[2]), u(b[3])};
  }
  // Every array of the scene, the ghosts' included [bytes] (collective).
  std::size_t bytesAllocated() const { return memoryParts().total(); }

 private:
  // A fixed dt keeps time = start + n dt, without the round-off of adding
  // dt n times; when 1/dt is a whole number (dt = 1e-4) it is computed as
  // n / (1/dt), the double nearest the decimal value, so that the time
  // stamps of the outputs read 0.06, not 0.060000000000000005.
  Real fixedStepTime(long n) const {
    const Real rate = 1 / timeStep_.dt;
    if (rate == std::round(rate) && rate < 9e15) return startTime_ + static_cast<Real>(n) / rate;
    return startTime_ + static_cast<Real>(n) * timeStep_.dt;
  }

  // The skin's length [m].
  Real skinDistance() const { return skin_ * model_.support(); }

  // Sort by cell, wrap and make the ghosts, build the grid and the list;
  // with a skin, remember the positions of the build. carryAll: every field
  // follows its particle, the rates too (always with a skin; resume(),
  // whose particles come with the rates of the snapshot).
  void sort(bool carryAll = false);

  // resume() with a skin: the list of the snapshot's build, at its positions.
  void rebuildRecordedList(bool checkOrder);
  // Several ranks: whether the work per rank is uneven enough to share the
  // particles out again (measured from the last build: work_).
  bool workIsUneven();
  // work_ from the current list; returns the busiest rank's sum over the
  // mean (collective).
  Real measureWork() const;
  // The sort of resume() must leave a one-rank snapshot in its order.
  void checkResumeOrder(const char* where) const;


  // Every owned particle within half the skin of its position at the last
  // build (the largest displacement, a max reduction), in one parallel
  // region with the refresh of the ghosts' advanced state from their
  // sources (the rest they hold from the last evaluation's syncs).
  bool listStillHolds() {
    const std::size_t n = P_.size();
    const Real half = skinDistance() / 2;
    const FieldSet advanced = advancedState(!P_.drho.empty());
    Real worst2 = 0;
#pragma omp parallel if (n >= kMinParallelSize)
    {
#pragma omp for schedule(static) reduction(max : worst2)
      for (std::size_t i = 0; i < n; ++i) worst2 = std::max(worst2, Vec<D>(P_.x[i] - P_.xList[i]).squaredNorm());
      P_.refreshGhostsInTeam(advanced);
    }
    if (!decomposition_) return worst2 <= half * half;
    // Every rank rebuilds when one must (the sort migrates: collective).
    const bool holds = mpi::allMax(comm_, worst2) <= half * half;
    if (holds) P_.refreshRemoteGhosts(advanced);
    return holds;
  }

  void evaluate();

  // A pass of the scene's own (step_start.hpp), then the ghosts of the
  // fields it declares it writes, as Model::sync does for the model's.
  template <class StepPass>
  void runPass(const StepPass& pass) {
    pass.run(P_, neighbours_, context_);
    P_.refreshGhosts(pass.fields(context_).writes);
  }

  // One loop over the particles: finish(i), the state check, and (adaptive
  // time steps only) the extremes the next time step needs. Returns the
  // first failure.
  template <class Finish>
  std::optional<StateFailure> finishStep(Finish&& finish) {
    return timeStep_.adaptive() ? finishStep<true>(finish) : finishStep<false>(finish);
  }

  template <bool kExtremes, class Finish>
  std::optional<StateFailure> finishStep(Finish& finish) {
    const std::size_t n = P_.size(), nFluid = P_.fluidCount();
    const bool density = !P_.drho.empty();
    std::size_t first = n;
    Real v2 = 0, a2 = 0, rhoMin = std::numeric_limits<Real>::infinity(), rhoMax = 0;
    // firstprivate: each thread checks with its own copy of the StateCheck,
    // whose bounds then stay in registers while the loop writes the
    // particles (callgrind, dam break: 0.9 M instructions less than with
    // the member itself).
    const StateCheck<D>& check = check_;
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize) firstprivate(check) \
    reduction(min : first, rhoMin) reduction(max : v2, a2, rhoMax)
    for (std::size_t i = 0; i < n; ++i) {
      finish(i);
      if (!check.ok(P_, i) && i < first) first = i;
      if constexpr (!kExtremes) continue;
      if (i < nFluid || density) {
        rhoMin = std::min(rhoMin, P_.rho[i]);
        rhoMax = std::max(rhoMax, P_.rho[i]);
      }
      if (i >= nFluid) continue;
      v2 = std::max(v2, P_.v[i].squaredNorm());
      a2 = std::max(a2, P_.a[i].squaredNorm());
    }
    if (decomposition_) {
      double highest[3] = {v2, a2, rhoMax};
      mpi::allMax(comm_, highest, 3);
      v2 = highest[0], a2 = highest[1], rhoMax = highest[2];
      rhoMin = mpi::allMin(comm_, rhoMin);
      // The failure of the lowest particle id on any rank, named on every rank.
      std::optional<StateFailure> mine;
      if (first < n) mine = check_.describe(P_, first);
      const auto firstFailure = mpi::firstOfRanks(comm_, mine ? static_cast<std::int64_t>(mine->id) : INT64_MAX);
      extremes_ = StateExtremes{v2, a2, rhoMin, rhoMax};
      if (firstFailure.rank < 0) return std::nullopt;
      StateFailure failure{mine ? mine->index : 0, firstFailure.key,
                           mpi::broadcast(comm_, mine ? mine->quantity : std::string(), firstFailure.rank),
                           mpi::broadcast(comm_, mine ? mine->detail : std::string(), firstFailure.rank)};
      failure.detail += " (on MPI rank " + std::to_string(firstFailure.rank) + ")";
      return failure;
    }
    extremes_ = StateExtremes{v2, a2, rhoMin, rhoMax};
    if (first == n) return std::nullopt;
    return check_.describe(P_, first);
  }

  Particles<D> P_;
  Model<D> model_;
  Integrator<D> integrator_;
  WallConstraint<D> walls_;  // reflecting clamp, wall guard or none
  StateCheck<D> check_;
  TimeStepControl timeStep_;
  std::optional<PeriodicGhosts<D>> ghosts_;
  mpi::Communicator comm_;  // the ranks of the run ({self, 0, 1}: one)
  std::unique_ptr<mpi::DomainDecomposition<D>> decomposition_;  // R > 1 only
  Real rebalanceTolerance_ = 0;  // set by setDecomposition (rebalance_tolerance)
  long balances_ = 0;
  mutable std::vector<Real> work_;  // scratch, per owned particle: 1 + its neighbours at the last build
  std::optional<ShiftingPass<D>> shifting_;
  std::optional<WallMotionPass<D>> wallMotion_;
  long guardActions_ = 0;
  FieldSet carriedMissing_ = 0;  // integrator state the particles came without
  bool listRecorded_ = false;     // the particles came with their list_build_position
  HashGrid<D> grid_;
  NeighbourList<D> neighbours_;
  Real skin_;        // Verlet skin, a fraction of the support
  Real listRadius_;  // support (1 + skin)
  long listBuilds_ = 0;
  Real startTime_;
  Real time_;
  long step_ = 0;
  StepContext context_;
  StateExtremes extremes_;
  TimeStepChoice lastStep_{timeStep_.dt, "fixed"};
};

// The member functions that do the work, compiled once for D = 2 and 3 in
// src/instantiate_scene.cpp; every other translation unit sees only their
// declarations (extern template below).
template <int D>
std::optional<StateFailure> Scene<D>::initialise(bool scaleMass) {
  sort();
  if (scaleMass) {
    scaleMassToRestDensity(P_, neighbours_, model_, comm_);
    P_.refreshGhosts();
  }
  // The first evaluation in the form of every step's: with an integrator
  // that takes the density rate apart (leap-frog, symplectic Euler) and a
  // model that has that pass, the density rate first, then the other
  // passes without it. So a run started from a snapshot (particle_file)
  // evaluates the forces at its first state as the run that wrote the
  // snapshot did at that step, by the same walk (the force walk's SIMD
  // rows take only this form: a restart of an inviscid run without XSPH
  // and with neighbour_skin = 0 is bit for bit, tests/test_restart.cpp).
  StepContext first{step_, time_, 0};
  first.densityRateApart =
      std::visit([](const auto& i) { return std::decay_t<decltype(i)>::kDensityRateApart; }, integrator_) &&
      !model_.densityRatePasses().empty();
  if (first.densityRateApart) model_.densityRate(P_, neighbours_);
  model_.evaluate(P_, neighbours_, first);
  return finishStep([](std::size_t) {});
}

template <int D>
std::optional<StateFailure> Scene<D>::resume(long step, Real time, bool inSortOrder) {
  step_ = step;
  time_ = time;
  if (step > 0)
    for (const FieldInfo& info : kFieldTable)
      if ((carriedMissing_ >> info.id) & 1u)
        throw std::runtime_error(std::string("the snapshot has no ") + info.vtkName + " array, which the integrator " +
                                 std::visit([](const auto& i) { return std::string(i.name); }, integrator_) +
                                 " carries from step to step (written with another integrator? resume with the "
                                 "run's own integrator)");
  const bool checkOrder = inSortOrder && !decomposition_;
  if (skin_ > 0) {
    rebuildRecordedList(checkOrder);
  } else {
    sort(/*carryAll=*/true);  // the snapshot's rates follow any move (none for a one-rank .vtp)
    if (checkOrder) checkResumeOrder("");
  }
  model_.refreshCspmMatrices(P_, neighbours_);
  return finishStep([](std::size_t) {});
}

template <int D>
std::optional<StateFailure> Scene<D>::step(Real landOn) {
  const TimeStepChoice choice = timeStep_.next(extremes_, model_, time_, landOn);
  lastStep_ = choice;
  context_ = StepContext{step_ + 1, time_ + choice.dt, choice.dt, time_};
  context_.shiftSumsGiven = model_.shiftSumsAtState();
  WallGuard<D>* guard = walls_.guard();
  if (guard && wallMotion_ && guard->paddle >= 0) {
    // The case places the paddle at t = 0, where sin = 0.
    guard->paddleOffset = wallMotion_->motion.displacement(time_ + choice.dt);
    guard->paddleVelocity = wallMotion_->motion.velocity(time_ + choice.dt);
  }
  long guarded = 0;
  auto constrain = [&](Particles<D>& P, std::size_t i) {
    if (walls_(P, i)) {
#pragma omp atomic
      ++guarded;
    }
  };
  std::optional<StateFailure> failure;
  if (shifting_) runPass(*shifting_);
  if (wallMotion_) runPass(*wallMotion_);
  if (auto* twoStep = std::get_if<TwoStepLeapFrog<D>>(&integrator_)) twoStep->step = step_;
  std::visit(
      [&](const auto& integrator) {
        context_.densityRateApart = std::decay_t<decltype(integrator)>::kDensityRateApart;
        integrator.advance(P_, choice.dt, [&] { evaluate(); }, constrain, [&] {
          if (skin_ == 0) P_.refreshGhosts(advancedState(!P_.drho.empty()));
          else prepareList();
          model_.densityRate(P_, neighbours_);
        });
        failure = finishStep([&](std::size_t i) { integrator.finish(P_, i, choice.dt); });
        P_.refreshGhosts(std::decay_t<decltype(integrator)>::finishes());
      },
      integrator_);
  guardActions_ += guarded;
  if (!failure) model_.afterStep(P_, neighbours_, context_);
  ++step_;
  // A step cut to land on end_time or an output time ends exactly there
  // (time + (t - time) can miss t by one ulp).
  const std::string_view cut = choice.criterion;
  if (!timeStep_.adaptive()) time_ = fixedStepTime(step_);
  else if (cut == "end") time_ = timeStep_.endTime;
  else if (cut == "output") time_ = landOn;
  else time_ += choice.dt;
  return failure;
}

template <int D>
Energy Scene<D>::energy() const {
  Energy e;
  for (std::size_t i = 0; i < P_.fluidCount(); ++i) e.kinetic += 0.5 * P_.m[i] * P_.v[i].squaredNorm();
  e.potential = model_.potentialEnergy(P_);
  if (decomposition_) {
    e.kinetic = mpi::allSum(comm_, e.kinetic);
    e.potential = mpi::allSum(comm_, e.potential);
  }
  return e;
}

template <int D>
void Scene<D>::sort(bool carryAll) {
  if (decomposition_) {
    const bool uneven = workIsUneven();
    // Wrapped first: a particle goes to the owner of its place in the box.
    if (ghosts_) ghosts_->wrap(P_);
    if (uneven) {
      decomposition_->balance(P_, listBuilds_ > 0 ? &work_ : nullptr);
      ++balances_;
    }
    decomposition_->migrate(P_);
  }
  sortByCell(P_, grid_, neighbours_, listRadius_, ghosts_ ? &*ghosts_ : nullptr, carryAll || skin_ > 0,
             decomposition_.get());
  ++listBuilds_;
  // (A cell walk had sortByCell copy them already, the ghosts' included.)
  if (skin_ > 0 && !neighbours_.visitsBuildPositions()) std::copy(P_.x.begin(), P_.x.begin() + static_cast<std::ptrdiff_t>(P_.size()), P_.xList.begin());
}

// Every sort on several ranks, before anything moves: the particles are
// still those of the last build, in its order, so the list gives each its
// work, 1 + its neighbours (the pairs the passes visit, plus what a
// particle costs alone). Two reductions of one number each.
template <int D>
bool Scene<D>::workIsUneven() {
  if (listBuilds_ == 0) return true;  // the first sort: shared out by count
  return measureWork() > 1 + rebalanceTolerance_;
}

template <int D>
Real Scene<D>::measureWork() const {
  const std::size_t n = P_.size();
  work_.resize(n);
  Real mine = 0;
  for (std::size_t i = 0; i < n; ++i) mine += work_[i] = Real(1) + static_cast<Real>(neighbours_.rowLength(i));
  const Real most = mpi::allMax(comm_, mine), sum = mpi::allSum(comm_, mine);
  return sum > 0 ? most * static_cast<Real>(comm_.size) / sum : 1;
}

template <int D>
void Scene<D>::checkResumeOrder(const char* where) const {
  const auto& order = grid_.order();
  for (std::size_t k = 0; k < P_.size(); ++k)
    if (order[k] != k)
      throw std::runtime_error(std::string("the snapshot is not in the order sph keeps its particles") + where +
                               " (written by another program?)");
}

// The snapshot holds the particles in the order of the last build and, in
// xList, where they were then: sorting them at those positions again must
// leave them in place (else the snapshot is not one sph wrote; checkOrder,
// one rank), and builds the same ghosts, grid and list. Then back to the
// current positions, found by id (on several ranks the sort migrates the
// particles). A snapshot without the record (all zero: written with no skin)
// gets a list at its current positions.
template <int D>
void Scene<D>::rebuildRecordedList(bool checkOrder) {
  const auto owned = static_cast<std::ptrdiff_t>(P_.size());
  if (!listRecorded_) {
    sort();
    return;
  }
  // Every rank's (id, position): the sort may give this rank others' particles.
  std::vector<mpi::ById<Vec<D>>> mine(P_.size());  // once, at the start
  for (std::size_t i = 0; i < P_.size(); ++i) mine[i] = {P_.id[i], P_.x[i]};
  const auto now = mpi::allGatherById(comm_, mine);
  std::copy(P_.xList.begin(), P_.xList.begin() + owned, P_.x.begin());
  sort();
  if (checkOrder) checkResumeOrder(" at its list_build_position");
  for (std::size_t i = 0; i < P_.size(); ++i) {
    const auto it = std::lower_bound(now.begin(), now.end(), P_.id[i],
                                     [](const auto& a, std::int64_t id) { return a.id < id; });
    if (it == now.end() || it->id != P_.id[i]) throw std::logic_error("Scene::rebuildRecordedList: a particle lost");
    P_.x[i] = it->value;
  }
  P_.refreshGhosts(fieldBit(kFieldX));
}

template <int D>
void Scene<D>::evaluate() {
  prepareList();
  model_.evaluate(P_, neighbours_, context_);
}

extern template class Scene<2>;
extern template class Scene<3>;

}  // namespace sph
