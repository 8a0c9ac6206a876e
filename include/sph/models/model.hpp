// Model<D>: a physics model as an explicit, ordered list of passes.
//
// evaluate() runs the passes in order on the sorted particles and their
// neighbour list, each with the step context (step index, time, dt);
// after every pass sits sync(), which refreshes the periodic ghosts of the
// fields the pass wrote from their sources (periodic_ghosts.hpp; each pass
// declares what it reads and writes, its fields(), fields.hpp), the hook
// where MPI halos will go too. A pass is a Pass<D> (pass.hpp: one of the
// value types of passes/, wrapped) and reports the term bits it ran, so a
// test can show that a switched-off term never runs. A second, usually empty, list runs after a step on the
// finished state (afterStep: the density re-initialisations), a third when
// the integrator asks for the density rate apart (densityRate: the
// density-rate pass, density_rate.hpp, with continuity density), and the
// passes add what the kernel corrections did to the model's counts. The
// presets that build the lists are declared in seed_wcsph.hpp and
// wcsph.hpp and compiled in src/seed_wcsph_model.cpp and
// src/wcsph_model.cpp: this file sees no pass type, term or pair loop.
//
// Besides its passes a model knows what the rest of the scene asks of it:
// its support radius and smoothing length, rest density, sound speed (for
// the CFL time step), kinematic viscosity (viscous time step), potential
// energy (energy.csv), and the particle fields it needs.
#pragma once

#include "sph/models/pass.hpp"
#include "sph/terms/equation_of_state_fwd.hpp"

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sph {

template <int D>
struct BodyForces;  // terms/body_forces.hpp

template <int D>
class Model {
 public:
  struct Info {
    std::string name;            // "seed_wcsph", "wcsph"
    Real support = 0;            // largest interaction distance
    Real smoothingLength = 0;    // h
    Real restDensity = 0;
    Real kinematicViscosity = 0; // for the viscous time-step limit (0: none)
    // Held by pointer, so that this header needs neither type: the EOS and
    // body-force headers rebuild the units that evaluate them, not every
    // unit that sees a model (src/model.cpp evaluates them here).
    std::shared_ptr<const EquationOfState> eos;  // required
    std::shared_ptr<const BodyForces<D>> bodies;  // none: no body forces
    FieldSet needs = 0;          // optional fields its passes use
    std::vector<std::string> termNames;
    // The velocity the forces see between drift and kick (leap-frog): false,
    // the estimate v^{n+1/2} + a^n dt/2 of v^{n+1}; true, the half-step
    // v^{n+1/2} itself, the only velocity the seed document's leap-frog
    // holds (seed_wcsph; docs/methods/seed-model.md).
    bool forcesSeeHalfStepVelocity = false;
    // Its evaluation leaves particle shifting's sums in the particles
    // (shiftSum, shiftGrad: terms/shifting_sums.hpp), for the next step's shift.
    bool shiftSums = false;
  };

  Model(Info info, PassList<D> passes, PassList<D> afterStep = {}, PassList<D> densityRate = {})
      : info_(std::move(info)),
        passes_(std::move(passes)),
        afterStep_(std::move(afterStep)),
        densityRate_(std::move(densityRate)) {
    if (!info_.eos) throw std::invalid_argument("Model: a model needs an equation of state (Info::eos)");
  }

  // rho (or its rate), p, a and the other rates at the current state. The
  // neighbour list must have been built on these positions.
  void evaluate(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const {
    executed_ = runPasses(passes_, P, neighbours, ctx) | (ctx.densityRateApart ? densityRateBits_ : 0u);
    executedAfterStep_ = 0;
    evaluated_ = true;
  }

  // d rho/dt alone, at the particles' x and v with the given neighbour list
  // (the density-rate list: the continuity and diffusion terms in a loop of
  // their own, synced as every pass): for the integrators that advance rho
  // like a position. Nothing without continuity density.
  void densityRate(Particles<D>& P, const NeighbourList<D>& neighbours) const {
    densityRateBits_ = densityRate_.empty() ? 0u : runPasses(densityRate_, P, neighbours, StepContext{});
  }

  // After step ctx.step has finished (the state check passed): the passes
  // that act on the finished state, with the neighbour list of the step's
  // last evaluation.
  void afterStep(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const {
    if (afterStep_.empty()) return;
    executedAfterStep_ = runPasses(afterStep_, P, neighbours, ctx);
    // A re-initialised density changes the volumes of the CSPM matrices the
    // next step's density-rate pass reads: refresh them, as a resume does.
    if (executedAfterStep_ != 0 && ctx.densityRateApart) refreshCspmMatrices(P, neighbours);
  }

  // The CSPM matrices L_i at the current state, for the density-rate pass
  // that reads them before the step's first evaluation: after a resume (a
  // snapshot does not hold them) and after a density re-initialisation.
  void refreshCspmMatrices(Particles<D>& P, const NeighbourList<D>& neighbours) const {
    runRole(PassRole::kCspmMatrices, P, neighbours);
  }

  // Density alone (the summation-density pass), for the seed's mass scaling.
  void computeDensity(Particles<D>& P, const NeighbourList<D>& neighbours) const {
    runRole(PassRole::kSummationDensity, P, neighbours);
  }

  const std::string& name() const { return info_.name; }
  Real support() const { return info_.support; }
  Real smoothingLength() const { return info_.smoothingLength; }
  Real restDensity() const { return info_.restDensity; }
  Real kinematicViscosity() const { return info_.kinematicViscosity; }
  const EquationOfState& eos() const { return *info_.eos; }
  FieldSet needs() const { return info_.needs; }
  const std::vector<std::string>& termNames() const { return info_.termNames; }
  bool forcesSeeHalfStepVelocity() const { return info_.forcesSeeHalfStepVelocity; }
  // Whether the particles hold particle shifting's sums at their state: the
  // model's last evaluation left them and no re-initialisation ran after it
  // (none before the first evaluation: a resumed scene's first shift walks).
  bool shiftSumsAtState() const { return info_.shiftSums && evaluated_ && executedAfterStep_ == 0; }
  const PassList<D>& passes() const { return passes_; }
  const PassList<D>& afterStepPasses() const { return afterStep_; }
  const PassList<D>& densityRatePasses() const { return densityRate_; }
  // The term bits the last evaluate() and the afterStep() after it ran (term_bits.hpp).
  unsigned executedTerms() const { return executed_ | executedAfterStep_; }
  // What the kernel corrections did so far (step_context.hpp).
  const CorrectionCounts& correctionCounts() const { return counts_; }

  // The potential energy of the conservative body forces (gravity, the
  // star's attraction), for energy.csv.
  Real potentialEnergy(const Particles<D>& P) const;

  // The regime check's references (regime_check.hpp): the EOS's sound speed
  // at rest density (the seed's p = k (rho - rho0): sqrt(k)), none for the
  // polytropic EOS of the toy stars; and the rest density of the density
  // window, for the Tait EOS of the water cases only (a linear EOS and the
  // seed's set a stiffness k and are compressible by design: the seed dam
  // break reaches 1.2 rho0).
  Real regimeSoundSpeed() const;
  Real regimeDensity() const;

  // Largest sound speed over the particles (for the CFL time step). Every
  // EOS here has c monotonic in rho, so it is c at the lowest or the highest
  // density.
  Real maxSoundSpeed(Real rhoMin, Real rhoMax) const;

 private:
  // After a pass: the ghosts take from their sources the fields the pass
  // wrote (its declared writes; the others they already hold, refreshed
  // before the first pass by the scene). Later, the MPI halos too.
  void sync(Particles<D>& P, FieldSet written) const { P.refreshGhosts(written); }

  unsigned runPasses(const PassList<D>& passes, Particles<D>& P, const NeighbourList<D>& neighbours,
                     StepContext ctx) const {
    ctx.counts = &counts_;
    unsigned ran = 0;
    for (const auto& pass : passes) {
      ran |= pass->run(P, neighbours, ctx);
      sync(P, pass->fields(ctx).writes);
    }
    return ran;
  }

  // The evaluation's passes of one role, run alone outside an evaluation.
  void runRole(PassRole role, Particles<D>& P, const NeighbourList<D>& neighbours) const {
    for (const auto& pass : passes_)
      if (pass->role() == role) pass->run(P, neighbours, StepContext{});
  }

  Info info_;
  PassList<D> passes_;
  PassList<D> afterStep_;
  PassList<D> densityRate_;
  mutable unsigned executed_ = 0, executedAfterStep_ = 0, densityRateBits_ = 0;
  mutable bool evaluated_ = false;
  mutable CorrectionCounts counts_;
};

extern template class Model<2>;
extern template class Model<3>;

}  // namespace sph
